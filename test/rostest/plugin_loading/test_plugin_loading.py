#!/usr/bin/env python3
"""Plugin loading through pluginlib from a params YAML, checked on the published costmaps:
two GradientLayer instances with their own parameters, a KeepoutFilter, and the clear error for an
unknown plugin type. Expected values are computed here from the documented formulas."""
import os
import subprocess
import threading
import unittest

import rospy
import rostest
import roslib.packages
from map_msgs.msg import OccupancyGridUpdate
from nav_msgs.msg import OccupancyGrid

W, H = 30, 20


def c_mod(a, b):
    """C's % (truncating toward zero), as the tutorial's int arithmetic computes it."""
    r = abs(a) % b
    return r if a >= 0 else -r


def gradient_row(width, size, factor):
    row, k = [], 0
    for _ in range(width):
        row.append(c_mod(254 - k * factor, 255) & 0xFF)
        k = k + 1 if k <= size else 0
    return row


def translate(cost):
    """costmap_2d's cost -> OccupancyGrid value."""
    if cost == 0:
        return 0
    if cost == 253:
        return 99
    if cost == 254:
        return 100
    if cost == 255:
        return -1
    return 1 + (97 * (cost - 1)) // 251


class GridWatcher:
    """Keeps the latest costmap, applying ~costmap_updates to it."""

    def __init__(self, ns):
        self.lock = threading.Condition()
        self.grid = None
        rospy.Subscriber(ns + "/costmap", OccupancyGrid, self.on_grid)
        rospy.Subscriber(ns + "/costmap_updates", OccupancyGridUpdate, self.on_update)

    def on_grid(self, msg):
        with self.lock:
            self.grid = list(msg.data)
            self.width = msg.info.width
            self.height = msg.info.height
            self.lock.notify_all()

    def on_update(self, msg):
        with self.lock:
            if self.grid is None:
                return
            for j in range(msg.height):
                for i in range(msg.width):
                    self.grid[(msg.y + j) * self.width + msg.x + i] = msg.data[j * msg.width + i]
            self.lock.notify_all()

    def wait_for(self, expected, timeout):
        """Waits until the grid equals expected (updates arrive as the node cycles); returns the last grid."""
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        with self.lock:
            while not rospy.is_shutdown() and rospy.Time.now() < deadline:
                if self.grid == expected:
                    break
                self.lock.wait(0.5)
            return None if self.grid is None else list(self.grid)


class PluginLoadingTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_plugin_loading")
        cls.a = GridWatcher("/costmap_a")
        cls.b = GridWatcher("/costmap_b")
        cls.mask_pub = rospy.Publisher("/test_keepout_mask", OccupancyGrid, queue_size=1, latch=True)
        mask = OccupancyGrid()
        mask.header.frame_id = "map"
        mask.info.resolution = 0.1
        mask.info.width, mask.info.height = W, H
        mask.info.origin.orientation.w = 1.0
        data = [-1] * (W * H)
        for j in range(5, 10):
            for i in range(10, 15):
                data[j * W + i] = 100  # a virtual wall
            for i in range(20, 25):
                data[j * W + i] = 50  # a costly area: cost round(50 * 254 / 100) = 127
            data[j * W + 2] = 0  # no effect
        mask.data = data
        cls.mask_pub.publish(mask)

    def test_two_instances_and_a_filter(self):
        row = gradient_row(W, 20, 10)
        expected = []
        for j in range(H):
            for i in range(W):
                cost = row[i]
                if 5 <= j < 10 and 10 <= i < 15:
                    cost = max(cost, 254)
                if 5 <= j < 10 and 20 <= i < 25:
                    cost = max(cost, 127)
                expected.append(translate(cost))
        got = self.a.wait_for(expected, 30.0)
        self.assertIsNotNone(got, "no costmap published on /costmap_a/costmap")
        self.assertEqual(got, expected)
        # The keepout block really is lethal and the gradient starts at 254 in column 0.
        self.assertEqual(got[6 * W + 12], 100)
        self.assertEqual(got[0], 100)

    def test_other_instance_other_parameters(self):
        row = gradient_row(W, 3, 60)
        self.assertEqual(row[:6], [254, 194, 134, 74, 14, 254])
        expected = [translate(c) for _ in range(H) for c in row]
        got = self.b.wait_for(expected, 30.0)
        self.assertIsNotNone(got, "no costmap published on /costmap_b/costmap")
        self.assertEqual(got, expected)

    def test_unknown_type_stops_start_up(self):
        rospy.set_param("/bad_costmap/plugins", [
            {"name": "gradient", "type": "costmap_layers/GradientLayer"},
            {"name": "mystery", "type": "costmap_layers/NoSuchLayer"},
        ])
        node = roslib.packages.find_node("costmap_layers", "costmap_node")
        self.assertTrue(node, "costmap_node not found")
        env = dict(os.environ)
        proc = subprocess.run([node[0], "__name:=bad_costmap"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              timeout=60, env=env)
        out = proc.stdout.decode(errors="replace")
        self.assertNotEqual(proc.returncode, 0, out)
        self.assertIn("unknown plugin type 'costmap_layers/NoSuchLayer'", out)
        self.assertIn("available types:", out)
        self.assertIn("costmap_layers/GradientLayer", out)
        self.assertIn("mystery", out)
        # One clear error, not a cascade.
        self.assertEqual(out.count("NoSuchLayer"), 1, out)


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "plugin_loading", PluginLoadingTest)
