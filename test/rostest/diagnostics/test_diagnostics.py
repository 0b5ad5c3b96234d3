#!/usr/bin/env python3
"""costmap_node's /diagnostics: one status for the costmap and one per layer. A map that never
arrives is an ERROR naming its topic, a filter without a mask a WARN naming its topic, a scan source
that is late a WARN naming its topic; each turns OK once its input arrives."""
import threading
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from nav_msgs.msg import OccupancyGrid
from sensor_msgs.msg import LaserScan

NODE = "costmap_node"
LEVEL = {0: "OK", 1: "WARN", 2: "ERROR", 3: "STALE"}


class DiagnosticsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_diagnostics")
        cls.lock = threading.Lock()
        cls.latest = {}
        rospy.Subscriber("/diagnostics", DiagnosticArray, cls.on_diagnostics, queue_size=50)

    @classmethod
    def on_diagnostics(cls, msg):
        with cls.lock:
            for s in msg.status:
                cls.latest[s.name] = s

    def status(self, task):
        with self.lock:
            return self.latest.get(NODE + ": " + task)

    def wait_for(self, task, predicate, timeout, what):
        """Waits until the named status exists and satisfies predicate; fails saying what was seen."""
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        while not rospy.is_shutdown() and rospy.Time.now() < deadline:
            s = self.status(task)
            if s is not None and predicate(s):
                return s
            rospy.sleep(0.05)
        s = self.status(task)
        seen = "nothing" if s is None else "%s: %s %s" % (LEVEL.get(s.level), s.message,
                                                          {kv.key: kv.value for kv in s.values})
        self.fail("%s: %s (last seen: %s)" % (task, what, seen))

    def test_missing_inputs_then_ok(self):
        # Every status is there, each missing input named.
        costmap = self.wait_for("costmap", lambda s: any(kv.key == "cycles" and int(kv.value) > 0 for kv in s.values),
                                30.0, "costmap status with update cycles")
        self.assertEqual(costmap.hardware_id, "/costmap_node")
        static = self.wait_for("layer static_layer", lambda s: s.level == DiagnosticStatus.ERROR, 10.0,
                               "ERROR while no map arrived")
        self.assertIn("no map yet on /diag_map", static.message)
        keepout = self.wait_for("layer keepout", lambda s: s.level == DiagnosticStatus.WARN, 10.0,
                                "WARN while no mask arrived")
        self.assertIn("no mask yet on /diag_mask", keepout.message)
        obstacles = self.wait_for("layer obstacles", lambda s: s.level == DiagnosticStatus.WARN, 10.0,
                                  "WARN for a late source")
        self.assertIn("/diag_scan", obstacles.message)
        self.assertIn("late", obstacles.message)
        self.wait_for("layer inflation", lambda s: s.level == DiagnosticStatus.OK, 10.0, "OK")
        self.wait_for("costmap", lambda s: s.level >= DiagnosticStatus.WARN and "static_layer" in s.message, 10.0,
                      "WARN naming the layers that are not current")

        # The map arrives: the static layer turns OK and says so, with what arrived on its topic.
        map_pub = rospy.Publisher("/diag_map", OccupancyGrid, queue_size=1, latch=True)
        grid = OccupancyGrid()
        grid.header.frame_id = "map"
        grid.header.stamp = rospy.Time.now()
        grid.info.resolution = 0.1
        grid.info.width, grid.info.height = 40, 40
        grid.info.origin.orientation.w = 1.0
        grid.data = [0] * 1600
        map_pub.publish(grid)
        static = self.wait_for("layer static_layer", lambda s: s.level == DiagnosticStatus.OK, 20.0,
                               "OK once the map arrived")
        values = {kv.key: kv.value for kv in static.values}
        self.assertEqual(values.get("maps accepted"), "1")
        self.assertIn("1 message", values.get("received on /diag_map", ""))

        # Scans at 10 Hz: the source is current again.
        scan_pub = rospy.Publisher("/diag_scan", LaserScan, queue_size=5)
        stop = threading.Event()

        def publish_scans():
            rate = rospy.Rate(10)
            while not stop.is_set() and not rospy.is_shutdown():
                s = LaserScan()
                s.header.frame_id = "laser"
                s.header.stamp = rospy.Time.now()
                s.angle_min, s.angle_increment = -0.2, 0.1
                s.angle_max = s.angle_min + 4 * s.angle_increment
                s.range_min, s.range_max = 0.05, 6.0
                s.ranges = [1.0] * 5
                scan_pub.publish(s)
                rate.sleep()

        t = threading.Thread(target=publish_scans)
        t.start()
        try:
            obstacles = self.wait_for("layer obstacles", lambda s: s.level == DiagnosticStatus.OK, 20.0,
                                      "OK once scans arrive")
            self.assertIn("accepted", {kv.key: kv.value for kv in obstacles.values}.get("source scan (/diag_scan)", ""))
            self.wait_for("costmap", lambda s: "static_layer" not in s.message and "obstacles" not in s.message,
                          20.0, "no layer named as not current")
        finally:
            stop.set()
            t.join()


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "diagnostics", DiagnosticsTest)
