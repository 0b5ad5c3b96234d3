#!/usr/bin/env python3
"""ZoneParameterFilter's setpoints against hostile dynamic_reconfigure servers. /stuck_server accepts
the call and never answers; /vanishing_server exits in the middle of the call; /good_server answers.
The set names the stuck server first. The costmap (started here, as /costmap_stuck) must keep
updating while a call hangs, report the stuck and the vanished server by their stable keys, still
apply /good_server's values (every new set too, only the newest mattering), and exit promptly on
SIGINT while a call hangs."""
import os
import signal
import subprocess
import sys
import time
import unittest

import roslib.packages
import rospy
import rostest
from std_msgs.msg import UInt8

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
sys.path.insert(0, HERE)
from fake_reconfigure import FakeServer  # noqa: E402
from grid_watch import CycleWatcher, ErrorLog, Latest, publish_row_mask  # noqa: E402
from robot_pose import RobotPose  # noqa: E402

NODE = "/costmap_stuck"
KEY = NODE + "/zone_filter/setpoint/"
# Mask cells of 1 m along x (robot at y = 0.5): 0 | 1 slow | 0
MASK = [0, 1, 0]


class SetpointStuckTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_setpoint_stuck")
        cls.log = ErrorLog(NODE)
        cls.stuck = FakeServer("stuck_server", answer=False)
        cls.good = FakeServer("good_server")
        cls.vanishing = subprocess.Popen([sys.executable, os.path.join(HERE, "vanishing_server.py")])
        rospy.wait_for_service("/vanishing_server/set_parameters", timeout=60)
        cls.state = Latest("/stuck_zone_state", UInt8)
        cls.cycles = CycleWatcher(NODE)
        cls.mask_pub = publish_row_mask("/stuck_zone_mask", MASK)
        cls.robot = RobotPose(NODE, 0.5, 0.5)
        node = roslib.packages.find_node("costmap_layers", "costmap_node")
        cls.node = subprocess.Popen([node[0], "__name:=costmap_stuck"])

    @classmethod
    def tearDownClass(cls):
        cls.stuck.release()
        for proc in (cls.node, cls.vanishing):
            if proc.poll() is None:
                proc.kill()
                proc.wait()

    def go(self, x, state):
        self.robot.place(x, 0.5)
        self.assertTrue(self.state.wait(lambda m: m.data == state, 20.0),
                        "no state %d at x = %.1f" % (state, x))

    def test_stuck_and_vanishing_servers(self):
        # The first set (nominal defaults): the call to /stuck_server hangs ...
        self.assertTrue(self.stuck.wait(lambda s: len(s.received) >= 1, 60.0), "/stuck_server was never called")
        # ... while the costmap keeps updating and publishing.
        self.assertTrue(self.cycles.wait(5, 30.0), "the costmap stopped updating while a call hung")
        # The hanging call is reported by its key, and abandoned: /good_server, named after it, gets its
        # value; /vanishing_server's exit in the middle of its call is reported by its key.
        self.assertTrue(self.log.wait(KEY + "stuck_server/max_vel_x", ["/stuck_server/set_parameters"], 30.0),
                        "the server that never answers was not reported: %s" % self.log.lines)
        self.assertTrue(self.log.wait(KEY + "vanishing_server/max_vel_x", ["/vanishing_server/set_parameters"],
                                         30.0), "the server that vanished mid-call was not reported: %s" % self.log.lines)
        self.assertEqual(self.vanishing.wait(timeout=30), 0)
        self.assertTrue(self.good.wait(lambda s: s.value == 0.8, 30.0),
                        "/good_server never got max_vel_x 0.8 behind the stuck server: %s" % self.good.received)

        # Zone changes faster than the stuck server's timeouts: only the newest set matters, and
        # /good_server ends with the newest value.
        sets = 1
        for x, state in [(1.5, 1), (0.5, 0), (1.5, 1), (0.5, 0), (1.5, 1)]:
            self.go(x, state)
            sets += 1
        self.assertTrue(self.good.wait(lambda s: s.value == 0.3, 60.0),
                        "/good_server never got the newest max_vel_x 0.3: %s" % self.good.received)
        self.assertLessEqual(len(self.good.received), sets, "more calls than sets: %s" % self.good.received)
        self.assertTrue(self.cycles.wait(5, 30.0), "the costmap stopped updating")

        # SIGINT while a call to /stuck_server hangs: the node exits promptly (roslaunch would wait
        # 15 s before escalating to SIGTERM).
        calls = len(self.stuck.received)
        self.go(0.5, 0)
        self.assertTrue(self.stuck.wait(lambda s: len(s.received) > calls, 30.0), "/stuck_server not called again")
        start = time.monotonic()
        self.node.send_signal(signal.SIGINT)
        try:
            rc = self.node.wait(timeout=10.0)
        except subprocess.TimeoutExpired:
            self.fail("costmap_node did not exit within 10 s of SIGINT while a call hung")
        took = time.monotonic() - start
        print("costmap_node exited %.2f s after SIGINT" % took)
        self.assertEqual(rc, 0)
        self.assertLess(took, 5.0, "costmap_node took %.1f s to exit on SIGINT" % took)


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "setpoint_stuck", SetpointStuckTest)
