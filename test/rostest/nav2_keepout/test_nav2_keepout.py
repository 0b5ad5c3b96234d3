#!/usr/bin/env python3
"""Nav2's keepout tutorial through real topics: costmap_filter_info_server and mask_server read Nav2's
parameter file unchanged (ros__parameters level removed), costmap_node's KeepoutFilter is configured
Nav2's way (filter_info_topic). Checks the keepout cells are lethal in the published costmap, the
"waiting for filter info" warning of a filter whose info has not come (read from /rosout by its key),
an info that moves a filter to another mask topic, and the info server's checks and warnings."""
import os
import signal
import subprocess
import sys
import threading
import unittest

import roslib.packages
import rospy
import rostest
from costmap_layers.msg import CostmapFilterInfo
from nav_msgs.msg import OccupancyGrid
from rosgraph_msgs.msg import Log

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from grid_watch import GridWatcher  # noqa: E402


def value_at(g, x, y):
    """The published value of the cell containing (x, y) [m], for any grid origin."""
    i = int((x - g.origin[0]) / g.resolution)
    j = int((y - g.origin[1]) / g.resolution)
    return g.data[j * g.width + i]


def square_mask(topic_origin, value=100):
    """A 0.5 m x 0.5 m mask at 0.05 m in frame map, all `value`, lower-left corner at topic_origin."""
    m = OccupancyGrid()
    m.header.frame_id = "map"
    m.header.stamp = rospy.Time.now()
    m.info.resolution = 0.05
    m.info.width = m.info.height = 10
    m.info.origin.position.x, m.info.origin.position.y = topic_origin
    m.info.origin.orientation.w = 1.0
    m.data = [value] * 100
    return m


