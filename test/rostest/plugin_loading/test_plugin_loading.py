#!/usr/bin/env python3
"""Plugin loading through pluginlib from a params YAML, checked on the published costmaps:
two GradientLayer instances with their own parameters, a KeepoutFilter, and the clear error for an
unknown plugin type. Expected values are computed here from the documented formulas."""
import os
import subprocess
import sys
import unittest

import rospy
import rostest
import roslib.packages
from nav_msgs.msg import OccupancyGrid

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from grid_watch import GridWatcher, translate  # noqa: E402

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
        self.a.wait_until(lambda g: g.data == expected, 30.0)
        got = self.a.snapshot()
        self.assertIsNotNone(got, "no costmap published on /costmap_a/costmap")
        self.assertEqual(got, expected)
        # The keepout block really is lethal and the gradient starts at 254 in column 0.
        self.assertEqual(got[6 * W + 12], 100)
        self.assertEqual(got[0], 100)

    def test_other_instance_other_parameters(self):
        row = gradient_row(W, 3, 60)
        self.assertEqual(row[:6], [254, 194, 134, 74, 14, 254])
        expected = [translate(c) for _ in range(H) for c in row]
        self.b.wait_until(lambda g: g.data == expected, 30.0)
        got = self.b.snapshot()
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
