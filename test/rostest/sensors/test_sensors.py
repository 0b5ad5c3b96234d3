#!/usr/bin/env python3
"""The sensor layers through real topics: LaserScan, PointCloud2 and Range publishers and a robot in
tf. Marks appear and clear; a reading in a frame tf does not know is dropped (the node keeps running
and says which frame); a source that stops makes the costmap not current, and the node says which."""
import math
import os
import struct
import sys
import threading
import unittest

import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import TransformStamped
from rosgraph_msgs.msg import Log
from geometry_msgs.msg import Point32
from sensor_msgs.msg import LaserScan, PointCloud, PointCloud2, PointField, Range

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from grid_watch import CycleWatcher, GridWatcher, logged_with_key  # noqa: E402


def static_tf(parent, child, x, y, z):
    t = TransformStamped()
    t.header.stamp = rospy.Time.now()
    t.header.frame_id = parent
    t.child_frame_id = child
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = x, y, z
    t.transform.rotation.w = 1.0
    return t


def scan(ranges, stamp):
    s = LaserScan()
    s.header.frame_id = "laser"
    s.header.stamp = stamp
    s.angle_min = -0.2
    s.angle_increment = 0.4 / (len(ranges) - 1)
    s.angle_max = s.angle_min + s.angle_increment * (len(ranges) - 1)
    s.range_min = 0.05
    s.range_max = 6.0
    s.ranges = ranges
    return s


def cloud(points, frame, stamp):
    c = PointCloud2()
    c.header.frame_id = frame
    c.header.stamp = stamp
    c.height, c.width = 1, len(points)
    c.fields = [PointField("x", 0, PointField.FLOAT32, 1), PointField("y", 4, PointField.FLOAT32, 1),
                PointField("z", 8, PointField.FLOAT32, 1)]
    c.is_bigendian = False
    c.point_step = 12
    c.row_step = 12 * len(points)
    c.data = b"".join(struct.pack("<fff", *p) for p in points)
    c.is_dense = True
    return c


def old_cloud(points, frame, stamp):
    c = PointCloud()
    c.header.frame_id = frame
    c.header.stamp = stamp
    c.points = [Point32(*p) for p in points]
    return c


def sonar(rng, stamp):
    r = Range()
    r.header.frame_id = "sonar"
    r.header.stamp = stamp
    r.radiation_type = Range.ULTRASOUND
    r.field_of_view = 0.1
    r.min_range = 0.05
    r.max_range = 3.0
    r.range = rng
    return r


class Robot:
    """The robot's pose in tf (map -> base_link), published at 20 Hz by a thread of the test."""

    def __init__(self):
        self.lock = threading.Lock()
        self.pose = (2.0, 5.0)
        self.broadcaster = tf2_ros.TransformBroadcaster()
        threading.Thread(target=self._run, daemon=True).start()

    def move_to(self, x, y):
        with self.lock:
            self.pose = (x, y)

    def _run(self):
        rate = rospy.Rate(20.0)
        while not rospy.is_shutdown():
            with self.lock:
                x, y = self.pose
            t = static_tf("map", "base_link", x, y, 0.0)
            t.header.stamp = rospy.Time.now()
            self.broadcaster.sendTransform(t)
            rate.sleep()


class SensorsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_sensors")
        cls.robot = Robot()
        cls.grid = GridWatcher("/costmap_node")
        cls.cycles = CycleWatcher("/costmap_node")
        cls.logs = []
        cls.log_lock = threading.Lock()

        def on_log(msg):
            with cls.log_lock:
                cls.logs.append((msg.name, msg.level, msg.msg))

        rospy.Subscriber("/rosout", Log, on_log)
        cls.statics = tf2_ros.StaticTransformBroadcaster()
        cls.statics.sendTransform([static_tf("base_link", "laser", 0.0, 0.0, 0.3),
                                   static_tf("base_link", "camera", 0.0, 0.0, 0.5),
                                   static_tf("base_link", "sonar", 0.0, 0.0, 0.2)])
        cls.scan_pub = rospy.Publisher("/scan", LaserScan, queue_size=5)
        cls.mount_pub = rospy.Publisher("/scan_mount", LaserScan, queue_size=5)
        cls.cloud_pub = rospy.Publisher("/cloud", PointCloud2, queue_size=5)
        cls.old_cloud_pub = rospy.Publisher("/old_cloud", PointCloud, queue_size=5)
        cls.sonar_pub = rospy.Publisher("/sonar", Range, queue_size=5)
        cls.vcloud_pub = rospy.Publisher("/vcloud", PointCloud2, queue_size=5)
        cls.tf_buffer = tf2_ros.Buffer()
        tf2_ros.TransformListener(cls.tf_buffer)
        cls.tf_buffer.lookup_transform("map", "laser", rospy.Time(0), rospy.Duration(20.0))
        assert cls.grid.wait_until(lambda g: True, 30.0), "no costmap published"

    def publish_for(self, pub, make, seconds, rate=10.0):
        """Publishes make(stamp) at rate for a while (stamps from now, so tf has them)."""
        r = rospy.Rate(rate)
        end = rospy.Time.now() + rospy.Duration(seconds)
        while rospy.Time.now() < end and not rospy.is_shutdown():
            pub.publish(make(rospy.Time.now() - rospy.Duration(0.05)))
            r.sleep()

    def lethal(self):
        """The lethal cells [m] of the published grid, for failure messages."""
        d = self.grid.snapshot() or []
        w = self.grid.width
        return [(round((i % w) * 0.1, 1), round((i // w) * 0.1, 1)) for i, v in enumerate(d) if v == 100]

    def said(self, key, *values):
        """Warnings logged under the stable key (relative to the node) that contain each value."""
        with self.log_lock:
            lines = [m[2] for m in self.logs if m[1] >= Log.WARN]
        return logged_with_key(lines, "/costmap_node/" + key, *values)

    def setUp(self):
        # Each case starts from the same state: the robot at (2, 5) facing +x, sensor layers cleared.
        from std_srvs.srv import Empty
        self.robot.move_to(2.0, 5.0)
        self.assertTrue(self.cycles.wait(2), "the update loop stopped")
        rospy.wait_for_service("/costmap_node/clear", 10.0)
        rospy.ServiceProxy("/costmap_node/clear", Empty)()
        self.assertTrue(self.grid.wait_until(lambda g: g.data.count(100) == 0, 10.0),
                        "lethal after ~clear: %s" % self.lethal())

    def test_laser_marks_and_clears(self):
        # Robot at (2, 5) facing +x, laser 0.3 m up: beams hitting 1.5 m ahead mark around (3.5, 5.0).
        self.publish_for(self.scan_pub, lambda st: scan([1.5] * 5, st), 1.0)
        self.assertTrue(self.grid.wait_until(lambda g: g.at(3.55, 5.0) == 100, 10.0), "the scan did not mark; lethal: %s" % self.lethal())
        self.assertEqual(self.grid.at(2.8, 5.0), 0)  # the ray before the hit is free
        # The obstacle moves away: longer readings along the same beams clear the old cells.
        self.publish_for(self.scan_pub, lambda st: scan([3.0] * 5, st), 1.0)
        self.assertTrue(self.grid.wait_until(lambda g: g.at(3.55, 5.0) == 0 and g.at(5.05, 5.0) == 100, 10.0),
                        "the old mark was not cleared or the new one not marked")

    def test_cloud_marks_within_heights_and_clears(self):
        # Camera 0.5 m up at (2, 5): a point 2 m ahead, 1 m left, at z -0.2 (0.3 m above the floor) marks;
        # one at z -0.45 (0.05 m, below min_obstacle_height 0.1) does not.
        self.publish_for(self.cloud_pub, lambda st: cloud([(2.0, 1.0, -0.2), (2.0, -1.0, -0.45)], "camera", st), 1.0)
        self.assertTrue(self.grid.wait_until(lambda g: g.at(4.05, 6.05) == 100, 10.0), "the cloud did not mark")
        self.assertEqual(self.grid.at(4.05, 4.05), 0)
        # A point farther along the same ray clears the first one.
        self.publish_for(self.cloud_pub, lambda st: cloud([(3.0, 1.5, -0.2)], "camera", st), 1.0)
        self.assertTrue(self.grid.wait_until(lambda g: g.at(4.05, 6.05) == 0 and g.at(5.05, 6.55) == 100, 10.0),
                        "the cloud's old mark was not cleared")

    def test_older_point_cloud_type_marks_and_clears(self):
        # The same as the PointCloud2 case through sensor_msgs/PointCloud, which costmap_2d reads (its
        # default data_type); it was refused at start-up before.
        self.publish_for(self.old_cloud_pub,
                         lambda st: old_cloud([(2.0, 1.0, -0.2), (2.0, -1.0, -0.45)], "camera", st), 1.0)
        self.assertTrue(self.grid.wait_until(lambda g: g.at(4.05, 6.05) == 100, 10.0), "the old cloud did not mark")
        self.assertEqual(self.grid.at(4.05, 4.05), 0)
        self.publish_for(self.old_cloud_pub, lambda st: old_cloud([(3.0, 1.5, -0.2)], "camera", st), 1.0)
        self.assertTrue(self.grid.wait_until(lambda g: g.at(4.05, 6.05) == 0 and g.at(5.05, 6.55) == 100, 10.0),
                        "the old cloud's old mark was not cleared")

    def test_sonar_marks_and_clears_on_max(self):
        # Facing +x at (2, 5): a 2 m echo marks (4, 5); a max-range reading clears it (clear_on_max_reading).
        self.publish_for(self.sonar_pub, lambda st: sonar(2.0, st), 1.5)
        self.assertTrue(self.grid.wait_until(lambda g: g.at(4.0, 5.0) == 100, 10.0), "the sonar did not mark (4, 5); lethal: %s" % self.lethal())
        self.publish_for(self.sonar_pub, lambda st: sonar(3.0, st), 1.5)
        self.assertTrue(self.grid.wait_until(lambda g: g.at(4.0, 5.0) == 0, 10.0),
                        "the max-range reading did not clear (4, 5)")

    def test_unknown_frame_is_dropped(self):
        before = self.grid.snapshot()
        # The node waits for tf a little (a bounded queue of readings), then drops them and says so.
        self.publish_for(self.cloud_pub, lambda st: cloud([(1.0, 0.0, 0.3)], "nowhere", st), 3.0)
        deadline = rospy.Time.now() + rospy.Duration(10.0)
        while not self.said("obstacle_layer/cloud/tf/wait", "nowhere") and rospy.Time.now() < deadline:
            rospy.sleep(0.2)
        said = self.said("obstacle_layer/cloud/tf/wait", "nowhere", "map")
        self.assertTrue(said, "no warning named the unknown frame and the global frame")
        # Nothing was marked from it, and the node still runs: a good reading is still taken.
        self.assertEqual(self.grid.snapshot().count(100), before.count(100))
        self.publish_for(self.scan_pub, lambda st: scan([1.0] * 5, st), 1.0)
        self.assertTrue(self.grid.wait_until(lambda g: g.at(3.05, 5.0) == 100, 10.0), "the node stopped taking readings")

    def test_sensor_frame_is_waited_for_then_used(self):
        # scan_mount's rays start at its sensor_frame `mount`, which tf does not know yet: its readings wait
        # for that frame too (not only for their own `laser`), then are dropped with a warning naming both
        # frames, and mark nothing.
        self.publish_for(self.mount_pub, lambda st: scan([1.5] * 5, st), 2.0)
        deadline = rospy.Time.now() + rospy.Duration(10.0)
        while not self.said("obstacle_layer/scan_mount/tf/wait", "mount") and rospy.Time.now() < deadline:
            rospy.sleep(0.2)
        self.assertTrue(self.said("obstacle_layer/scan_mount/tf/wait", "'laser'", "sensor_frame 'mount'", "map"),
                        "no warning named the reading's frame and the missing sensor_frame")
        self.assertEqual(self.grid.at(3.55, 5.0), 0, "a reading whose sensor_frame tf cannot place marked")
        # Once tf has the frame, the same readings mark 1.5 m ahead.
        self.statics.sendTransform([static_tf("base_link", "laser", 0.0, 0.0, 0.3),
                                    static_tf("base_link", "camera", 0.0, 0.0, 0.5),
                                    static_tf("base_link", "sonar", 0.0, 0.0, 0.2),
                                    static_tf("base_link", "mount", 0.0, 0.0, 0.3)])
        self.tf_buffer.lookup_transform("map", "mount", rospy.Time(0), rospy.Duration(10.0))
        self.publish_for(self.mount_pub, lambda st: scan([1.5] * 5, st), 1.0)
        self.assertTrue(self.grid.wait_until(lambda g: g.at(3.55, 5.0) == 100, 10.0),
                        "the readings did not mark once sensor_frame was in tf; lethal: %s" % self.lethal())

    def test_late_source_is_reported(self):
        # The laser expects a reading every 1.0 s: after it stops, the layer is not current and says so.
        self.publish_for(self.scan_pub, lambda st: scan([1.0] * 5, st), 0.5)
        deadline = rospy.Time.now() + rospy.Duration(15.0)
        while not self.said("obstacle_layer/late/scan") and rospy.Time.now() < deadline:
            rospy.sleep(0.2)
        self.assertTrue(self.said("obstacle_layer/late/scan", "scan"), "no warning named the late source")

    def test_marks_stay_in_place_while_the_robot_moves(self):
        self.publish_for(self.scan_pub, lambda st: scan([1.0] * 5, st), 1.0)
        self.assertTrue(self.grid.wait_until(lambda g: g.at(3.05, 5.0) == 100, 10.0))
        for step in range(1, 11):  # drive 0.5 m in 5 cm steps, a cycle or more each
            self.robot.move_to(2.0 + 0.05 * step, 5.0)
            self.assertTrue(self.cycles.wait(1), "the update loop stopped")
        self.assertTrue(self.cycles.wait(2), "the update loop stopped")
        # From (2.5, 5) the same obstacle is 0.5 m ahead: the mark is where it was in the map.
        self.publish_for(self.scan_pub, lambda st: scan([0.5] * 5, st), 1.0)
        self.assertTrue(self.grid.wait_until(lambda g: g.at(3.05, 5.0) == 100, 10.0))

    def test_clear_services(self):
        from std_srvs.srv import Empty
        self.robot.move_to(2.5, 5.0)
        self.assertTrue(self.cycles.wait(2), "the update loop stopped")
        # The robot is at (2.5, 5). A camera point 3.5 m ahead marks (6.0, 5.0); a later cloud sees only a
        # point elsewhere, so that mark stays in the grid without being in any buffer; the laser marks
        # 1 m ahead, inside the square ~clear_around_robot keeps (reset_distance 3 m).
        self.publish_for(self.cloud_pub, lambda st: cloud([(3.5, 0.0, -0.2)], "camera", st), 1.0)
        self.publish_for(self.cloud_pub, lambda st: cloud([(0.8, 0.6, -0.2)], "camera", st), 1.0)
        self.publish_for(self.scan_pub, lambda st: scan([1.0] * 5, st), 1.0)
        self.assertTrue(self.grid.wait_until(lambda g: g.at(3.55, 5.0) == 100 and g.at(6.05, 5.0) == 100, 10.0),
                        "lethal: %s" % self.lethal())
        rospy.wait_for_service("/costmap_node/clear_around_robot", 10.0)
        rospy.ServiceProxy("/costmap_node/clear_around_robot", Empty)()
        self.assertTrue(self.grid.wait_until(lambda g: g.at(6.05, 5.0) == 0, 10.0), "lethal: %s" % self.lethal())
        self.assertEqual(self.grid.at(3.55, 5.0), 100)
        rospy.ServiceProxy("/costmap_node/clear", Empty)()
        # Everything the sensor layers held is gone until new readings come.
        self.assertTrue(self.grid.wait_until(lambda g: g.data.count(100) == 0, 10.0),
                        "lethal after ~clear: %s" % self.lethal())

    def test_voxels_reach_rviz_topics_while_subscribed(self):
        # publish_voxel_map: the voxel layer offers ~voxel_layer/voxel_grid, voxel_markers (a cube list)
        # and voxel_cloud, built only while someone subscribes. Camera 0.5 m up at (2, 5): a point
        # (2.05, 0.05, -0.15) from it is at (4.05, 5.05, 0.35) in the map: column (40, 50), level 3 of
        # 0.1 m voxels, whose centre is (4.05, 5.05, 0.35).
        from costmap_layers.msg import VoxelMap
        from visualization_msgs.msg import Marker
        got = {"grid": None, "marker": None, "cloud": None}

        def keep(key):
            return lambda m: got.__setitem__(key, m)

        ns = "/costmap_node/voxel_layer/"
        subs = [rospy.Subscriber(ns + "voxel_grid", VoxelMap, keep("grid")),
                rospy.Subscriber(ns + "voxel_markers", Marker, keep("marker")),
                rospy.Subscriber(ns + "voxel_cloud", PointCloud2, keep("cloud"))]
        try:
            self.publish_for(self.vcloud_pub, lambda st: cloud([(2.05, 0.05, -0.15)], "camera", st), 1.0)
            deadline = rospy.Time.now() + rospy.Duration(10.0)
            marked = (1 << 19) | (1 << 3)
            while rospy.Time.now() < deadline and not (
                    got["marker"] and got["marker"].points and got["cloud"] and got["cloud"].width and got["grid"]
                    and got["grid"].data[50 * 100 + 40] & marked == marked):
                rospy.sleep(0.1)
            g, m, c = got["grid"], got["marker"], got["cloud"]
            self.assertTrue(g and m and m.points and c and c.width, "no voxels on the three topics: %s" % got)
            self.assertEqual((g.size_x, g.size_y, g.size_z), (100, 100, 10))
            self.assertEqual(g.header.frame_id, "map")
            self.assertAlmostEqual(g.resolutions.z, 0.1)
            self.assertEqual(len(g.data), 100 * 100)
            col = g.data[50 * 100 + 40]
            self.assertEqual(col & ((1 << 19) | (1 << 3)), (1 << 19) | (1 << 3), "column %x" % col)
            self.assertEqual(m.type, Marker.CUBE_LIST)
            self.assertEqual(m.header.frame_id, "map")
            self.assertEqual(len(m.points), 1, [(p.x, p.y, p.z) for p in m.points])
            p = m.points[0]
            self.assertAlmostEqual(p.x, 4.05, places=4)
            self.assertAlmostEqual(p.y, 5.05, places=4)
            self.assertAlmostEqual(p.z, 0.35, places=4)
            self.assertAlmostEqual(m.scale.z, 0.1, places=6)
            self.assertEqual(c.width, 1)
            self.assertEqual(c.header.frame_id, "map")
            x, y, z = struct.unpack_from("<fff", bytes(c.data), 0)
            self.assertAlmostEqual(x, 4.05, places=4)
            self.assertAlmostEqual(z, 0.35, places=4)
            # The obstacle layer was not asked to publish voxels: it offers no such topic.
            topics = [t for t, _ in rospy.get_published_topics()]
            self.assertIn(ns + "voxel_grid", topics)
            self.assertNotIn("/costmap_node/obstacle_layer/voxel_grid", topics)
        finally:
            for s in subs:
                s.unregister()


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "sensors", SensorsTest)
