#!/usr/bin/env python3
"""costmap_node's AsymmetricInflationLayer (nav2_costmap_2d:: name) on a plan received as nav_msgs/Path.
Lethal cells N (20, 24) and S (20, 16), 0.45 m north and 0.35 m south of the plan y = 2.0; the costs are
read 0.4 m beyond each: floor(252 exp(-f (0.4 - 0.1))) is 186 for factor 1 (the disfavoured left) and 12
for factor 10. Without a plan both are 12; a plan driven the other way swaps them; bad plans (a NaN
position, no poses) are refused and the costs stay."""
import os
import sys
import unittest

import rospy
import rostest
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import OccupancyGrid, Path

from costmap_layers.srv import GetCosts

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from grid_watch import CycleWatcher  # noqa: E402

NS = "/costmap_node/"
NORTH, SOUTH = (2.05, 2.85), (2.05, 1.25)  # cells (20, 28) and (20, 12)


def path(xs, y=2.0):
    p = Path()
    p.header.frame_id = "map"
    for x in xs:
        s = PoseStamped()
        s.header.frame_id = "map"
        s.pose.position.x, s.pose.position.y = x, y
        s.pose.orientation.w = 1.0
        p.poses.append(s)
    return p


class AsymmetricInflationTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_asymmetric_inflation")
        cls.cycles = CycleWatcher("/costmap_node")
        grid = OccupancyGrid()
        grid.header.frame_id = "map"
        grid.info.resolution = 0.1
        grid.info.width = grid.info.height = 40
        grid.info.origin.orientation.w = 1.0
        data = [0] * 1600
        data[24 * 40 + 20] = 100
        data[16 * 40 + 20] = 100
        grid.data = data
        cls.map_pub = rospy.Publisher("/asym_map", OccupancyGrid, queue_size=1, latch=True)
        cls.map_pub.publish(grid)
        cls.plan_pub = rospy.Publisher("/asym_plan", Path, queue_size=5)
        rospy.wait_for_service(NS + "get_cost", 30.0)
        cls.get_cost = rospy.ServiceProxy(NS + "get_cost", GetCosts)

    def costs(self):
        poses = []
        for x, y in (NORTH, SOUTH):
            p = PoseStamped()
            p.header.frame_id = "map"
            p.pose.position.x, p.pose.position.y = x, y
            p.pose.orientation.w = 1.0
            poses.append(p)
        return list(self.get_cost(False, poses).costs)

    def wait_costs(self, expected, publish=None, timeout=20.0):
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        seen = None
        while not rospy.is_shutdown() and rospy.Time.now() < deadline:
            if publish is not None:
                self.plan_pub.publish(publish)
            self.cycles.wait(1, 2.0)
            seen = self.costs()
            if seen == expected:
                return
        self.fail("costs north/south: expected %s, saw %s" % (expected, seen))

    def test_plan_sides(self):
        # No plan yet: symmetric with the larger factor.
        self.wait_costs([12.0, 12.0])
        # Along +x: north is left (disfavoured, factor 1).
        forward = path([0.5, 1.5, 2.5, 3.5])
        self.wait_costs([186.0, 12.0], publish=forward)
        # Bad plans are refused: the costs stay.
        bad = path([0.5, 1.5, 2.5, 3.5])
        bad.poses[1].pose.position.x = float("nan")
        for plan in (bad, path([])):
            for _ in range(3):
                self.plan_pub.publish(plan)
                self.assertTrue(self.cycles.wait(2))
            self.assertEqual(self.costs(), [186.0, 12.0])
        # Driven the other way: south is left now.
        self.wait_costs([12.0, 186.0], publish=path([3.5, 2.5, 1.5, 0.5]))


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "asymmetric_inflation", AsymmetricInflationTest)
