#!/usr/bin/env python3
"""Node-level checks of two defect classes an outside attack found:
- a grid that grows and shrinks back between two publishes must never give a ~costmap_updates window
  that leaves the grid it refers to (the window of the big grid was read from the small one);
- a 1 kHz flood of every sensor for 10 s must delay neither ~costmap publishing nor a service reply by
  more than two update periods, and the dropped readings are reported.
Bounds are in the node's periods (update 2 Hz, publish 1 Hz), generous for a loaded 2-core machine."""
import os
import subprocess
import sys
import threading
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import PolygonStamped
from map_msgs.msg import OccupancyGridUpdate
from nav_msgs.msg import OccupancyGrid
from rosgraph_msgs.msg import Log
from std_srvs.srv import Empty

UPDATE_PERIOD = 0.5   # update_frequency 2 Hz
PUBLISH_PERIOD = 1.0  # publish_frequency 1 Hz
HERE = os.path.dirname(os.path.abspath(__file__))


def grid_msg(size):
    g = OccupancyGrid()
    g.header.frame_id = "map"
    g.header.stamp = rospy.Time.now()
    g.info.width = g.info.height = size
    g.info.resolution = 0.05
    g.info.origin.orientation.w = 1.0
    data = [0] * (size * size)
    for k in range(size):  # a wall along the bottom row
        data[k] = 100
    g.data = data
    return g


class FloodTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_flood")
        cls.lock = threading.Condition()
        cls.grid_size = None      # (width, height) of the latest full grid
        cls.bad_updates = []      # updates that do not fit the grid they refer to
        cls.publish_times = []    # arrival of every ~costmap or ~costmap_updates message
        cls.cycles = 0            # ~footprint messages: one per update cycle
        cls.logs = []

        def on_grid(m):
            with cls.lock:
                cls.grid_size = (m.info.width, m.info.height)
                cls.publish_times.append(time.monotonic())
                cls.lock.notify_all()

        def on_update(u):
            with cls.lock:
                cls.publish_times.append(time.monotonic())
                w, h = cls.grid_size or (0, 0)
                if (u.x < 0 or u.y < 0 or u.x + u.width > w or u.y + u.height > h
                        or len(u.data) != u.width * u.height):
                    cls.bad_updates.append((u.x, u.y, u.width, u.height, len(u.data), w, h))

        def on_footprint(_):
            with cls.lock:
                cls.cycles += 1
                cls.lock.notify_all()

        def on_log(m):
            if m.name == "/costmap_node" and m.level >= Log.WARN:
                with cls.lock:
                    cls.logs.append(m.msg)

        rospy.Subscriber("/costmap_node/costmap", OccupancyGrid, on_grid)
        rospy.Subscriber("/costmap_node/costmap_updates", OccupancyGridUpdate, on_update)
        rospy.Subscriber("/costmap_node/footprint", PolygonStamped, on_footprint)
        rospy.Subscriber("/rosout", Log, on_log)
        cls.map_pub = rospy.Publisher("/map", OccupancyGrid, queue_size=1)
        deadline = time.time() + 20
        while cls.map_pub.get_num_connections() == 0 and time.time() < deadline:
            time.sleep(0.05)
        cls.map_pub.publish(grid_msg(100))
        assert cls.wait_for(lambda: cls.grid_size == (100, 100), 40.0), "no 100x100 costmap to start from"

    @classmethod
    def wait_for(cls, predicate, timeout):
        deadline = time.monotonic() + timeout
        with cls.lock:
            while not predicate() and time.monotonic() < deadline:
                cls.lock.wait(0.1)
            return predicate()

    def wait_cycles(self, n, timeout=10.0):
        with self.lock:
            target = self.cycles + n
        self.assertTrue(self.wait_for(lambda: self.cycles >= target, timeout), "the update loop stopped")

    def test_a_new_subscriber_gets_the_current_grid_at_once(self):
        # costmap_2d's rule: each new ~costmap subscriber gets the current grid from the connect
        # callback, not a latched one from the last resize, and without waiting for a change. A new
        # subscriber is a new connection: another process (a second rospy subscriber in this process
        # would share this process's connection).
        self.map_pub.publish(grid_msg(100))
        self.assertTrue(self.wait_for(lambda: self.grid_size == (100, 100), 10 * PUBLISH_PERIOD))
        self.wait_cycles(2)
        for _ in range(2):
            out = subprocess.run(["rostopic", "echo", "-n", "1", "/costmap_node/costmap/info/width"],
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True,
                                 timeout=5 * PUBLISH_PERIOD + 10.0)
            self.assertEqual(out.stdout.split()[:1], ["100"], out.stderr)

    def test_resizes_between_publishes(self):
        for _ in range(5):
            self.map_pub.publish(grid_msg(1000))
            self.wait_cycles(1)
            self.map_pub.publish(grid_msg(100))
            self.wait_cycles(1)
        self.assertTrue(self.wait_for(lambda: self.grid_size == (100, 100), 10 * PUBLISH_PERIOD))
        self.wait_cycles(3)  # a few publishes after the last resize
        with self.lock:
            self.assertEqual(self.bad_updates, [], "updates that leave their grid (x, y, w, h, len, grid w, h)")

    def test_sensor_flood_delays_nothing(self):
        # A 50 m map: the range cones of the flood cover a quarter million cells each.
        self.map_pub.publish(grid_msg(1000))
        self.assertTrue(self.wait_for(lambda: self.grid_size == (1000, 1000), 10 * PUBLISH_PERIOD))
        with self.lock:
            first = len(self.publish_times)
        flood = subprocess.Popen([sys.executable, os.path.join(HERE, "flood_pub.py"), "10", "1000"],
                                 stdout=subprocess.PIPE, universal_newlines=True)
        rospy.wait_for_service("/costmap_node/clear", timeout=10.0)
        clear = rospy.ServiceProxy("/costmap_node/clear", Empty, persistent=True)
        replies = []
        start = time.monotonic()
        while flood.poll() is None and time.monotonic() - start < 60.0:
            t0 = time.monotonic()
            clear()
            replies.append(time.monotonic() - t0)
            time.sleep(0.2)
        out, _ = flood.communicate(timeout=30.0)
        end = time.monotonic()
        print(out, "service replies: %d, slowest %.3f s" % (len(replies), max(replies)))
        self.assertIn("flood_pub: sent", out)
        sent = int(out.split("sent ")[1].split()[0])
        self.assertGreaterEqual(sent, 5000, "the flood was not a flood: %s" % out)  # >= 500 Hz per topic
        self.assertGreater(len(replies), 10)
        self.assertLessEqual(max(replies), 2 * UPDATE_PERIOD, "a service reply waited behind the flood")
        with self.lock:
            times = [t for t in self.publish_times[first:] if t <= end] + [end]
        gaps = [b - a for a, b in zip([start] + times[:-1], times)]
        self.assertLessEqual(max(gaps), PUBLISH_PERIOD + 2 * UPDATE_PERIOD,
                             "~costmap publishing stalled during the flood: gaps %s" % sorted(gaps)[-3:])
        # What was dropped is said, not silent.
        with self.lock:
            said = [m for m in self.logs if "range readings arrive faster than the update loop" in m]
        self.assertTrue(said, "no warning about the dropped range readings")


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "flood", FloodTest)
