#!/usr/bin/env python3
"""TurtleBot3's burger move_base costmap files, unchanged, through move_base_costmaps.launch.

Expected grids are computed here from costmap_2d's rules, written out below, not from this package:
  - StaticLayer (trinary, lethal_cost_threshold 100, unknown_cost_value -1, track_unknown_space true,
    costmap_2d's default): 100 -> 254, -1 -> 255, 0 -> 0, written over the master.
  - ObstacleLayer (track_unknown_space false: its own grid starts FREE) combined by maximum over the
    whole update window: a master cell that is unknown (255) takes the layer's 0; scan hits are 254.
  - InflationLayer: cell radius (unsigned)(inflation_radius / resolution) (costmap_2d's cellDistance);
    a cell at distance d cells from the nearest lethal cell costs 254 at d = 0, 253 when d * res <=
    inscribed radius, else (uchar)(252 * exp(-cost_scaling_factor * (d * res - inscribed))); it is
    written when the master holds less, or holds 255 and the cost is >= 253.
  - The footprint is padded by footprint_padding 0.01 (costmap_2d's default): burger's x 0.041 becomes
    0.051, the inscribed radius.
"""
import math
import os
import queue
import signal
import struct
import subprocess
import sys
import threading
import unittest

import roslib.packages
import rospy
import rostest
from nav_msgs.msg import OccupancyGrid
from sensor_msgs.msg import LaserScan

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from grid_watch import GridWatcher, translate  # noqa: E402

ROBOT = (0.425, 1.825)
HIT_RANGE = 0.6
BEAMS = [-math.pi, -math.pi / 2, 0.0, math.pi / 2]
F32_005 = struct.unpack("f", struct.pack("f", 0.05))[0]  # the map's resolution as a float32 message carries it


def hits():
    return [(ROBOT[0] + HIT_RANGE * math.cos(a), ROBOT[1] + HIT_RANGE * math.sin(a)) for a in BEAMS]


