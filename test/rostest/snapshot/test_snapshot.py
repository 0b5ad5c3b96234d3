#!/usr/bin/env python3
"""costmap_snapshot's two waits are on the wall clock: ~timeout bounds the wait for the first grid only
(a grid that came keeps the tool going for its ~wait, however long that is), and under /use_sim_time
with no /clock the tool neither hangs nor waits forever."""
import os
import subprocess
import tempfile
import time
import unittest

import rospy
import rostest
from nav_msgs.msg import OccupancyGrid

TOPIC = "/snapshot_test/grid"


class SnapshotTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_snapshot")
        cls.pub = rospy.Publisher(TOPIC, OccupancyGrid, queue_size=1, latch=True)
        grid = OccupancyGrid()
        grid.header.frame_id = "map"
        grid.info.resolution = 0.1
        grid.info.width = 4
        grid.info.height = 3
        grid.info.origin.orientation.w = 1.0
        grid.data = [0, 100, -1, 50] * 3
        cls.pub.publish(grid)
        cls.dir = tempfile.mkdtemp(prefix="snapshot_test_")

    def run_tool(self, name, wait, timeout, topic=TOPIC, limit=30.0):
        """Runs costmap_snapshot; returns (exit code, seconds taken, the PNG's path, its output)."""
        out = os.path.join(self.dir, name + ".png")
        start = time.monotonic()
        p = subprocess.run(
            ["rosrun", "costmap_layers", "costmap_snapshot", "__name:=" + name, "_topic:=" + topic,
             "_output:=" + out, "_wait:=%g" % wait, "_timeout:=%g" % timeout],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=limit, check=False)
        return p.returncode, time.monotonic() - start, out, p.stdout.decode(errors="replace")

    def test_1_wait_longer_than_timeout_keeps_the_grid(self):
        # The latched grid comes within a second or two of the start; the timeout runs out during ~wait.
        rc, took, out, text = self.run_tool("snap_real", wait=8.0, timeout=5.0)
        self.assertEqual(rc, 0, "a grid came within the timeout, yet: " + text)
        self.assertTrue(os.path.getsize(out) > 0, text)
        self.assertGreaterEqual(took, 8.0, "the tool did not wait ~wait after the first grid")

    def test_2_no_grid_times_out(self):
        rc, took, _, text = self.run_tool("snap_none", wait=0.0, timeout=1.0, topic="/snapshot_test/nothing")
        # Nothing on this topic: the tool gives up after ~timeout with one error naming the topic.
        self.assertNotEqual(rc, 0)
        self.assertLess(took, 20.0)
        self.assertIn("no costmap on", text)

    def test_3_sim_time_without_clock(self):
        rospy.set_param("/use_sim_time", True)
        try:
            rc, took, out, text = self.run_tool("snap_sim", wait=1.0, timeout=10.0)
        except subprocess.TimeoutExpired:
            self.fail("costmap_snapshot hung under /use_sim_time with no /clock")
        finally:
            rospy.set_param("/use_sim_time", False)
        self.assertEqual(rc, 0, text)
        self.assertTrue(os.path.getsize(out) > 0, text)
        self.assertGreaterEqual(took, 1.0)


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "snapshot", SnapshotTest)
