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
import unittest

import rospy
import rostest
from dynamic_reconfigure.msg import Config
from std_msgs.msg import UInt8

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from fake_reconfigure import FakeServer  # noqa: E402
from grid_watch import ErrorLog, Latest, publish_row_mask  # noqa: E402
from robot_pose import RobotPose  # noqa: E402

# Mask cells of 1 m along x (robot at y = 0.5): 0 | 1 slow | 2 crowded | 0 | 3 too_fast | 0
MASK = [0, 1, 2, 0, 3, 0]


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
        cls.planner = FakeServer("fake_planner")
        cls.state = Latest("/zone_state", UInt8)
        cls.inflation = Latest("/costmap_node/inflation_layer/parameter_updates", Config)
        cls.mask_pub = publish_row_mask("/zone_mask", MASK)
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