def inflate(master, w, h, res, inscribed, radius, scaling):
    """costmap_2d's inflation written into master (a list of costs), from its lethal cells."""
    cell_radius = int(math.ceil(radius / res))  # costmap_2d's cellDistance(): ceil
    sources = [(k % w, k // w) for k, c in enumerate(master) if c == 254]
    best = [None] * (w * h)
    for sx, sy in sources:
        for y in range(max(0, sy - cell_radius), min(h, sy + cell_radius + 1)):
            for x in range(max(0, sx - cell_radius), min(w, sx + cell_radius + 1)):
                d2 = (x - sx) ** 2 + (y - sy) ** 2
                k = y * w + x
                if best[k] is None or d2 < best[k]:
                    best[k] = d2
    out = list(master)
    for k, d2 in enumerate(best):
        if d2 is None:
            continue
        d = math.sqrt(d2)
        if d > cell_radius:
            continue
        if d == 0:
            cost = 254
        elif d * res <= inscribed:
            cost = 253
        else:
            cost = int(252 * math.exp(-scaling * (d * res - inscribed)))
        old = out[k]
        if (old == 255 and cost >= 253) or (old != 255 and old < cost):
            out[k] = cost
    return out


def describe_diff(got, expected, w):
    bad = [k for k in range(len(expected)) if got[k] != expected[k]]
    return "%d cells differ, e.g. %s" % (
        len(bad), [((k % w, k // w), got[k], expected[k]) for k in bad[:10]])


class Output:
    """Reads a process' output lines on a thread, so that the test can wait for a line with a timeout."""

    def __init__(self, proc):
        self.proc = proc
        self.lines = []
        self.q = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        for raw in iter(self.proc.stdout.readline, b""):
            line = raw.decode(errors="replace")
            self.lines.append(line)
            self.q.put(line)

    def wait_for(self, text, timeout):
        deadline = rospy.get_time() + timeout
        while rospy.get_time() < deadline:
            if any(text in line for line in self.lines):
                return True
            try:
                self.q.get(timeout=0.5)
            except queue.Empty:
                pass
        return any(text in line for line in self.lines)

    def text(self):
        return "".join(self.lines)


def start_costmap(name, ns, extra=()):
    node = roslib.packages.find_node("costmap_layers", "costmap_node")
    # Line-buffered, so that the info lines (stdout) are all there when the node is stopped.
    proc = subprocess.Popen(["stdbuf", "-oL", node[0], "__name:=" + name, "__ns:=" + ns] + list(extra),
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    return proc, Output(proc)


def stop(proc):
    proc.send_signal(signal.SIGINT)  # roscpp shuts down cleanly on SIGINT
    try:
        proc.wait(timeout=20)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()


class MoveBaseConfigsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_move_base_configs")
        cls.map = rospy.wait_for_message("/map", OccupancyGrid, timeout=60)
        cls.global_ = GridWatcher("/move_base/global_costmap")
        cls.local = GridWatcher("/move_base/local_costmap")
        cls.scan_pub = rospy.Publisher("/scan", LaserScan, queue_size=5)
        cls.scan_timer = rospy.Timer(rospy.Duration(0.1), cls.publish_scan)

    @classmethod
    def publish_scan(cls, _event):
        scan = LaserScan()
        scan.header.stamp = rospy.Time.now()
        scan.header.frame_id = "base_scan"
        scan.angle_min = BEAMS[0]
        scan.angle_increment = math.pi / 2
        scan.angle_max = BEAMS[-1]
        scan.range_min = 0.12
        scan.range_max = 3.5
        scan.ranges = [HIT_RANGE] * len(BEAMS)
        cls.scan_pub.publish(scan)

    def static_master(self):
        """The master after the static layer: costmap_2d's interpretValue, trinary, unknown tracked."""
        return [254 if v == 100 else 255 if v == -1 else 0 for v in self.map.data]

    def test_global_costmap(self):
        info = self.map.info
        w, h = info.width, info.height
        master = self.static_master()
        # The obstacle layer's maximum over the whole first window: unknown cells become its FREE.
        master = [0 if c == 255 else c for c in master]
        for hx, hy in hits():
            i = int(math.floor((hx - info.origin.position.x) / F32_005))
            j = int(math.floor((hy - info.origin.position.y) / F32_005))
            master[j * w + i] = 254
        expected = [translate(c) for c in inflate(master, w, h, F32_005, 0.051, 1.0, 3.0)]
        ok = self.global_.wait_until(lambda g: g.data == expected, 90.0)
        got = self.global_.snapshot()
        self.assertIsNotNone(got, "no costmap on /move_base/global_costmap/costmap")
        self.assertEqual((self.global_.width, self.global_.height), (w, h))
        self.assertTrue(ok, describe_diff(got, expected, w))
        # The walls are lethal and inflated: a wall cell, and the 253 ring next to it.
        wall = self.map.data.index(100)
        self.assertEqual(got[wall], 100)
        # Unknown map cells: costmap_2d's StaticLayer keeps them unknown, its ObstacleLayer (tracking
        # off, as TurtleBot3's files leave it) then writes FREE over them: none is left.
        self.assertGreater(list(self.map.data).count(-1), 100000)
        self.assertEqual(got.count(-1), 0)
        # The four scan hits are marked.
        for hx, hy in hits():
            i = int(math.floor((hx + 10.0) / F32_005))
            j = int(math.floor((hy + 10.0) / F32_005))
            self.assertEqual(got[j * w + i], 100, (hx, hy))

    def test_local_costmap(self):
        # 3 m x 3 m at 0.05 m, rolling with the robot in odom: only the scan hits and their inflation.
        self.assertTrue(self.local.wait_until(lambda g: g.width == 60 and g.height == 60, 60.0))
        state = {}

        def matches(g):
            ox, oy = g.origin
            master = [0] * (60 * 60)
            for hx, hy in hits():
                i = int(math.floor((hx - ox) / 0.05 + 1e-6))
                j = int(math.floor((hy - oy) / 0.05 + 1e-6))
                if 0 <= i < 60 and 0 <= j < 60:
                    master[j * 60 + i] = 254
            state["expected"] = [translate(c) for c in inflate(master, 60, 60, 0.05, 0.051, 1.0, 3.0)]
            state["got"] = list(g.data)
            return state["got"] == state["expected"]

        ok = self.local.wait_until(matches, 60.0)
        self.assertTrue(ok, describe_diff(state["got"], state["expected"], 60))
        self.assertEqual(state["got"].count(100), 4)

    def test_converted_plugin_list_printed_once(self):
        watcher = GridWatcher("/probe/global_costmap")
        proc, out = start_costmap("global_costmap", "/probe", ["--move-base"])
        try:
            self.assertTrue(watcher.wait_until(lambda g: g.width == self.map.info.width, 90.0), out.text())
        finally:
            stop(proc)
        text = out.text()
        self.assertEqual(text.count("parameter \"plugins\" not provided"), 1, text)
        self.assertEqual(text.count("the same costmap as a plugin list"), 1, text)
        for line in ['  - {name: "static_layer", type: "costmap_2d::StaticLayer"}',
                     '  - {name: "obstacle_layer", type: "costmap_2d::ObstacleLayer"}',
                     '  - {name: "inflation_layer", type: "costmap_2d::InflationLayer"}',
                     '  obstacle_range: 3.0', '  raytrace_range: 3.5', '  observation_sources: "scan"',
                     '  cost_scaling_factor: 3.0', '  inflation_radius: 1.0']:
            self.assertEqual(text.count(line), 1, line + "\n" + text)
        self.assertIn("(costmap_2d::StaticLayer, loaded as costmap_layers/StaticLayer)", text)
        self.assertIn("holds a move_base file's `global_costmap:` section", text)
        # TurtleBot3's files hold no key this package does not know.
        self.assertNotIn("is not a parameter of costmap_layers", text)
        self.assertNotIn("is ignored", text)

    def test_unknown_keys_warned_once_with_nearest_name(self):
        watcher = GridWatcher("/probe/misspelt")
        proc, out = start_costmap("misspelt", "/probe", ["--move-base"])
        try:
            self.assertTrue(watcher.wait_until(lambda g: g.width == self.map.info.width, 90.0), out.text())
            got = watcher.snapshot()
        finally:
            stop(proc)
        text = out.text()
        for line in [
            "parameter 'inflaton_radius' in /probe/misspelt/inflation_layer is not a parameter of costmap_layers "
            "and is ignored (did you mean `inflation_radius`?)",
            "parameter 'robot_raduis' in /probe/misspelt is not a parameter of costmap_layers and is ignored "
            "(did you mean `robot_radius`?)",
            "parameter 'footprint_topic' in /probe/misspelt is ignored: costmap_2d subscribes to it",
        ]:
            self.assertEqual(text.count(line), 1, line + "\n" + text)
        # The static layer keeps unknown cells unknown (costmap_2d's StaticLayer default), and the
        # inflation layer runs with its defaults (the radius was misspelt): 0.55 m, factor 10, over
        # the robot_radius default 0.46 m padded by 0.01 m. The expected grid of just those rules:
        w, h = self.map.info.width, self.map.info.height
        # costmap_2d's makeFootprintFromRadius: 16 points on the circle; padding moves each point by
        # 0.01 along x and y away from the centre; the inscribed radius is the nearest edge.
        pts = []
        for k in range(16):
            a = k * 2 * math.pi / 16
            x, y = 0.46 * math.cos(a), 0.46 * math.sin(a)
            x += math.copysign(0.01, x) if x != 0 else 0.0
            y += math.copysign(0.01, y) if y != 0 else 0.0
            pts.append((x, y))

        def seg_dist(p, q):
            (x1, y1), (x2, y2) = p, q
            dx, dy = x2 - x1, y2 - y1
            t = max(0.0, min(1.0, -(x1 * dx + y1 * dy) / (dx * dx + dy * dy)))
            return math.hypot(x1 + t * dx, y1 + t * dy)

        inscribed = min(seg_dist(pts[k], pts[(k + 1) % 16]) for k in range(16))
        expected = [translate(c) for c in inflate(self.static_master(), w, h, F32_005, inscribed, 0.55, 10.0)]
        self.assertEqual(got, expected, describe_diff(got, expected, w))
        unknown = got.count(-1)
        print("misspelt probe: %d unknown cells of %d unknown in the map" % (unknown, list(self.map.data).count(-1)))
        self.assertGreater(unknown, 100000)


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "move_base_configs", MoveBaseConfigsTest)
