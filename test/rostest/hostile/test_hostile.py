#!/usr/bin/env python3
"""Hostile input: for every input class the node reads (maps, masks, map updates, speed limits, laser
scans, point clouds, ranges, tf) the malformed variants (truncated, oversized, NaN/inf, negative or
zero sizes, huge dimensions, wrong frames, stale stamps and stamps at the end of ROS time) are
published while the node runs. It must keep running, the published costmap and /max_speed must keep
their last good values, and each problem must be reported by an error that names the field and its
value, throttled (not once per message)."""
import math
import os
import struct
import sys
import threading
import time
import unittest

import rospy
import rostest
from costmap_layers.msg import MaxSpeed, SpeedLimit, SpeedLimits
from map_msgs.msg import OccupancyGridUpdate
from nav_msgs.msg import OccupancyGrid
from rosgraph_msgs.msg import Log
from geometry_msgs.msg import TransformStamped
from sensor_msgs.msg import LaserScan, PointCloud2, PointField, Range
from tf2_msgs.msg import TFMessage

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from grid_watch import CycleWatcher, GridWatcher, logged_with_key  # noqa: E402
from grid_watch import occupancy_grid as grid  # noqa: E402

NAN = float("nan")
INF = float("inf")


def stamped(msg, stamp):
    msg.header.stamp = stamp
    return msg


def scan(**kw):
    s = LaserScan()
    s.header.frame_id = "base_link"
    s.header.stamp = rospy.Time.now() - rospy.Duration(0.05)
    s.angle_min, s.angle_max, s.angle_increment = -0.1, 0.1, 0.1
    s.range_min, s.range_max = 0.1, 5.0
    s.ranges = [1.0, 1.0, 1.0]
    for k, v in kw.items():
        setattr(s, k, v)
    return s


def cloud(**kw):
    c = PointCloud2()
    c.header.frame_id = "base_link"
    c.header.stamp = rospy.Time.now() - rospy.Duration(0.05)
    c.height, c.width = 1, 2
    c.fields = [PointField("x", 0, PointField.FLOAT32, 1), PointField("y", 4, PointField.FLOAT32, 1),
                PointField("z", 8, PointField.FLOAT32, 1)]
    c.point_step, c.row_step = 12, 24
    c.data = struct.pack("<ffffff", 1.0, 0.0, 0.3, 1.0, 0.1, 0.3)
    for k, v in kw.items():
        setattr(c, k, v)
    return c


def sonar(**kw):
    r = Range()
    r.header.frame_id = "base_link"
    r.header.stamp = rospy.Time.now() - rospy.Duration(0.05)
    r.field_of_view, r.min_range, r.max_range, r.range = 0.3, 0.1, 3.0, 1.0
    for k, v in kw.items():
        setattr(r, k, v)
    return r


class HostileTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_hostile")
        cls.grid = GridWatcher("/costmap_node")
        cls.cycles = CycleWatcher("/costmap_node")
        cls.lock = threading.Lock()
        cls.logs = []
        cls.speeds = []

        def on_log(m):
            if m.name == "/costmap_node" and m.level >= Log.WARN:
                with cls.lock:
                    cls.logs.append(m.msg)

        def on_speed(m):
            with cls.lock:
                cls.speeds.append(m.max_speed)

        rospy.Subscriber("/rosout", Log, on_log)
        rospy.Subscriber("/max_speed", MaxSpeed, on_speed)
        cls.pubs = {
            "/map": rospy.Publisher("/map", OccupancyGrid, queue_size=10),
            "/map_updates": rospy.Publisher("/map_updates", OccupancyGridUpdate, queue_size=10),
            "/keepout_filter_mask": rospy.Publisher("/keepout_filter_mask", OccupancyGrid, queue_size=10),
            "/speed_filter_mask": rospy.Publisher("/speed_filter_mask", OccupancyGrid, queue_size=10),
            "/features": rospy.Publisher("/features", SpeedLimits, queue_size=10),
            "/scan": rospy.Publisher("/scan", LaserScan, queue_size=10),
            "/cloud": rospy.Publisher("/cloud", PointCloud2, queue_size=10),
            "/sonar": rospy.Publisher("/sonar", Range, queue_size=10),
            "/tf": rospy.Publisher("/tf", TFMessage, queue_size=10),
        }
        # A good state to keep: the static map with the keepout dock drawn, and area 1's limit.
        dock = (14.0, 8.5)
        assert cls.grid.wait_until(lambda g: g.at(*dock) == 100, 40.0), "no good costmap to start from"
        deadline = time.time() + 20
        while time.time() < deadline:
            with cls.lock:
                if cls.speeds and cls.speeds[-1] == 0.3:
                    break
            time.sleep(0.1)
        assert cls.cycles.wait(5), "the update loop stopped"  # let the first cycles' own output settle
        cls.good_grid = cls.grid.snapshot()
        with cls.lock:
            cls.good_speeds = list(cls.speeds)
        for p in cls.pubs.values():  # let every publisher connect before the bad input goes out
            deadline = time.time() + 10
            while p.get_num_connections() == 0 and time.time() < deadline:
                time.sleep(0.05)

    def flood(self, topic, messages, repeat=5):
        import rosnode
        for _ in range(repeat):
            for m in messages:
                self.pubs[topic].publish(m)
                rospy.sleep(0.02)  # pacing: a subscriber queue holds few messages
        self.assertTrue(self.cycles.wait(3), "the update loop stopped after bad input on %s" % topic)
        self.assertTrue(rosnode.rosnode_ping("/costmap_node", max_count=1),
                        "costmap_node died after bad input on %s" % topic)

    def said(self, key, *values):
        """Lines logged under the stable key (relative to the node) that contain each value."""
        with self.lock:
            return logged_with_key(self.logs, "/costmap_node/" + key, *values)

    def wait_said(self, key, *values, timeout=10.0):
        deadline = time.time() + timeout
        while not self.said(key, *values) and time.time() < deadline:
            time.sleep(0.1)
        return self.said(key, *values)

    def test_bad_input_of_every_class(self):
        bad_grids = [
            grid(10, 10, 0.05, [0] * 7),                    # truncated data
            grid(10, 10, 0.05, [0] * 1000),                 # oversized data
            grid(10, 10, 0.0, [0] * 100),                   # zero resolution
            grid(10, 10, NAN, [0] * 100),                   # NaN resolution
            grid(10, 10, 0.05, [0] * 100, ox=INF),          # infinite origin
            grid(100000, 100000, 0.05, [0] * 16),           # would need 10 G cells
            grid(0, 10, 0.05, []),                          # zero width
        ]
        for topic in ("/map", "/keepout_filter_mask", "/speed_filter_mask"):
            self.flood(topic, bad_grids, repeat=3)
        # A mask in a frame tf does not know: the speed filter cannot place the robot in it, so the
        # last published limit stays.
        self.flood("/speed_filter_mask", [grid(10, 10, 0.5, [1] * 100, frame="nowhere")], repeat=1)

        bad_update = OccupancyGridUpdate()
        bad_update.header.frame_id = "map"
        bad_update.x, bad_update.y, bad_update.width, bad_update.height = 310, 190, 50, 50  # leaves the map
        bad_update.data = [100] * 2500
        short_update = OccupancyGridUpdate()
        short_update.header.frame_id = "map"
        short_update.x, short_update.y, short_update.width, short_update.height = 1, 1, 5, 5
        short_update.data = [100] * 3  # truncated
        self.flood("/map_updates", [bad_update, short_update])

        bad_features = SpeedLimits()
        bad_features.header.frame_id = "map"
        bad_features.header.stamp = rospy.Time.now()
        bad_features.limits = [SpeedLimit(1, NAN), SpeedLimit(2, -1.0)]
        self.flood("/features", [bad_features])

        self.flood("/scan", [scan(angle_increment=0.0), scan(angle_increment=NAN), scan(range_max=INF),
                             scan(ranges=[1.0] * 1000), scan(angle_min=-INF)])
        self.flood("/cloud", [cloud(point_step=0), cloud(row_step=3), cloud(data=b"\x00" * 5),
                              cloud(fields=[PointField("x", 100, PointField.FLOAT32, 1)]),
                              cloud(width=1000000000, row_step=12000000000 % (2 ** 32)), cloud(is_bigendian=True)])
        self.flood("/sonar", [sonar(range=NAN), sonar(field_of_view=-1.0), sonar(min_range=INF), sonar(max_range=NAN)])

        # Stale stamps. Well-formed grids and speed limits stamped before the ones in force (a replayed
        # latched message, an old publisher still running) would roll the costmap back if applied:
        # a free map, free masks, an update that clears the rack, area 1 at 0.9 m/s.
        old = rospy.Time(1.0)
        self.flood("/map", [stamped(grid(10, 10, 0.05, [0] * 100), old)], repeat=2)
        self.flood("/keepout_filter_mask", [stamped(grid(10, 10, 0.05, [0] * 100), old)], repeat=2)
        self.flood("/speed_filter_mask", [stamped(grid(10, 10, 0.05, [0] * 100), old)], repeat=2)
        stale_update = OccupancyGridUpdate()
        stale_update.header.frame_id = "map"
        stale_update.x, stale_update.y, stale_update.width, stale_update.height = 158, 144, 5, 5  # the rack
        stale_update.data = [0] * 25
        self.flood("/map_updates", [stamped(stale_update, old)], repeat=2)
        stale_features = SpeedLimits()
        stale_features.header.frame_id = "map"
        stale_features.limits = [SpeedLimit(1, 0.9)]
        self.flood("/features", [stamped(stale_features, old)], repeat=2)
        # Sensor readings from an hour ago are older than any transform tf keeps; readings from an hour
        # ahead are refused as soon as they arrive.
        # Either would mark 2 m ahead of the robot if it were used.
        hour = rospy.Duration(3600)
        self.flood("/scan", [stamped(scan(ranges=[2.0] * 3), rospy.Time.now() - hour)], repeat=3)
        self.flood("/scan", [stamped(scan(ranges=[2.0] * 3), rospy.Time.now() + hour)], repeat=12)
        self.flood("/cloud", [stamped(cloud(), rospy.Time.now() - hour)], repeat=3)
        self.flood("/sonar", [stamped(sonar(), rospy.Time.now() + hour)], repeat=12)
        # Stamps at the end of ROS time (secs = 0xFFFFFFFF, about 68 years on): ROS's own Time - Time
        # throws that far from now, which in a subscriber callback would end the node.
        end = rospy.Time(0xFFFFFFFF, 0)
        self.flood("/scan", [stamped(scan(ranges=[2.0] * 3), end)], repeat=3)
        self.flood("/cloud", [stamped(cloud(), end)], repeat=3)
        self.flood("/sonar", [stamped(sonar(), end)], repeat=3)
        # The same stamp on /tf: tf2 adds its cache length to it (ROS time arithmetic throws), and
        # tf2_ros's own listener lets that end the node; the node's listener names it and drops it.
        far_tf = TransformStamped()
        far_tf.header.frame_id, far_tf.child_frame_id = "map", "hostile_frame"
        far_tf.header.stamp = end
        far_tf.transform.rotation.w = 1.0
        self.flood("/tf", [TFMessage([far_tf])], repeat=3)
        self.assertTrue(self.cycles.wait(10), "the update loop stopped")

        # Still running: it answers a service and keeps publishing.
        import rosnode
        self.assertTrue(rosnode.rosnode_ping("/costmap_node", max_count=1), "costmap_node died")

        # The good state is kept. Sensor layers: the big-endian cloud is well-formed (the node reads it
        # byte-swapped, garbage coordinates but not a crash); compare the cells nobody's sensor reaches.
        now = self.grid.snapshot()
        w = self.grid.width
        changed = [(i % w, i // w) for i, (a, b) in enumerate(zip(now, self.good_grid)) if a != b]
        far = [c for c in changed if math.hypot(c[0] * 0.05 - 5.0, c[1] * 0.05 - 1.5) > 6.0]
        self.assertEqual(far, [], "the costmap changed where no valid reading reached")
        for x, y in [(14.0, 8.5), (0.1, 5.0), (8.0, 7.3)]:  # keepout dock, a wall, a rack
            self.assertEqual(self.grid.at(x, y), 100)
        with self.lock:
            self.assertEqual(self.speeds[len(self.good_speeds):], [], "/max_speed changed")
        ahead = int(1.5 / self.grid.resolution) * w + int(7.0 / self.grid.resolution)  # 2 m ahead of the robot
        self.assertEqual(now[ahead], self.good_grid[ahead], "a stale reading was marked")

        # Each problem was named by its stable key (the field), with the value.
        expectations = [
            ("static_layer/map/data", "7"),
            ("keepout_filter/mask/data", "7"),
            ("speed_filter/mask/data", "7"),
            ("static_layer/map/info.resolution", "0"),
            ("static_layer/map/info.origin", "x=inf"),
            ("static_layer/map/info.cells", "100000x100000"),
            ("static_layer/map/info.width", "0x10"),
            ("speed_filter/transform", "nowhere"),
            ("static_layer/map_update/width", "x=310"),
            ("static_layer/map_update/data", "3"),
            ("speed_filter/features/limits", "nan"),
            ("obstacle_layer/invalid/scan", "angle_increment"),
            ("obstacle_layer/invalid/cloud", "point_step"),
            ("range_layer/invalid_range", "range"),
            ("static_layer/map/header.stamp", "1.000"),
            ("keepout_filter/mask/header.stamp", "1.000"),
            ("speed_filter/mask/header.stamp", "1.000"),
            ("static_layer/map_update/header.stamp", "1.000"),
            ("speed_filter/features_stamp", "1.000"),
            ("obstacle_layer/scan/tf/stamp", "header.stamp"),
            ("obstacle_layer/cloud/tf/stamp", "header.stamp"),
            ("obstacle_layer/scan/tf/future", "header.stamp"),
            ("range_layer/sonar/tf/future", "header.stamp"),
            ("obstacle_layer/cloud/tf/future", "4294967295"),
            ("tf/transforms", "4294967295", "hostile_frame"),
        ]
        for key, *values in expectations:
            self.assertTrue(self.wait_said(key, *values, timeout=5.0), "nothing logged under [/costmap_node/%s] with %s; got:\n%s" % (
                key, values, "\n".join(self.logs[-40:])))
        # Throttled: a key is not logged once per message (each bad grid went out 3 times to each of 3
        # topics, and each scan 5 times, within seconds).
        for key in ("static_layer/map/data", "keepout_filter/mask/data", "obstacle_layer/invalid/scan"):
            n = len(self.said(key))
            self.assertLessEqual(n, 2, "[%s] logged %d times: not throttled" % (key, n))


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "hostile", HostileTest)