class Nav2KeepoutTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_nav2_keepout")
        cls.grid = GridWatcher("/costmap_node")
        cls.logs = []
        cls.log_cond = threading.Condition()

        def on_log(m):
            with cls.log_cond:
                cls.logs.append(m)
                cls.log_cond.notify_all()

        rospy.Subscriber("/rosout", Log, on_log)

    def wait_log(self, key, timeout):
        """The first /rosout line ending with the stable key "[<key>]", or None after timeout [s]."""
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        with self.log_cond:
            while not rospy.is_shutdown() and rospy.Time.now() < deadline:
                for m in self.logs:
                    if m.msg.endswith("[" + key + "]"):
                        return m
                self.log_cond.wait(0.5)
        return None

    def test_1_keepout_zone_is_lethal(self):
        # Inside the tutorial mask's two black blocks, and free space between them.
        walls = [(1.8, 0.5), (2.3, 0.1), (-0.25, 0.5)]
        self.assertTrue(self.grid.wait_until(lambda g: all(value_at(g, x, y) == 100 for x, y in walls), 40.0),
                        "the tutorial's keepout cells are not lethal in the published costmap")
        self.assertEqual(value_at(self.grid, 0.5, 0.5), 0)
        self.assertEqual(value_at(self.grid, 2.0, 2.0), 0)  # the mask's 205 grey: free under Nav2's rule

    def test_2_waiting_for_filter_info_is_said(self):
        m = self.wait_log("/costmap_node/late_keepout/waiting", 20.0)
        self.assertIsNotNone(m, "no [/costmap_node/late_keepout/waiting] warning on /rosout")
        self.assertEqual(m.level, Log.WARN)
        self.assertIn("waiting for filter info on /late_filter_info", m.msg)

    def test_3_an_info_with_another_mask_topic_moves_the_subscription(self):
        info_pub = rospy.Publisher("/late_filter_info", CostmapFilterInfo, queue_size=1, latch=True)
        mask_a = rospy.Publisher("/late_mask_a", OccupancyGrid, queue_size=1, latch=True)
        mask_b = rospy.Publisher("/late_mask_b", OccupancyGrid, queue_size=1, latch=True)
        mask_a.publish(square_mask((-2.5, -2.5)))
        mask_b.publish(square_mask((3.0, -2.5)))
        info = CostmapFilterInfo(type=0, filter_mask_topic="/late_mask_a", base=0.0, multiplier=1.0)
        info.header.stamp = rospy.Time.now()
        info_pub.publish(info)
        self.assertTrue(self.grid.wait_until(lambda g: value_at(g, -2.25, -2.25) == 100, 30.0),
                        "the mask named by the first info is not in the costmap")
        self.assertEqual(value_at(self.grid, 3.25, -2.25), 0)
        info.filter_mask_topic = "/late_mask_b"
        info.header.stamp = rospy.Time.now()
        info_pub.publish(info)
        self.assertTrue(
            self.grid.wait_until(lambda g: value_at(g, 3.25, -2.25) == 100 and value_at(g, -2.25, -2.25) == 0, 30.0),
            "a new info naming another mask topic did not move the filter to it")
        # The tutorial's filter is untouched.
        self.assertEqual(value_at(self.grid, 1.8, 0.5), 100)
        # Each move is logged by the node, with the layer's key.
        deadline = rospy.Time.now() + rospy.Duration(10.0)

        def moved():
            return [m.msg for m in self.logs if m.msg.endswith("[/costmap_node/late_keepout/input]") and "/late_mask_b" in m.msg]

        with self.log_cond:
            while not moved() and rospy.Time.now() < deadline:
                self.log_cond.wait(0.5)
            self.assertTrue(moved(), "no [/costmap_node/late_keepout/input] line naming /late_mask_b on /rosout")

    def test_3b_a_sender_moving_the_mask_topic_over_and_over_grows_nothing(self):
        # Each move subscribes anew; what the node keeps per topic (the receipts in its diagnostics) and
        # the lines it logs must not grow with the number of topics a sender names.
        import rosgraph
        from diagnostic_msgs.msg import DiagnosticArray
        statuses = []
        status_cond = threading.Condition()

        def on_diagnostics(msg):
            with status_cond:
                statuses.extend(s for s in msg.status if s.name.endswith("layer late_keepout"))
                status_cond.notify_all()

        diag_sub = rospy.Subscriber("/diagnostics", DiagnosticArray, on_diagnostics, queue_size=50)
        master = rosgraph.Master("/test_nav2_keepout")
        info_pub = rospy.Publisher("/late_filter_info", CostmapFilterInfo, queue_size=100, latch=True)

        def move_to(topic):
            info = CostmapFilterInfo(type=0, filter_mask_topic=topic, base=0.0, multiplier=1.0)
            info.header.stamp = rospy.Time.now()
            info_pub.publish(info)
            deadline = rospy.Time.now() + rospy.Duration(20.0)
            while rospy.Time.now() < deadline:  # until the node reads the topic (polled with a deadline)
                subscribers = dict(master.getSystemState()[1])
                if "/costmap_node" in subscribers.get(topic, []):
                    return
                rospy.sleep(0.02)
            self.fail("costmap_node never subscribed " + topic)

        start = rospy.Time.now()
        for k in range(25):
            move_to("/late_mask_x%d" % k)
        move_to("/late_mask_b")
        self.assertTrue(self.grid.wait_until(lambda g: value_at(g, 3.25, -2.25) == 100, 30.0),
                        "back on /late_mask_b, its mask is not in the costmap")
        # The diagnostics now name the one mask topic the filter reads (and its info topic).
        with status_cond:
            seen = len(statuses)
            deadline = rospy.Time.now() + rospy.Duration(10.0)
            while len(statuses) < seen + 2 and rospy.Time.now() < deadline:
                status_cond.wait(0.5)
            self.assertGreaterEqual(len(statuses), seen + 2, "no diagnostics of late_keepout")
            keys = [v.key for v in statuses[-1].values if "late_mask" in v.key]
        diag_sub.unregister()
        self.assertEqual(keys, ["received on /late_mask_b"])
        # 26 moves within seconds: at most 10 lines (the first of each move per 10 s).
        with self.log_cond:
            lines = [m for m in self.logs if m.msg.endswith("[/costmap_node/late_keepout/input]")
                     and m.header.stamp >= start]
        self.assertGreaterEqual(len(lines), 1)
        self.assertLessEqual(len(lines), 10, "\n".join(m.msg for m in lines))

    def run_info_server(self, name, *args):
        exe = roslib.packages.find_node("costmap_layers", "costmap_filter_info_server")
        self.assertTrue(exe, "costmap_filter_info_server not found")
        env = dict(os.environ, ROSCONSOLE_STDOUT_LINE_BUFFERED="1")
        return subprocess.Popen([exe[0], "__name:=" + name] + list(args), stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, universal_newlines=True, env=env)

    def test_4_info_server_refuses_bad_parameters(self):
        # Parameters given on the command line stay on the server: one node name per case.
        for k, (args, needle) in enumerate([(["_type:=7"], "type must be 0"),
                             (["_type:=speed"], "~type must be an integer (got \"speed\")"),
                             (["_base:=1e39"], "~base does not fit the message's float32"),
                             (["_mask_topic:=a b"], "parameter ~mask_topic: the topic")]):
            proc = self.run_info_server("bad_info_server_%d" % k, *args)
            out, err = proc.communicate(timeout=30)
            self.assertEqual(proc.returncode, 1, (args, out, err))
            self.assertIn(needle, out + err, args)
            self.assertIn("[costmap_filter_info_server/startup]", out + err)
            self.assertEqual((out + err).count("FATAL"), 1, (args, out, err))

    def test_5_info_server_warns_about_use_sim_time_and_publishes(self):
        got = []
        done = threading.Event()

        def on_info(m):
            got.append(m)
            done.set()

        rospy.Subscriber("/probe_info", CostmapFilterInfo, on_info)
        proc = self.run_info_server("probe_info_server", "_use_sim_time:=true", "_type:=2", "_base:=0.1",
                                    "_multiplier:=0.01", "_filter_info_topic:=/probe_info", "_mask_topic:=/probe_mask")
        try:
            self.assertTrue(done.wait(30.0), "the info server published nothing")
            self.assertEqual(got[0].type, 2)
            self.assertEqual(got[0].filter_mask_topic, "/probe_mask")
            self.assertAlmostEqual(got[0].base, 0.1, places=6)
            self.assertAlmostEqual(got[0].multiplier, 0.01, places=6)
        finally:
            proc.send_signal(signal.SIGINT)
            out, err = proc.communicate(timeout=30)
        self.assertIn("[costmap_filter_info_server/use_sim_time]", err)
        self.assertIn("has no effect in ROS 1", err)
        self.assertIn("[costmap_filter_info_server/published]", out)


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "nav2_keepout", Nav2KeepoutTest)
