#!/usr/bin/env python3
"""The bridged AsymmetricInflationLayer inside a real move_base (asymmetric_move_base.test, issue 37).

The map is a corridor 6 m long: walls up to y = 0.5 m and from y = 1.55 m, free between, at 0.05 m.
The robot stands at (0.525, 1.025), on the corridor's centre line. Probe cells 0.25 m (5 cells) from
each wall, at y = 0.725 (south) and y = 1.325 (north): their cost is costmap_2d's
floor(252 exp(-f (0.25 - r))) with r the inscribed radius of the 16-gon costmap_2d makes of
robot_radius 0.1 (0.1 cos(pi / 16) = 0.098 m): 117 for f = 5 and 216 for f = 1 (published as 45 and
84). Each wall's cells are 0.55 m from the centre line, within the layer's inflation_radius 0.6, so
they take the side of the plan navfn makes along it:
- no plan yet: symmetric with the larger factor (5) on both sides;
- navfn's plan east (left = north): the north wall with factor 1, the south one with 5;
- a plan west: the sides swap (navfn, now planning on the asymmetric costs, keeps south of the centre
  line: the south wall is nearer, the north one may be beyond inflation_radius and take factor 5 either
  way);
- a plan ending 0.2 m from the robot (within goal_distance_threshold 0.5): symmetric again.
Each case waits on costmap arrivals with a deadline, never on a fixed sleep."""
import math
import os
import sys
import unittest

import rospy
import rostest
from nav_msgs.msg import OccupancyGrid, Path
from nav_msgs.srv import GetPlan

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                "rostest"))
from grid_watch import GridWatcher, Latest, translate  # noqa: E402
from grid_watch import map_pose as pose  # noqa: E402
from grid_watch import occupancy_grid  # noqa: E402

WIDTH, HEIGHT, RES = 120, 41, 0.05
SOUTH_WALL_ROWS, NORTH_WALL_FROM = 10, 31  # rows 0..9 and 31..40 are walls
ROBOT = (0.525, 1.025)
SOUTH_Y, NORTH_Y = 0.725, 1.325  # probe rows 14 and 26: 5 cells from rows 9 and 31
PROBE_XS = [0.525 + 0.5 * k for k in range(11)]  # along the whole corridor


def cost(factor, distance=0.25, inscribed=0.1 * math.cos(math.pi / 16)):
    """costmap_2d's inflation cost at `distance` [m] from an obstacle cell, as published."""
    return translate(int(252 * math.exp(-factor * (distance - inscribed))))


SLOW, FAST = cost(1.0), cost(5.0)  # 84 and 45


class AsymmetricInMoveBaseTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_asymmetric_move_base")
        data = [100 if j < SOUTH_WALL_ROWS or j >= NORTH_WALL_FROM else 0
                for j in range(HEIGHT) for _ in range(WIDTH)]
        cls.map_pub = rospy.Publisher("/map", OccupancyGrid, queue_size=1, latch=True)
        cls.map_pub.publish(occupancy_grid(WIDTH, HEIGHT, RES, data, stamp=rospy.Time()))
        cls.grid = GridWatcher("/move_base/global_costmap")
        cls.navfn_plan = Latest("/move_base/NavfnROS/plan", Path)
        rospy.wait_for_service("/move_base/make_plan", timeout=90.0)
        cls.make_plan = rospy.ServiceProxy("/move_base/make_plan", GetPlan)

    @staticmethod
    def sides(g, xs):
        """(south, north) probe values at each of xs."""
        return [(g.at(x, SOUTH_Y), g.at(x, NORTH_Y)) for x in xs]

    def expect(self, south, north, why, along=(0.0, 6.0)):
        """The probes at every PROBE_XS within `along` (the stretch the plan covers: beyond its ends the
        walls are farther than inflation_radius from it and have no side) read (south, north)."""
        xs = [x for x in PROBE_XS if along[0] <= x <= along[1]]
        ok = self.grid.wait_until(
            lambda g: g.width == WIDTH and g.height == HEIGHT and self.sides(g, xs) == [(south, north)] * len(xs),
            timeout=30.0)
        seen = self.sides(self.grid, xs) if self.grid.width == WIDTH else "a %dx%d grid" % (
            self.grid.width, self.grid.height)
        plan = getattr(self, "last_plan", [])
        self.assertTrue(ok, "%s: expected (south, north) %s everywhere along the corridor, saw %s at x %s;"
                        " the plan (every 5th pose) %s" % (why, (south, north), seen, xs, [
                            (round(p.pose.position.x, 3), round(p.pose.position.y, 3)) for p in plan[::5]]))

    def plan(self, start, goal, ys):
        """navfn's plan through move_base's make_plan, checked to keep within ys (the y range that puts the
        wall the case looks at within inflation_radius of it) and to be the one navfn published on the
        topic the layer reads."""
        res = self.make_plan(start=pose(*start), goal=pose(*goal), tolerance=0.0)
        poses = res.plan.poses
        self.assertGreater(len(poses), 10, "navfn found no plan from %s to %s" % (start, goal))
        self.last_plan = poses
        y = [p.pose.position.y for p in poses]
        self.assertTrue(ys[0] <= min(y) and max(y) <= ys[1], "navfn's plan runs at y %.3f..%.3f, outside %s" % (
            min(y), max(y), ys))
        last = poses[-1].pose.position
        published = self.navfn_plan.wait(
            lambda m: len(m.poses) == len(poses) and m.poses[-1].pose.position == last, timeout=10.0)
        self.assertTrue(published, "navfn did not publish its plan on /move_base/NavfnROS/plan")
        return poses

    def test_1_symmetric_with_the_larger_factor_before_any_plan(self):
        self.expect(FAST, FAST, "no plan yet")
        self.assertEqual(self.grid.at(3.0, 0.4), 100)  # the walls themselves
        self.assertEqual(self.grid.at(3.0, 1.6), 100)

    def test_2_east_plan_makes_the_north_wall_costlier(self):
        self.plan(ROBOT, (5.475, ROBOT[1]), ys=(0.975, 1.075))  # the north wall's cells within 0.6 m
        self.expect(FAST, SLOW, "plan east (north on its left)", along=(0.525, 5.475))

    def test_3_west_plan_swaps_the_sides(self):
        # From the far end back to 1 m ahead of the robot: its end is farther than goal_distance_threshold.
        self.plan((5.475, ROBOT[1]), (1.525, ROBOT[1]), ys=(0.6, 1.075))  # the south wall's within 0.6 m
        # Checked from 1 m past the plan's end on: there navfn's plan turns north-west back to the centre
        # line, and the wall cells beyond its end take the side of its last segment's line (Nav2's rule:
        # the nearest segment decides, here by its end point), part of the north wall's the left.
        self.expect(SLOW, FAST, "plan west (south on its left)", along=(2.525, 5.475))

    def test_4_symmetric_again_near_the_plan_end(self):
        self.plan((5.475, ROBOT[1]), (ROBOT[0] + 0.2, ROBOT[1]), ys=(0.55, 1.5))
        self.expect(FAST, FAST, "robot 0.2 m from the plan's end")


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "move_base_asymmetric", AsymmetricInMoveBaseTest)
