#!/usr/bin/env python3
"""KeepoutFilter's escape mode through real topics: a robot placed half inside a lethal keepout zone
gets a ramp of passable costs that fall toward the way out (and no inflation around the zone while
it escapes); moved out, the zone is lethal again behind it, inflated as a wall."""
import math
import os
import sys
import unittest

import rospy
import rostest
from nav_msgs.msg import OccupancyGrid

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from grid_watch import GridWatcher, translate  # noqa: E402
from robot_pose import RobotPose  # noqa: E402

RES = 0.05
FOOTPRINT_CIRCUMSCRIBED = 0.3 * math.sqrt(2.0)  # the 0.6 m square


def make_mask():
    """8 m x 4 m at 0.05 m: lethal keepout (100) for x >= 4 m, free elsewhere."""
    m = OccupancyGrid()
    m.header.frame_id = "map"
    m.header.stamp = rospy.Time.now()
    m.info.resolution = RES
    m.info.width, m.info.height = 160, 80
    m.info.origin.orientation.w = 1.0
    m.data = ([0] * 80 + [100] * 80) * 80
    return m


def ramp(k):
    """The escape cost of the k-th column into the zone (depth k cells), by the documented rule."""
    depth = k * RES
    return 252 if depth >= FOOTPRINT_CIRCUMSCRIBED else max(1, math.ceil(252 * depth / FOOTPRINT_CIRCUMSCRIBED))


class KeepoutEscapeTest(unittest.TestCase):
    def test_escape_and_lethal_again(self):
        rospy.init_node("test_keepout_escape")
        grid = GridWatcher("/costmap_node")
        robot = RobotPose("/costmap_node", 2.0, 2.0)
        pub = rospy.Publisher("/keepout_mask", OccupancyGrid, queue_size=1, latch=True)
        pub.publish(make_mask())
        row_y = 2.0

        def column(k):  # centre x of the k-th column into the zone (k = 1: the first)
            return 4.0 + (k - 0.5) * RES

        # Clear of the zone: lethal, and inflated like a wall (inscribed 253 -> 99 right outside it).
        self.assertTrue(robot.move_to(2.0, 2.0))
        self.assertTrue(grid.wait_until(lambda g: g.at(column(1), row_y) == 100 and g.at(3.975, row_y) == 99, 20.0),
                        "the zone is not a lethal, inflated wall while the robot is clear of it")

        # Half inside: centre on the zone's edge.
        self.assertTrue(robot.move_to(4.0, 2.0))
        expected = [translate(ramp(k)) for k in range(1, 13)]
        self.assertTrue(grid.wait_until(lambda g: [g.at(column(k), row_y) for k in range(1, 13)] == expected, 20.0),
                        "no escape ramp: %s, expected %s" % ([grid.at(column(k), row_y) for k in range(1, 13)],
                                                              expected))
        snap = grid.snapshot()
        width = grid.width
        j = int(row_y / RES)
        row = snap[j * width:(j + 1) * width]
        zone = row[80:]
        self.assertTrue(all(1 <= v <= 98 for v in zone), "a zone cell is not passable: %s" % zone)
        self.assertEqual(zone, sorted(zone), "the costs do not fall toward the way out (smaller x)")
        # No inflation around the zone while the robot escapes: outside it everything is free.
        self.assertEqual(row[:80], [0] * 80)

        # Footprint clear (to 3.3 m), the centre 0.7 m from the zone: lethal again behind it.
        self.assertTrue(robot.move_to(3.0, 2.0))
        self.assertTrue(grid.wait_until(lambda g: g.at(column(1), row_y) == 100 and g.at(3.975, row_y) == 99, 20.0),
                        "the zone is not lethal again once the robot is out")
        self.assertEqual(grid.at(3.0, row_y), 0, "the robot's cell is inflated: it would be stuck")


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "keepout_escape", KeepoutEscapeTest)
