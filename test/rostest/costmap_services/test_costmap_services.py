#!/usr/bin/env python3
"""costmap_node's Nav2 services (~get_cost, ~clear_around_pose, ~clear_except_region, ~clear_entirely)
on a known map. The static layer draws one lethal cell S (70, 50); the obstacle layer holds four marks
A (30, 50), B (40, 50), C (60, 50), D (20, 80) that outlive their cloud. The robot is at (2, 5), yaw 0.
Nav2's clear_costmap_service_test (plugins lists: empty, clearable, non-clearable, unknown and mixed)
and costmap_cost_service_test (with and without footprint) are ported with known expected costs."""
import math
import os
import struct
import sys
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import OccupancyGrid
from sensor_msgs.msg import PointCloud2, PointField
from std_srvs.srv import Empty

from costmap_layers.srv import (ClearCostmapAroundPose, ClearCostmapExceptRegion, ClearEntireCostmap,
                                GetCosts)

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from grid_watch import CycleWatcher, ErrorLog, logged_with_key  # noqa: E402

NS = "/costmap_node/"
# Cell centres [m] of the marks, the static cell and a free cell.
A, B, C, D = (3.05, 5.05), (4.05, 5.05), (6.05, 5.05), (2.05, 8.05)
S, F = (7.05, 5.05), (2.55, 5.05)
MARKS = [A, B, C, D]
PERSISTENCE = 0.2  # the source's observation_persistence [s] (costmap.yaml)


def pose(x, y, frame="map", yaw=0.0):
    p = PoseStamped()
    p.header.frame_id = frame
    p.pose.position.x, p.pose.position.y = x, y
    p.pose.orientation.z, p.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    return p


def cloud(points, stamp):
    c = PointCloud2()
    c.header.frame_id = "map"
    c.header.stamp = stamp
    c.height, c.width = 1, len(points)
    c.fields = [PointField("x", 0, PointField.FLOAT32, 1), PointField("y", 4, PointField.FLOAT32, 1),
                PointField("z", 8, PointField.FLOAT32, 1)]
    c.point_step, c.row_step = 12, 12 * len(points)
    c.data = b"".join(struct.pack("<fff", x, y, 0.5) for x, y in points)
    c.is_dense = True
    return c


class CostmapServicesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_costmap_services")
        cls.cycles = CycleWatcher("/costmap_node")
        grid = OccupancyGrid()
        grid.header.frame_id = "map"
        grid.info.resolution = 0.1
        grid.info.width = grid.info.height = 100
        grid.info.origin.orientation.w = 1.0
        data = [0] * 10000
        data[50 * 100 + 70] = 100  # S
        grid.data = data
        cls.map_pub = rospy.Publisher("/svc_map", OccupancyGrid, queue_size=1, latch=True)
        cls.map_pub.publish(grid)
        cls.cloud_pub = rospy.Publisher("/svc_marks", PointCloud2, queue_size=5)
        for name in ["get_cost", "clear_around_pose", "clear_except_region", "clear_entirely", "clear"]:
            rospy.wait_for_service(NS + name, 30.0)
        cls.get_cost = rospy.ServiceProxy(NS + "get_cost", GetCosts)
        cls.around_pose = rospy.ServiceProxy(NS + "clear_around_pose", ClearCostmapAroundPose)
        cls.except_region = rospy.ServiceProxy(NS + "clear_except_region", ClearCostmapExceptRegion)
        cls.entirely = rospy.ServiceProxy(NS + "clear_entirely", ClearEntireCostmap)
        cls.clear = rospy.ServiceProxy(NS + "clear", Empty)

    def costs(self, points, use_footprint=False):
        return list(self.get_cost(use_footprint, [pose(x, y) for x, y in points]).costs)

    def wait_costs(self, points, expected, timeout=20.0):
        """Waits until the costs at points are the expected ones; fails with what was seen."""
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        seen = None
        while not rospy.is_shutdown() and rospy.Time.now() < deadline:
            seen = self.costs(points)
            if seen == expected:
                return
            self.cycles.wait(1, 2.0)
        self.fail("costs at %s: expected %s, saw %s" % (points, expected, seen))

    def setUp(self):
        # The obstacle layer forgets everything, then holds A..D (and S is drawn from the map).
        self.clear()
        deadline = rospy.Time.now() + rospy.Duration(30.0)
        stamp = None
        while not rospy.is_shutdown() and rospy.Time.now() < deadline:
            stamp = rospy.Time.now()
            self.cloud_pub.publish(cloud(MARKS, stamp))
            self.cycles.wait(1, 2.0)
            if self.costs(MARKS + [S]) == [254.0] * 5:
                break
        # The cloud is purged once older than its persistence; the marks stay in the layer's grid.
        while not rospy.is_shutdown() and rospy.Time.now() <= stamp + rospy.Duration(PERSISTENCE + 0.05):
            self.cycles.wait(1, 2.0)
        self.assertTrue(self.cycles.wait(3))
        self.assertEqual(self.costs(MARKS + [S, F]), [254.0] * 5 + [0.0])

    def assert_untouched(self):
        self.assertTrue(self.cycles.wait(2))
        self.assertEqual(self.costs(MARKS + [S, F]), [254.0] * 5 + [0.0])

    def test_get_cost(self):
        r = self.get_cost(False, [pose(*A), pose(*F), pose(*S), pose(-1.0, 5.0)])
        self.assertEqual(list(r.costs), [254.0, 0.0, 254.0, 254.0])  # off the map: lethal, as Nav2
        self.assertFalse(r.success)
        r = self.get_cost(False, [pose(*A), pose(*F)])
        self.assertEqual(list(r.costs), [254.0, 0.0])
        self.assertTrue(r.success)
        # In base_link (the robot at (2, 5)): (1.05, 0.05) is A, (4.05, 0.05) is C, (0.55, 0.05) is F.
        r = self.get_cost(False, [pose(1.05, 0.05, "base_link"), pose(4.05, 0.05, "base_link"),
                                  pose(0.55, 0.05, "base_link"), pose(3.05, 5.05, "")])
        self.assertEqual(list(r.costs), [254.0, 254.0, 0.0, 254.0])
        self.assertTrue(r.success)
        # A pose that cannot be placed is 255 and success false; the others are answered.
        r = self.get_cost(False, [pose(*A), pose(1.0, 1.0, "nowhere"), pose(float("nan"), 5.0),
                                  pose(2.0, float("inf"))])
        self.assertEqual(list(r.costs), [254.0, 255.0, 255.0, 255.0])
        self.assertFalse(r.success)
        bad_q = pose(*A)
        bad_q.pose.orientation.x = float("nan")
        r = self.get_cost(True, [bad_q])
        self.assertEqual(list(r.costs), [255.0])
        # The footprint (radius 0.2, 16 vertices, one at angle pi) at (3.25, 5.05): that vertex is at
        # x 3.05, in A's cell; the pose's own cell (32, 50) is free. At (3.55, 5.05) it spans cells 33..37.
        r = self.get_cost(True, [pose(3.25, 5.05), pose(3.55, 5.05)])
        self.assertEqual(list(r.costs), [254.0, 0.0])
        self.assertTrue(r.success)
        self.assertEqual(self.costs([(3.25, 5.05)]), [0.0])
        # Empty and too long lists.
        r = self.get_cost(False, [])
        self.assertEqual((list(r.costs), r.success), ([], True))
        r = self.get_cost(False, [pose(*A)] * 10001)
        self.assertEqual((list(r.costs), r.success), ([], False))

    def test_clear_around_pose(self):
        nan, inf = float("nan"), float("inf")
        for p, d, plugins in [(pose(*B), nan, []), (pose(*B), -1.0, []), (pose(*B), -inf, []),
                              (pose(nan, 5.0), 0.5, []), (pose(4.0, inf), 0.5, []), (pose(*B, "nowhere"), 0.5, []),
                              (pose(*B), 0.5, ["static_layer"]), (pose(*B), 0.5, ["voxel_layer"]),
                              (pose(*B), 0.5, ["obstacle_layer", "voxel_layer"]),
                              (pose(*B), 0.5, ["obstacle_layer", "static_layer"])]:
            self.assertFalse(self.around_pose(p, d, plugins).success, (p.pose.position, d, plugins))
        self.assert_untouched()
        # Side 0.5 around B: cells 37..42 (x 3.8..4.3), so B goes and A stays.
        self.assertTrue(self.around_pose(pose(*B), 0.5, []).success)
        self.wait_costs(MARKS + [S], [254.0, 0.0, 254.0, 254.0, 254.0])
        # In base_link, (4.05, 0.05) is C; side 0, only its cell; the named clearable plugin only.
        self.assertTrue(self.around_pose(pose(4.05, 0.05, "base_link"), 0.0, ["obstacle_layer"]).success)
        self.wait_costs(MARKS + [S], [254.0, 0.0, 0.0, 254.0, 254.0])

    def test_clear_except_region(self):
        for d, plugins in [(float("nan"), []), (-1.0, []), (-float("inf"), []), (1.0, ["static_layer"]),
                           (1.0, ["voxel_layer"]), (1.0, ["obstacle_layer", "voxel_layer"]),
                           (1.0, ["obstacle_layer", "static_layer"])]:
            self.assertFalse(self.except_region(d, plugins).success, (d, plugins))
        self.assert_untouched()
        # Keeping everything (an infinite square) with the clearable plugin named changes nothing.
        self.assertTrue(self.except_region(float("inf"), ["obstacle_layer"]).success)
        self.assert_untouched()
        # Side 2.5 around the robot (2, 5): cells 7..32 x 37..62 are kept: A only; S is not clearable.
        self.assertTrue(self.except_region(2.5, []).success)
        self.wait_costs(MARKS + [S], [254.0, 0.0, 0.0, 0.0, 254.0])

    def test_clear_entirely(self):
        for plugins in [["static_layer"], ["voxel_layer"], ["obstacle_layer", "voxel_layer"],
                        ["obstacle_layer", "static_layer"]]:
            self.assertFalse(self.entirely(plugins).success, plugins)
        self.assert_untouched()
        self.assertTrue(self.entirely(["obstacle_layer"]).success)
        self.wait_costs(MARKS + [S], [0.0, 0.0, 0.0, 0.0, 254.0])

    def test_clear_entirely_every_layer(self):
        # Every layer is reset; the static layer draws its map again, so S comes back.
        self.assertTrue(self.entirely([]).success)
        self.wait_costs(MARKS + [S], [0.0, 0.0, 0.0, 0.0, 254.0])

    def test_zz_refusals_flooding_a_service_are_logged_once_per_period(self):
        # Any peer may call the services as fast as it likes: each refusal is still answered (255, success
        # false), but its error line is throttled per service (ThrottledLog, 5 s), not one per call.
        log = ErrorLog("/costmap_node")
        deadline = rospy.Time.now() + rospy.Duration(30.0)
        while log.sub.get_num_connections() < 1 and rospy.Time.now() < deadline:
            rospy.sleep(0.05)  # polled with a deadline, not a fixed wait
        self.assertGreaterEqual(log.sub.get_num_connections(), 1, "no connection to /rosout")
        calls = 0
        start = time.monotonic()
        while time.monotonic() - start < 6.0:  # longer than one throttle period
            r = self.get_cost(False, [pose(1.0, 1.0, "nowhere")])
            self.assertEqual(list(r.costs), [255.0])
            self.assertFalse(r.success)
            calls += 1
        # A refusal right after a success of the same service is said: the lines of what was done have
        # keys of their own (clear_around_pose last refused in test_clear_around_pose, over 6 s ago).
        self.assertTrue(self.around_pose(pose(*B), 0.5, []).success)
        self.assertFalse(self.around_pose(pose(*B), float("nan"), []).success)
        # A refusal of another kind (too many poses: its own key, never logged before) is said at once,
        # and once it has arrived every line of the flood has (one publisher's messages come in order).
        too_many = self.get_cost(False, [pose(*F)] * 10001)
        self.assertFalse(too_many.success)
        marker = log.wait("get_cost/poses", ("10001",), timeout=30.0)
        log.sub.unregister()
        with log.cond:
            seen = list(log.lines)
        self.assertTrue(marker, "the refusal of 10001 poses was not logged: %s" % seen[-5:])
        self.assertTrue(logged_with_key(seen, "clear_around_pose", "nan"),
                        "the refusal after a success was not logged: %s" % seen[-5:])
        flood = [m for m in logged_with_key(seen, "get_cost") if "'nowhere'" in m]
        self.assertGreater(calls, 50)
        # 6 s of refusals: one line, or two when test_get_cost's refusal had just started a period.
        self.assertTrue(1 <= len(flood) <= 2, "%d lines for %d refused calls: %s" % (len(flood), calls, flood[:3]))


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "costmap_services", CostmapServicesTest)
