#!/usr/bin/env python3
"""ZoneParameterFilter through real topics and services: the robot (tf published here) drives over a
mask (published here) with zones 1 (slow), 2 (crowded) and 3 (too_fast); /fake_planner, a
dynamic_reconfigure server hosted here (the Reconfigure service and a latched ConfigDescription, as
a generated server has), sees max_vel_x set on entering and restored on leaving; the costmap's own
InflationLayer (its real dynamic_reconfigure server) gets inflation_radius 1.0 in the crowded zone
and 0.55 again outside; a value out of /fake_planner's range is refused, reported by its stable key,
and never sent; a node that does not exist and a parameter the server does not have are reported."""
import os
import sys
import threading
import unittest

import rospy
import rostest
from dynamic_reconfigure.msg import (Config, ConfigDescription, DoubleParameter, Group, GroupState,
                                     ParamDescription)
from dynamic_reconfigure.srv import Reconfigure, ReconfigureResponse
from nav_msgs.msg import OccupancyGrid
from std_msgs.msg import UInt8

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from grid_watch import ErrorLog  # noqa: E402
from robot_pose import RobotPose  # noqa: E402

# Mask cells of 1 m along x (robot at y = 0.5): 0 | 1 slow | 2 crowded | 0 | 3 too_fast | 0
MASK = [0, 1, 2, 0, 3, 0]


class FakePlanner:
    """A dynamic_reconfigure server with one double parameter max_vel_x in [0, 2], as a generated
    server answers: unknown names are not in the answer, out-of-range values are clamped."""

    def __init__(self):
        self.cond = threading.Condition()
        self.value = 1.5         # before anyone sets it
        self.received = []       # every max_vel_x value a request carried
        self.requests = 0
        desc = ConfigDescription()
        group = Group(name="Default", type="", parameters=[], parent=0, id=0)
        group.parameters.append(ParamDescription(name="max_vel_x", type="double", level=0,
                                                 description="max_vel_x", edit_method=""))
        desc.groups.append(group)
        desc.min = Config(doubles=[DoubleParameter("max_vel_x", 0.0)])
        desc.max = Config(doubles=[DoubleParameter("max_vel_x", 2.0)])
        desc.dflt = Config(doubles=[DoubleParameter("max_vel_x", 1.5)])
        self.desc_pub = rospy.Publisher("/fake_planner/parameter_descriptions", ConfigDescription,
                                        queue_size=1, latch=True)
        self.desc_pub.publish(desc)
        self.srv = rospy.Service("/fake_planner/set_parameters", Reconfigure, self.on_set)

    def on_set(self, req):
        with self.cond:
            self.requests += 1
            for p in req.config.doubles:
                if p.name == "max_vel_x":
                    self.received.append(p.value)
                    self.value = min(2.0, max(0.0, p.value))
            self.cond.notify_all()
            answer = Config(doubles=[DoubleParameter("max_vel_x", self.value)],
                            groups=[GroupState(name="Default", state=True, id=0, parent=0)])
        return ReconfigureResponse(config=answer)

    def wait_value(self, v, timeout):
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        with self.cond:
            while abs(self.value - v) > 1e-9 and not rospy.is_shutdown() and rospy.Time.now() < deadline:
                self.cond.wait(0.2)
            return abs(self.value - v) <= 1e-9


class Latest:
    """The latest message on a topic, with a wait on a condition."""

    def __init__(self, topic, cls):
        self.cond = threading.Condition()
        self.msg = None
        rospy.Subscriber(topic, cls, self.on_msg)

    def on_msg(self, m):
        with self.cond:
            self.msg = m
            self.cond.notify_all()

    def wait(self, predicate, timeout):
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        with self.cond:
            while not (self.msg is not None and predicate(self.msg)) and not rospy.is_shutdown() \
                    and rospy.Time.now() < deadline:
                self.cond.wait(0.2)
            return self.msg is not None and predicate(self.msg)


def radius_of(config):
    for p in config.doubles:
        if p.name == "inflation_radius":
            return p.value
    return None


class ZoneParamsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_zone_params")
        cls.log = ErrorLog("/costmap_node")
        cls.planner = FakePlanner()
        cls.state = Latest("/zone_state", UInt8)
        cls.inflation = Latest("/costmap_node/inflation_layer/parameter_updates", Config)
        mask = OccupancyGrid()
        mask.header.frame_id = "map"
        mask.info.resolution = 1.0
        mask.info.width = len(MASK)
        mask.info.height = 1
        mask.info.origin.orientation.w = 1.0
        mask.data = MASK
        cls.mask_pub = rospy.Publisher("/zone_mask", OccupancyGrid, queue_size=1, latch=True)
        cls.mask_pub.publish(mask)
        cls.robot = RobotPose("/costmap_node", 0.5, 0.5)

    def go(self, x, state):
        self.robot.place(x, 0.5)
        self.assertTrue(self.state.wait(lambda m: m.data == state, 20.0),
                        "no state %d at x = %.1f (last: %s)" % (state, x, self.state.msg))

    def test_setpoints_applied_restored_and_refused(self):
        # Outside every zone: the nominal defaults, on both servers.
        self.go(0.5, 0)
        self.assertTrue(self.planner.wait_value(0.8, 30.0), "max_vel_x never set to its default 0.8")
        self.assertTrue(self.inflation.wait(lambda c: abs(radius_of(c) - 0.55) < 1e-9, 30.0))
        # slow: max_vel_x 0.3 on entering ...
        self.go(1.5, 1)
        self.assertTrue(self.planner.wait_value(0.3, 20.0), "max_vel_x not 0.3 in the slow zone")
        # ... crowded: the costmap's own inflation layer takes 1.0, and max_vel_x is restored to 0.8.
        self.go(2.5, 2)
        self.assertTrue(self.inflation.wait(lambda c: abs(radius_of(c) - 1.0) < 1e-9, 20.0),
                        "inflation_radius not 1.0 in the crowded zone: %s" % self.inflation.msg)
        self.assertTrue(self.planner.wait_value(0.8, 20.0), "max_vel_x not restored on leaving the slow zone")
        # Out of every zone: inflation_radius back to 0.55.
        self.go(3.5, 0)
        self.assertTrue(self.inflation.wait(lambda c: abs(radius_of(c) - 0.55) < 1e-9, 20.0),
                        "inflation_radius not restored on leaving the crowded zone")
        # too_fast: 5.0 is outside /fake_planner's [0, 2]: refused, reported by key, never sent.
        self.go(4.5, 3)
        key = "/costmap_node/zone_filter/setpoint/fake_planner/max_vel_x"
        self.assertTrue(self.log.wait(key, ["5"], 20.0), "the refused max_vel_x 5.0 was not reported")
        self.go(5.5, 0)
        self.assertTrue(self.planner.wait_value(0.8, 20.0))
        self.assertNotIn(5.0, self.planner.received)
        self.assertAlmostEqual(self.planner.value, 0.8)

    def test_missing_node_and_unknown_parameter_are_reported(self):
        self.assertTrue(self.log.wait("/costmap_node/ghost_filter/setpoint/no_such_node/speed",
                                         ["/no_such_node"], 60.0),
                        "a setpoint for a node that does not exist was not reported")
        self.assertTrue(self.log.wait("/costmap_node/ghost_filter/setpoint/fake_planner/no_such_param",
                                         ["no_such_param"], 60.0),
                        "a setpoint for a parameter the server does not have was not reported")


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "zone_params", ZoneParamsTest)
