#!/usr/bin/env python3
"""Nav2's speed tutorial through real topics: costmap_filter_info_server and mask_server read Nav2's
parameter file unchanged (ros__parameters level removed), costmap_node's SpeedFilter is configured
Nav2's way (filter_info_topic, speed_limit_topic), a fake robot drives through the zones. Checks the
limits on /speed_limit are Nav2's (type 1, base 100, multiplier -1: 100 - mask value percent) and
mask_server's load summary under both pixel rules."""
import os
import re
import signal
import subprocess
import threading
import unittest

import roslib.packages
import rospy
import rostest
from costmap_layers.msg import Nav2SpeedLimit


class Nav2SpeedTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_nav2_speed")
        cls.limits = []
        cls.cond = threading.Condition()

        def on_limit(m):
            with cls.cond:
                cls.limits.append((m.percentage, round(m.speed_limit, 6)))
                cls.cond.notify_all()

        rospy.Subscriber("/speed_limit", Nav2SpeedLimit, on_limit)

    def test_1_speed_zones_give_nav2s_limits(self):
        # Waiting at the start, on a free cell, once the info and the mask are in: 0 % (no limit).
        with self.cond:
            self.assertTrue(self.cond.wait_for(lambda: (True, 0.0) in self.limits, timeout=40.0),
                            "no percent limit on /speed_limit: %s" % self.limits)
        rospy.set_param("/fake_robot/start", True)
        deadline = rospy.Time.now() + rospy.Duration(60.0)
        while not rospy.get_param("/fake_robot/done", False) and rospy.Time.now() < deadline:
            rospy.sleep(0.1)
        self.assertTrue(rospy.get_param("/fake_robot/done", False), "the robot did not finish its route")
        # At the goal the last limit (80 %) comes within two update cycles.
        with self.cond:
            self.assertTrue(self.cond.wait_for(lambda: self.limits and self.limits[-1] == (True, 80.0), timeout=5.0),
                            "not 80 %% at the goal: %s" % self.limits)
            percent = [v for p, v in self.limits if p]
        start = percent.index(0.0)
        # free 0 (no limit), mask 40 -> 60 %, free, mask 70 -> 30 %, free, mask 20 -> 80 %.
        self.assertEqual(percent[start:], [0.0, 100.0 - 40, 0.0, 100.0 - 70, 0.0, 100.0 - 20])

    def run_mask_server(self, name, *args):
        exe = roslib.packages.find_node("costmap_layers", "mask_server")
        self.assertTrue(exe, "mask_server not found")
        env = dict(os.environ, ROSCONSOLE_STDOUT_LINE_BUFFERED="1")
        proc = subprocess.Popen([exe[0], "__name:=" + name] + list(args), stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, universal_newlines=True, env=env)
        # It logs its summary, then publishes and spins (or exits on a bad parameter): read until the
        # "published" line or the end, then stop it.
        lines = []

        def read():
            for line in proc.stdout:
                lines.append(line)
                if "[mask_server/published]" in line:
                    return

        reader = threading.Thread(target=read)
        reader.start()
        reader.join(30.0)
        if proc.poll() is None:
            proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=30)
        reader.join(5.0)
        # rosconsole colours its lines; the stable key ends the text inside the colour codes.
        plain = re.compile(r"\x1b\[[0-9;]*m")
        return plain.sub("", "".join(lines) + out), plain.sub("", err)

    def test_2_mask_server_summary_with_nav2s_rule(self):
        # Nav2's parameter name topic_name: a Nav2 mask, read with Nav2's pixel rule.
        out, err = self.run_mask_server("nav2_mask_probe", "_yaml_filename:=" + rospy.get_param("~speed_mask"),
                                        "_topic_name:=/probe_speed_mask")
        summary = [l for l in out.splitlines() if l.endswith("[mask_server/loaded]")]
        self.assertEqual(len(summary), 1, out + err)
        s = summary[0]
        for part in ["384x384 cells at 0.05 m/cell", "origin (-10, -10, 0)", "frame map", "mode nav2_scale",
                     "pixel rule nav2", "values: 0 x 8181, 20 x 138514, 40 x 500, 70 x 180, 100 x 81"]:
            self.assertIn(part, s)
        self.assertNotIn("[mask_server/pixel_rule]", err)

    def test_3_mask_server_warns_about_the_other_pixel_rule(self):
        # The same Nav2 mask read with ROS 1's rule: white 1, black 99, and a warning.
        out, err = self.run_mask_server("ros1_mask_probe", "_yaml_filename:=" + rospy.get_param("~speed_mask"),
                                        "_topic:=/probe_speed_mask_ros1")
        self.assertIn("pixel rule ros1", out)
        self.assertIn("1 x 8181", out)
        self.assertIn("99 x 81", out)
        warning = [l for l in err.splitlines() if l.endswith("[mask_server/pixel_rule]")]
        self.assertEqual(len(warning), 1, err)
        self.assertIn("pixel_rule: nav2", warning[0])

    def test_4_mask_server_refuses_both_topic_names(self):
        out, err = self.run_mask_server("both_topics_probe", "_yaml_filename:=" + rospy.get_param("~speed_mask"),
                                        "_topic:=/a", "_topic_name:=/b")
        self.assertIn("topic_name", err)
        self.assertIn("are both set", err)


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "nav2_speed", Nav2SpeedTest)
