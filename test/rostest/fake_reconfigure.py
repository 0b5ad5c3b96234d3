"""A dynamic_reconfigure server hosted by a rostest (the Reconfigure service and a latched
ConfigDescription, as a generated server has), with one double parameter max_vel_x in [0, 2]
(default 1.5); shared by the zone_params and setpoint_stuck rostests."""
import threading

import rospy
from dynamic_reconfigure.msg import (Config, ConfigDescription, DoubleParameter, Group, GroupState,
                                     ParamDescription)
from dynamic_reconfigure.srv import Reconfigure, ReconfigureResponse


def description():
    desc = ConfigDescription()
    group = Group(name="Default", type="", parameters=[], parent=0, id=0)
    group.parameters.append(ParamDescription(name="max_vel_x", type="double", level=0,
                                             description="max_vel_x", edit_method=""))
    desc.groups.append(group)
    desc.min = Config(doubles=[DoubleParameter("max_vel_x", 0.0)])
    desc.max = Config(doubles=[DoubleParameter("max_vel_x", 2.0)])
    desc.dflt = Config(doubles=[DoubleParameter("max_vel_x", 1.5)])
    return desc


class FakeServer:
    """The server at /<name>. It answers as a generated server does (unknown names are not in the
    answer, out-of-range values are clamped); with answer=False its handler never returns (until
    release()) and keeps the value it had."""

    def __init__(self, name, answer=True):
        self.cond = threading.Condition()
        self.answer = answer
        self.released = False
        self.value = 1.5  # before anyone sets it
        self.received = []  # every max_vel_x value a request carried, in order
        self.pub = rospy.Publisher("/%s/parameter_descriptions" % name, ConfigDescription, queue_size=1,
                                   latch=True)
        self.pub.publish(description())
        self.srv = rospy.Service("/%s/set_parameters" % name, Reconfigure, self.on_set)

    def on_set(self, req):
        with self.cond:
            for p in req.config.doubles:
                if p.name == "max_vel_x":
                    self.received.append(p.value)
                    if self.answer:
                        self.value = min(2.0, max(0.0, p.value))
            self.cond.notify_all()
            while not self.answer and not self.released:
                self.cond.wait()
            answer = Config(doubles=[DoubleParameter("max_vel_x", self.value)],
                            groups=[GroupState(name="Default", state=True, id=0, parent=0)])
        return ReconfigureResponse(config=answer)

    def wait(self, predicate, timeout):
        """Waits until predicate(self) holds (on requests, not on a fixed sleep); returns whether it does."""
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        with self.cond:
            while not predicate(self) and not rospy.is_shutdown() and rospy.Time.now() < deadline:
                self.cond.wait(0.2)
            return predicate(self)

    def wait_value(self, v, timeout):
        """Waits until the server holds max_vel_x = v; returns whether it does."""
        return self.wait(lambda s: abs(s.value - v) <= 1e-9, timeout)

    def release(self):
        with self.cond:
            self.released = True
            self.cond.notify_all()
