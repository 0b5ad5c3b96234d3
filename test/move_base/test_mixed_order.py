#!/usr/bin/env python3
"""move_base with bridged plugins and costmap_2d's own layers in one process, in the order of one
scenario of mixed/ (see mixed/mixed.launch and the mixed_*.test files, issue 33):
- move_base came up at all (before the fix it died when a bridged plugin was loaded before
  costmap_2d::ObstacleLayer: the bridge had mapped costmap_2d's plugin library, so class_loader never
  registered its factories);
- navfn's plan (move_base's make_plan) goes around the keepout band that the bridged KeepoutFilter draws;
- costmap_2d's own ObstacleLayer and VoxelLayer mark the scans published for them in move_base's local
  costmap, and the bridged ObstacleLayer its own, where the scenario has it there.
Each check waits on arrivals with a deadline, never on a fixed sleep."""
import math
import os
import sys
import threading
import unittest

import rospy
import rostest
from nav_msgs.srv import GetPlan
from sensor_msgs.msg import LaserScan

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "rostest"))
from grid_watch import GridWatcher  # noqa: E402
from grid_watch import map_pose as pose  # noqa: E402

START = (1.0, 1.0)  # fake_robot's pose in mixed.launch
GOAL = (5.0, 1.0)
# The keepout band of keepout.pgm (make_maps.py): x in [2.8, 3.2) m, y in [0, 3.0) m.
BAND = (2.8, 3.2, 0.0, 3.0)
LETHAL = 100  # cost 254 as published
RANGE = 0.6  # [m] of every beam published below
# topic: the beam direction in base_link [rad] (the robot faces +x), so each obstacle layer's hits land
# in a cell of their own, 0.6 m from the robot.
SCANS = {"/scan": math.pi / 2, "/scan_voxel": math.pi, "/scan_bridged": -math.pi / 2}


def hit(topic):
    """Where the beams of topic end, in map [m]."""
    a = SCANS[topic]
    return START[0] + RANGE * math.cos(a), START[1] + RANGE * math.sin(a)


def value_at(g, x, y):
    """The value of the cell of g (a GridWatcher, origin anywhere: the local costmap rolls) holding (x, y)."""
    if g.data is None or not g.resolution:
        return None
    i = int(math.floor((x - g.origin[0]) / g.resolution))
    j = int(math.floor((y - g.origin[1]) / g.resolution))
    if not (0 <= i < g.width and 0 <= j < g.height):
        return None
    return g.data[j * g.width + i]


def scan(angle):
    """A short fan of beams (about 6 degrees) around angle, all RANGE long, from base_link."""
    s = LaserScan()
    s.header.frame_id = "base_link"
    s.angle_min, s.angle_max, s.angle_increment = angle - 0.05, angle + 0.05, 0.01
    s.range_min, s.range_max = 0.05, 5.0
    s.ranges = [RANGE] * 11
    return s


class MixedOrderTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_mixed_order")
        cls.bridged_local = bool(rospy.get_param("~bridged_local_obstacles", False))
        # The scans whose marks the local costmap must show (default: the scenario's, below).
        cls.scan_topics = rospy.get_param("~scan_topics", None)
        cls.global_grid = GridWatcher("/move_base/global_costmap")
        cls.local_grid = GridWatcher("/move_base/local_costmap")
        # make_plan is advertised once both costmaps and their plugins are up: move_base alive.
        rospy.wait_for_service("/move_base/make_plan", timeout=60.0)
        cls.make_plan = rospy.ServiceProxy("/move_base/make_plan", GetPlan)
        cls.publishers = {t: rospy.Publisher(t, LaserScan, queue_size=1) for t in SCANS}
        cls.scanning = threading.Event()

    @classmethod
    def tearDownClass(cls):
        cls.scanning.clear()

    def publish_scans(self):
        """Publishes every scan at 10 Hz, stamped now (the layers look up tf at the stamp), from now on."""
        if self.scanning.is_set():
            return
        self.scanning.set()

        def run():
            rate = rospy.Rate(10.0)
            while self.scanning.is_set() and not rospy.is_shutdown():
                for topic, pub in self.publishers.items():
                    s = scan(SCANS[topic])
                    s.header.stamp = rospy.Time.now()
                    pub.publish(s)
                rate.sleep()

        threading.Thread(target=run, daemon=True).start()

    def test_plan_goes_around_the_keepout_zone(self):
        centre = (3.0, 1.0)
        self.assertTrue(self.global_grid.wait_until(lambda g: g.at(*centre) == LETHAL, timeout=30.0),
                        "the keepout band never became lethal in move_base's global costmap")
        # Asked again on each new costmap publication until the deadline: the costmap the planner reads
        # is redrawn by move_base's update thread.
        deadline = rospy.Time.now() + rospy.Duration(30.0)
        while True:
            seen = self.global_grid.count
            poses = self.make_plan(start=pose(*START), goal=pose(*GOAL), tolerance=0.0).plan.poses
            ys = [p.pose.position.y for p in poses]
            crosses = any(BAND[0] <= p.pose.position.x < BAND[1] and BAND[2] <= p.pose.position.y < BAND[3]
                          for p in poses)
            if len(poses) > 2 and not crosses:
                break
            self.assertLess(rospy.Time.now(), deadline, "navfn's plan %s: %d poses, max y %s" % (
                "crosses the band" if crosses else "is empty", len(poses), max(ys, default=None)))
            self.global_grid.wait_until(lambda g: g.count > seen, timeout=1.0)
        # The gap is above the band (y >= 3.0): the plan passes there.
        self.assertGreater(max(ys), BAND[3], "the plan does not pass above the band")

    def test_obstacle_layers_mark_their_scans_in_the_local_costmap(self):
        topics = self.scan_topics or (["/scan", "/scan_voxel"] + (["/scan_bridged"] if self.bridged_local else []))
        # Nothing there before the scans: what is marked below is the scans'.
        self.assertTrue(self.local_grid.wait_until(
            lambda g: all(value_at(g, *hit(t)) not in (None, LETHAL) for t in topics), timeout=30.0),
            "the local costmap never showed the scans' cells free of obstacles before any scan")
        self.publish_scans()
        for topic in topics:
            ok = self.local_grid.wait_until(lambda g: value_at(g, *hit(topic)) == LETHAL, timeout=20.0)
            self.assertTrue(ok, "%s never marked at %s in move_base's local costmap (value %s)" % (
                topic, hit(topic), value_at(self.local_grid, *hit(topic))))


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "test_mixed_order", MixedOrderTest)
