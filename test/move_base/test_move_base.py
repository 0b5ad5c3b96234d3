#!/usr/bin/env python3
"""costmap_layers' plugins inside a real move_base (see move_base.test):
- navfn's plan (move_base's make_plan) goes around the keepout band, and straight through it once the
  bridged KeepoutFilter is switched off with its toggle service;
- the bridged SpeedFilter publishes the speed zone's limit on /max_speed from move_base's costmap;
- the bridged GradientLayer's ramps appear in move_base's published local costmap, and the bridged
  DenoiseLayer after it clears the ramps' lethal columns (groups smaller than its minimal_group_size);
- move_base's global costmap equals costmap_node's with the same layers on the same inputs, cell by cell.
Each case waits on arrivals with a deadline, never on a fixed sleep."""
import math
import os
import shlex
import subprocess
import sys
import threading
import unittest

import dynamic_reconfigure.client
import roslib.packages
import rospkg
import rospy
import rostest
from costmap_layers.msg import MaxSpeed
from geometry_msgs.msg import Point32, Polygon
from nav_msgs.msg import OccupancyGrid
from nav_msgs.srv import GetPlan
from std_srvs.srv import Empty, SetBool

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "rostest"))
from grid_watch import ErrorLog, GridWatcher, translate  # noqa: E402
from grid_watch import occupancy_grid as grid  # noqa: E402
from grid_watch import map_pose as pose  # noqa: E402

START = (1.0, 1.0)
GOAL = (5.0, 1.0)
# The keepout band of keepout.pgm (make_maps.py): x in [2.8, 3.2) m, y in [0, 3.0) m.
BAND = (2.8, 3.2, 0.0, 3.0)
LETHAL = 100  # cost 254 as published


def in_band(x, y, margin=0.0):
    return BAND[0] - margin <= x < BAND[1] + margin and BAND[2] <= y < BAND[3] + margin


def room(width, height):
    """A room as mask_server publishes room.pgm (make_maps.py): walls two cells thick = 100, free = 0."""
    return grid(width, height, 0.05, [100 if i < 2 or j < 2 or i >= width - 2 or j >= height - 2 else 0
                                      for j in range(height) for i in range(width)])


def length(poses):
    return sum(
        math.hypot(b.pose.position.x - a.pose.position.x, b.pose.position.y - a.pose.position.y)
        for a, b in zip(poses, poses[1:])
    )


def move_base_stderr():
    """All move_base wrote to stderr so far, from its first line (copied by stderr_to_log.sh into the log
    directory of this run)."""
    path = os.path.join(rospkg.get_log_dir(), rospy.get_param("/run_id"), "move_base-stderr.log")
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read()


class MoveBaseTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_move_base")
        cls.global_grid = GridWatcher("/move_base/global_costmap")
        cls.local_grid = GridWatcher("/move_base/local_costmap")
        cls.twin = GridWatcher("/twin")
        cls.speed_cond = threading.Condition()
        cls.speeds = []
        rospy.Subscriber("/max_speed", MaxSpeed, cls._on_speed)
        rospy.wait_for_service("/move_base/make_plan", timeout=120.0)
        rospy.wait_for_service("/move_base/global_costmap/keepout/toggle", timeout=60.0)
        cls.make_plan = rospy.ServiceProxy("/move_base/make_plan", GetPlan)
        cls.clear_costmaps = rospy.ServiceProxy("/move_base/clear_costmaps", Empty)
        cls.map_pub = rospy.Publisher("/map", OccupancyGrid, queue_size=1, latch=True)
        cls.toggle = rospy.ServiceProxy("/move_base/global_costmap/keepout/toggle", SetBool)
        cls.move_base_errors = ErrorLog("/move_base")  # the error lines move_base writes to /rosout

    @classmethod
    def _on_speed(cls, msg):
        with cls.speed_cond:
            cls.speeds.append(msg.max_speed)
            cls.speed_cond.notify_all()

    def set_keepout(self, on):
        self.assertTrue(self.toggle(on).success)
        centre = (3.0, 1.0)
        ok = self.global_grid.wait_until(
            lambda g: g.width == 120 and (g.at(*centre) == LETHAL) == on, timeout=30.0)
        self.assertTrue(ok, "the band centre never became %s in move_base's costmap" % ("lethal" if on else "free"))

    def plan(self, goes_around, timeout=30.0):
        """navfn's plan from START to GOAL once it goes around the band (or, goes_around False, through it):
        the costmap the planner reads is redrawn by move_base's update thread, after the published one
        said so or after a clear; asked again on each new costmap publication until the deadline."""
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        while True:
            seen = self.global_grid.count
            res = self.make_plan(start=pose(*START), goal=pose(*GOAL), tolerance=0.0)
            poses = res.plan.poses
            crosses = any(in_band(p.pose.position.x, p.pose.position.y) for p in poses)
            if len(poses) > 2 and crosses != goes_around:
                return poses
            if rospy.Time.now() > deadline:
                self.fail("navfn's plan %s the band: %d poses, max y %s" % (
                    "crosses" if crosses else "avoids", len(poses),
                    max((p.pose.position.y for p in poses), default=None)))
            self.global_grid.wait_until(lambda g: g.count > seen, timeout=1.0)

    def test_plan_goes_around_the_zone_and_straight_without_it(self):
        try:
            self.set_keepout(True)
            around = self.plan(goes_around=True)
            self.assertGreater(max(p.pose.position.y for p in around), BAND[3],
                               "the plan does not pass above the band, where the gap is")
            # It crosses x = 3.0 at y >= 3.0: by the triangle inequality no such path is shorter than this.
            self.assertGreaterEqual(length(around), 2 * math.hypot(3.0 - START[0], BAND[3] - START[1]))

            self.set_keepout(False)
            straight = self.plan(goes_around=False)
            self.assertLess(length(straight), 4.0 * 1.1)
            self.assertLess(max(abs(p.pose.position.y - START[1]) for p in straight), 0.3)
        finally:
            self.set_keepout(True)

    def test_speed_filter_publishes_the_zone_limit(self):
        # speed.pgm: 30 around the start; nav2 mode limit = base + multiplier * v = 0.0 + 0.01 * 30.
        with self.speed_cond:
            ok = self.speed_cond.wait_for(lambda: any(abs(s - 0.3) < 1e-9 for s in self.speeds), timeout=60.0)
        self.assertTrue(ok, "no /max_speed 0.3 from move_base's SpeedFilter; seen %s" % self.speeds)

    def test_zone_parameter_filter_slows_move_base_own_planner(self):
        # The robot starts in the zone of state 30: the bridged ZoneParameterFilter sets
        # /move_base/DWAPlannerROS max_vel_x to 0.3 through dynamic_reconfigure, from inside move_base.
        from std_msgs.msg import UInt8
        state = rospy.wait_for_message("/zone_state", UInt8, timeout=60.0)
        deadline = rospy.Time.now() + rospy.Duration(30.0)
        while state.data != 30 and rospy.Time.now() < deadline:
            state = rospy.wait_for_message("/zone_state", UInt8, timeout=30.0)
        self.assertEqual(state.data, 30)
        client = dynamic_reconfigure.client.Client("/move_base/DWAPlannerROS", timeout=30.0)
        value = None
        while rospy.Time.now() < deadline:
            value = client.get_configuration(timeout=5.0)["max_vel_x"]
            if abs(value - 0.3) < 1e-9:
                break
            rospy.wait_for_message("/move_base/DWAPlannerROS/parameter_updates", rospy.AnyMsg, timeout=5.0)
        self.assertAlmostEqual(value, 0.3, places=9)

    def test_gradient_pattern_denoised_in_the_local_costmap(self):
        # Along every row from the window's first column: cost (254 - k * 10) % 255, k = i mod 22, from the
        # bridged GradientLayer; then the bridged DenoiseLayer clears each lethal column (k = 0: a group
        # of 19 or 20 cells, fewer than its minimal_group_size 25) to free space.
        def expected(i):
            return 0 if i % 22 == 0 else translate((254 - (i % 22) * 10) % 255)

        def matches(g):
            # 2.0 m x 1.0 m at 0.05 m (costmap_2d truncates width / resolution)
            return g.width == 40 and g.height in (19, 20) and all(
                g.data[j * g.width + i] == expected(i) for j in range(g.height) for i in range(g.width))

        ok = self.local_grid.wait_until(matches, timeout=60.0)
        row = self.local_grid.snapshot()[:40] if self.local_grid.snapshot() else None
        self.assertTrue(ok, "the local costmap's rows are not the gradient: first row %s" % row)

    def assert_same_grids(self, width, height):
        def ready(g):
            return g.width == width and g.height == height and g.at(3.0, 1.0) == LETHAL and g.at(1.0, 1.0) == 0

        self.assertTrue(self.global_grid.wait_until(ready, timeout=60.0), "move_base never drew the map and the zone")
        self.assertTrue(self.twin.wait_until(ready, timeout=60.0), "costmap_node never drew the map and the zone")
        mb = self.global_grid.snapshot()
        tw = self.twin.snapshot()
        self.assertEqual((self.global_grid.width, self.global_grid.height), (self.twin.width, self.twin.height))
        self.assertEqual(self.global_grid.origin, self.twin.origin)
        diff = [k for k in range(len(mb)) if mb[k] != tw[k]]
        self.assertEqual(diff[:10], [], "%d cells differ, e.g. (index, move_base, costmap_node) %s" %
                         (len(diff), [(k, mb[k], tw[k]) for k in diff[:10]]))
        return mb

    def test_clear_costmaps_keeps_the_map_and_the_zone(self):
        self.set_keepout(True)
        seen = self.global_grid.count
        self.clear_costmaps()
        # costmap_2d empties the master and resets every layer; the bridged layers draw everything again,
        # and the redrawn costmap is published.
        self.assertTrue(self.global_grid.wait_until(lambda g: g.count > seen, timeout=30.0),
                        "no costmap published after clear_costmaps")
        self.assert_same_grids(120, 80)
        self.plan(goes_around=True)

    def test_a_map_of_another_size_resizes_move_base_and_the_zone_follows(self):
        self.set_keepout(True)
        try:
            self.map_pub.publish(room(140, 90))
            mb = self.assert_same_grids(140, 90)
            # The new walls are drawn where the new map has them, in the resized grid.
            self.assertEqual(mb[89 * 140 + 139], LETHAL)
            self.assertEqual(self.global_grid.at(6.5, 4.0), 0)
        finally:
            self.map_pub.publish(room(120, 80))
            self.assertTrue(self.global_grid.wait_until(lambda g: g.width == 120 and g.height == 80, timeout=60.0))

    def test_same_grid_as_costmap_node(self):
        self.set_keepout(True)
        mb = self.assert_same_grids(120, 80)
        # Not a trivial grid: walls, the zone, inflation ramps and free space are all there.
        self.assertIn(LETHAL, mb)
        self.assertIn(0, mb)
        self.assertTrue(any(0 < v < 99 for v in mb), "no inflation ramp in the grid")


    def test_dynamic_reconfigure_of_a_bridged_layer_redraws_move_base_costmap(self):
        # The cell centred 0.375 m left of the band: outside a 0.3 m inflation, inside a 0.4 m one.
        probe = (2.425, 1.025)
        self.set_keepout(True)
        client = dynamic_reconfigure.client.Client("/move_base/global_costmap/inflation", timeout=30.0)
        try:
            self.assertTrue(self.global_grid.wait_until(lambda g: g.width == 120 and g.at(*probe) == 0, 30.0))
            client.update_configuration({"inflation_radius": 0.4})
            self.assertTrue(self.global_grid.wait_until(lambda g: g.at(*probe) > 0, timeout=30.0),
                            "inflation_radius 0.4 set through dynamic_reconfigure never reached the costmap")
        finally:
            client.update_configuration({"inflation_radius": 0.3})
        self.assertTrue(self.global_grid.wait_until(lambda g: g.at(*probe) == 0, timeout=30.0))
        self.assert_same_grids(120, 80)

    def test_malformed_maps_and_masks_leave_move_base_costmap_as_it_was(self):
        # Malformed grids on the map and both mask topics reach the bridged StaticLayer, KeepoutFilter,
        # SpeedFilter and ZoneParameterFilter inside move_base's process (costmap_node, the twin, gets
        # them too): each is named under its stable key and dropped, and both costmaps keep the last good
        # map and masks.
        self.set_keepout(True)
        bad = [
            grid(10, 10, 0.05, [0] * 7),  # truncated data
            grid(10, 10, 0.05, [0] * 1000),  # oversized data
            grid(10, 10, 0.0, [0] * 100),  # zero resolution
            grid(100000, 100000, 0.05, [0] * 16),  # would need 10 G cells
            grid(0, 10, 0.05, []),  # zero width
        ]
        # topic: (subscribing processes, [(key under /move_base/global_costmap/, values)]). The truncated and
        # the oversized grid share the key ".../data" and its throttle period: either one may be the one
        # named (a subscriber queue of 1 drops some of a burst).
        expected = {
            "/map": (2, [("static/map/data", ()), ("static/map/info.resolution", ("0",)),
                         ("static/map/info.cells", ("100000x100000",))]),
            "/keepout_mask": (2, [("keepout/mask/data", ())]),
            "/speed_mask": (1, [("speed/mask/data", ()), ("zones/mask/data", ())]),  # move_base only
        }
        for topic, (processes, keys) in expected.items():
            pub = rospy.Publisher(topic, OccupancyGrid, queue_size=10)
            try:
                # move_base (and the twin) connected before the first message.
                deadline = rospy.Time.now() + rospy.Duration(30.0)
                while pub.get_num_connections() < processes and rospy.Time.now() < deadline:
                    rospy.sleep(0.05)  # polled with a deadline, not a fixed wait
                self.assertGreaterEqual(pub.get_num_connections(), processes, "subscribers missing on " + topic)
                for key, values in keys:
                    logged = []
                    while not logged and rospy.Time.now() < deadline:
                        for m in bad:  # again until named: a subscriber queue may drop a message
                            m.header.stamp = rospy.Time.now()
                            pub.publish(m)
                        logged = self.move_base_errors.wait("/move_base/global_costmap/" + key, values, timeout=1.0)
                    self.assertTrue(logged, "move_base logged nothing under [/move_base/global_costmap/%s] with %s;"
                                    " last lines:\n%s" % (key, values, "\n".join(self.move_base_errors.lines[-20:])))
            finally:
                pub.unregister()
        # Still the good state, and still planning on it.
        self.assert_same_grids(120, 80)
        self.assertEqual(self.global_grid.at(3.0, 1.0), LETHAL)
        self.plan(goes_around=True)

    def test_a_bad_parameter_stops_move_base_naming_it(self):
        # A second move_base whose bridged inflation layer has a negative radius: like costmap_node, it
        # stops at start-up with a fatal error naming the parameter and the value (rather than planning
        # on a costmap without the layer).
        ns = "/bad_move_base"
        rospy.set_param(ns, {
            "base_global_planner": "navfn/NavfnROS",
            "base_local_planner": "dwa_local_planner/DWAPlannerROS",
            "global_costmap": {
                "global_frame": "map", "robot_base_frame": "base_link", "robot_radius": 0.1,
                "plugins": [{"name": "inflation", "type": "costmap_layers::move_base::InflationLayer"}],
                "inflation": {"inflation_radius": -1.0},
            },
            "local_costmap": {"global_frame": "map", "robot_base_frame": "base_link", "plugins": []},
        })
        # The program itself (not rosrun's shell script), behind the prefix move_base.test puts before
        # move_base: scripts/dev/sanitize_package.sh sets it to preload the sanitizer runtime for the
        # instrumented plugins; empty otherwise.
        prefix = shlex.split(os.environ.get("COSTMAP_LAYERS_MOVE_BASE_PREFIX", ""))
        program = roslib.packages.find_node("move_base", "move_base")
        self.assertTrue(program, "move_base not found")
        proc = subprocess.run(prefix + [program[0], "__name:=bad_move_base"],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=120, text=True)
        self.assertNotEqual(proc.returncode, 0, "move_base kept running with a negative inflation_radius")
        fatal = [line for line in proc.stdout.splitlines()
                 if "/bad_move_base/global_costmap/inflation" in line and "inflation_radius" in line]
        self.assertTrue(fatal, "no error naming the parameter; move_base printed:\n" + proc.stdout[-3000:])
        self.assertIn("-1", fatal[0])

    def test_zz_a_footprint_of_nan_leaves_the_bridged_layers_footprint(self):
        # costmap_2d hands the footprint its `footprint` topic carries (geometry_msgs/Polygon, float32)
        # to every plugin as it is. NaN vertices would make every inflated cell within inflation_radius
        # inscribed (253) and switch a keepout filter's escape mode on anywhere: the bridge names the
        # vertex and keeps the last good footprint. (Named to run last: costmap_2d itself keeps the
        # footprint it was handed.)
        self.assert_same_grids(120, 80)
        # The footprint costmap_2d set at start-up was taken without a word: nothing about a footprint in
        # what move_base wrote to stderr from its first line on (a /rosout subscriber may connect later).
        start_up = move_base_stderr()
        self.assertEqual([line for line in start_up.splitlines() if "/footprint]" in line], [])
        nan = float("nan")
        pub = rospy.Publisher("/move_base/global_costmap/footprint", Polygon, queue_size=1)
        try:
            deadline = rospy.Time.now() + rospy.Duration(30.0)
            while pub.get_num_connections() < 1 and rospy.Time.now() < deadline:
                rospy.sleep(0.05)  # polled with a deadline, not a fixed wait
            self.assertGreaterEqual(pub.get_num_connections(), 1, "move_base does not read its footprint topic")
            # Several times (a subscriber queue of 1 may drop one); then several costmap publications.
            for _ in range(3):
                seen = self.global_grid.count
                pub.publish(Polygon([Point32(nan, nan, 0.0)] * 4))
                self.assertTrue(self.global_grid.wait_until(lambda g: g.count >= seen + 3, timeout=30.0))
        finally:
            pub.unregister()
        # The inflation is still the twin's, cell for cell (NaN taken in would make it 253 out to 0.3 m),
        # and each bridged layer said why it kept its footprint.
        self.assert_same_grids(120, 80)
        logged = self.move_base_errors.wait("/move_base/global_costmap/inflation/footprint", ("vertex 0", "not finite"),
                                            timeout=10.0)
        self.assertTrue(logged, "move_base logged nothing under [/move_base/global_costmap/inflation/footprint];"
                        " last lines:\n%s" % "\n".join(self.move_base_errors.lines[-20:]))
        # The file the start-up check read gets the lines as they are written: this one is there too.
        key = "[/move_base/global_costmap/inflation/footprint]"
        deadline = rospy.Time.now() + rospy.Duration(10.0)
        while key not in move_base_stderr() and rospy.Time.now() < deadline:
            rospy.sleep(0.05)  # polled with a deadline, not a fixed wait
        self.assertIn(key, move_base_stderr(), "the error is not in move_base's stderr log: the start-up check"
                      " above read nothing")


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "test_move_base", MoveBaseTest)
