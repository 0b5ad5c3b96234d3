#!/usr/bin/env python3
"""costmap_node under /use_sim_time. Before the first /clock it runs no update cycle (costmap_2d's loop
does not run either) and says why in /diagnostics, instead of publishing a costmap built without any
stamped input. Once /clock runs it updates and publishes. When /clock jumps back (rosbag play --loop),
/diagnostics and the costmap keep coming. speed_limiter's command timeout works without /clock too (its
watchdog is timed on the steady clock while the ROS clock does not move), and the age of the last message
on a layer's topic in /diagnostics is real time, not 0 s while /clock is behind the arrival. All waits here are on the wall clock: this process's
ROS time is the simulated one it publishes."""
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from geometry_msgs.msg import Twist
from nav_msgs.msg import MapMetaData, OccupancyGrid
from rosgraph_msgs.msg import Clock

NODE = "costmap_node"
LEVEL = {0: "OK", 1: "WARN", 2: "ERROR", 3: "STALE"}


class SimClockTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_sim_clock")
        cls.lock = threading.Lock()
        cls.status = None  # the latest "costmap_node: costmap" status
        cls.static_status = None  # the latest "costmap_node: layer static" status
        cls.status_count = 0
        cls.grid_count = 0
        cls.clock_pub = rospy.Publisher("/clock", Clock, queue_size=10)
        rospy.Subscriber("/diagnostics", DiagnosticArray, cls.on_diagnostics, queue_size=50)
        rospy.Subscriber("/" + NODE + "/costmap", OccupancyGrid, cls.on_grid, queue_size=10)
        cls.commands = []  # what speed_limiter sent on /cmd_vel
        cls.cmd_pub = rospy.Publisher("/cmd_vel_in", Twist, queue_size=10)
        cls.map_pub = rospy.Publisher("/map", OccupancyGrid, queue_size=1, latch=True)
        rospy.Subscriber("/cmd_vel", Twist, cls.on_command, queue_size=50)

    @classmethod
    def on_command(cls, msg):
        with cls.lock:
            cls.commands.append(msg.linear.x)

    @classmethod
    def on_diagnostics(cls, msg):
        with cls.lock:
            for s in msg.status:
                if s.name == NODE + ": costmap":
                    cls.status = s
                    cls.status_count += 1
                elif s.name == NODE + ": layer static":
                    cls.static_status = s

    @classmethod
    def on_grid(cls, _msg):
        with cls.lock:
            cls.grid_count += 1

    def counts(self):
        with self.lock:
            return self.status_count, self.grid_count

    def wait_for(self, predicate, timeout, what):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            with self.lock:
                s = self.status
            if s is not None and predicate(s):
                return s
            time.sleep(0.05)
        with self.lock:
            s = self.status
        seen = "nothing" if s is None else "%s: %s" % (LEVEL.get(s.level), s.message)
        self.fail("%s (last seen: %s)" % (what, seen))

    def run_clock(self, start_s, seconds):
        """Publishes /clock from start_s at the wall clock's pace for `seconds` of wall time."""
        t0 = time.monotonic()
        while time.monotonic() - t0 < seconds:
            self.clock_pub.publish(Clock(clock=rospy.Time.from_sec(start_s + time.monotonic() - t0)))
            time.sleep(0.01)

    def test_no_clock_then_clock_then_clock_back(self):
        # No /clock: /diagnostics still comes, with an ERROR naming /clock; no costmap is published.
        s = self.wait_for(lambda s: s.level == DiagnosticStatus.ERROR and "/clock" in s.message, 20.0,
                          "an ERROR naming /clock while no /clock arrived")
        self.assertIn("/use_sim_time", s.message)
        time.sleep(1.5)
        statuses, grids = self.counts()
        self.assertGreaterEqual(statuses, 2, "/diagnostics must keep coming without /clock")
        self.assertEqual(grids, 0, "no costmap before the first /clock")

        # speed_limiter without /clock: a command passes, and 0.5 s after it stops a zero command follows.
        deadline = time.monotonic() + 10.0
        while self.cmd_pub.get_num_connections() == 0 and time.monotonic() < deadline:
            time.sleep(0.05)
        self.assertGreater(self.cmd_pub.get_num_connections(), 0, "speed_limiter never subscribed cmd_vel_in")
        command = Twist()
        command.linear.x = 0.4
        self.cmd_pub.publish(command)
        deadline = time.monotonic() + 5.0
        while time.monotonic() < deadline:
            with self.lock:
                sent = list(self.commands)
            if len(sent) >= 2:
                break
            time.sleep(0.05)
        self.assertEqual(sent[:2], [0.4, 0.0],
                         "speed_limiter must forward the command, then send a zero one when commands stop, "
                         "with no /clock (got %s)" % sent)

        # /clock runs from 100 s: cycles and a costmap, and the ERROR is gone.
        runner = threading.Thread(target=self.run_clock, args=(100.0, 10.0))
        runner.start()
        try:
            self.wait_for(lambda s: "/clock" not in s.message and
                          any(kv.key == "cycles" and int(kv.value) > 0 for kv in s.values), 8.0,
                          "update cycles once /clock runs")
            deadline = time.monotonic() + 5.0
            while self.counts()[1] == 0 and time.monotonic() < deadline:
                time.sleep(0.05)
            self.assertGreater(self.counts()[1], 0, "a costmap once /clock runs")
            # The map arrives while the ROS clock reads about 100 s.
            grid = OccupancyGrid(info=MapMetaData(resolution=0.1, width=40, height=40))
            grid.header.frame_id = "map"
            grid.info.origin.orientation.w = 1.0
            grid.data = [0] * (40 * 40)
            grid.data[20 * 40 + 20] = 100
            self.map_pub.publish(grid)
            self.wait_static(lambda v: v.startswith("1 message"), 5.0, "the map's receipt")
        finally:
            runner.join()

        # /clock jumps back to 1 s (a bag played in a loop): both keep coming at their wall-clock pace.
        statuses, grids = self.counts()
        self.run_clock(1.0, 3.0)
        statuses_after, grids_after = self.counts()
        self.assertGreaterEqual(statuses_after - statuses, 3,
                                "/diagnostics (period 0.5 s) must keep coming after /clock jumped back")
        with self.lock:
            s = self.status
        seen = "%s: %s %s" % (LEVEL.get(s.level), s.message, {kv.key: kv.value for kv in s.values})
        self.assertGreaterEqual(grids_after - grids, 2, "the costmap (2 Hz) must keep coming after the jump; " + seen)
        self.assertNotIn("/clock", s.message)
        self.assertNotEqual(s.level, DiagnosticStatus.ERROR, s.message)
        # The map came >= 3 s of real time ago, at ROS time ~105 s; ROS time now reads ~4 s.
        self.wait_static(lambda v: float(v.split("last ")[1].split(" s ago")[0]) >= 2.5, 3.0,
                         "the map's receipt age in real time after /clock went back")

    def wait_static(self, predicate, timeout, what):
        """Waits for the static layer's "received on /map" value to satisfy predicate."""
        deadline = time.monotonic() + timeout
        value = None
        while time.monotonic() < deadline:
            with self.lock:
                s = self.static_status
            values = {} if s is None else {kv.key: kv.value for kv in s.values}
            value = values.get("received on /map")
            if value is not None and predicate(value):
                return value
            time.sleep(0.05)
        self.fail("%s (last seen: %s)" % (what, value))


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "test_sim_clock", SimClockTest)
