#!/usr/bin/env python3
"""The filters through real topics: mask_server + features_server + costmap_node + a robot moving in
tf. Checks the sequence of /max_speed values, that keepout cells are lethal in the published costmap,
that toggling the filter off removes its effect, and that costmap_tool gives the node's grid."""
import json
import os
import subprocess
import sys
import tempfile
import threading
import unittest

import roslib.packages
import rospy
import rostest
from costmap_layers.msg import MaxSpeed
from std_srvs.srv import SetBool

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from grid_watch import GridWatcher, translate  # noqa: E402

class FiltersTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_filters")
        cls.speeds = []
        cls.speed_cond = threading.Condition()
        cls.grid = GridWatcher("/costmap_node")

        def on_speed(msg):
            with cls.speed_cond:
                cls.speeds.append(round(msg.max_speed, 6))
                cls.speed_cond.notify_all()

        # Recorded from here on, before any case can start the robot (it holds its first pose until
        # ~start): the whole route's values, whichever case drives it.
        rospy.Subscriber("/max_speed", MaxSpeed, on_speed)

    def drive_route(self):
        """Brings the robot to the end of its route (9.0, 5.1), where it then stays. fake_robot drives
        its route once: the first case that needs it there starts it, the others find it done. Each case
        that depends on where the robot stands calls this itself, so no case relies on another having
        run before it (unittest runs them in name order, and a single case may be run alone)."""
        rospy.set_param("/fake_robot/start", True)
        deadline = rospy.Time.now() + rospy.Duration(60.0)
        while not rospy.get_param("/fake_robot/done", False) and rospy.Time.now() < deadline:
            rospy.sleep(0.1)  # polling a condition (the robot's ~done), with a deadline
        self.assertTrue(rospy.get_param("/fake_robot/done", False), "the robot did not finish its route")

    def set_keepout(self, on):
        toggle = rospy.ServiceProxy("/costmap_node/keepout_filter/toggle", SetBool)
        toggle.wait_for_service(10.0)
        self.assertTrue(toggle(on).success)

    def test_1_speed_limits_along_the_route(self):
        # The first (latched) value arrives while the robot waits at its start, in no area.
        with self.speed_cond:
            self.speed_cond.wait_for(lambda: self.speeds, timeout=30.0)
        self.assertEqual(self.speeds[:1], [1.0])
        self.drive_route()
        # start in no area: default 1.0; area 1: 0.3; the -1 strip keeps 0.3; no area: 1.0; area 2: 0.6;
        # up the lane, in no area: 1.0. (The last change may come a cycle after the robot stopped.)
        expected = [1.0, 0.3, 1.0, 0.6, 1.0]
        with self.speed_cond:
            self.speed_cond.wait_for(lambda: len(self.speeds) >= len(expected), timeout=10.0)
            self.assertEqual(self.speeds, expected)

    def test_2_keepout_is_lethal_and_toggles_off(self):
        dock = [(12.5, 8.0), (14.0, 8.5), (15.0, 9.0)]  # inside the keepout mask's 100 region
        self.assertTrue(self.grid.wait_until(lambda g: all(g.at(x, y) == 100 for x, y in dock), 30.0),
                        "keepout cells are not lethal in the published costmap")
        # The wet floor (mask 50) costs round(50 * 254 / 100) = 127 -> 1 + 97 * 126 // 251 = 49.
        self.assertEqual(self.grid.at(14.5, 1.2), translate(127))
        toggle = rospy.ServiceProxy("/costmap_node/keepout_filter/toggle", SetBool)
        toggle.wait_for_service(10.0)
        # On again whatever fails below: no later case may find the filter switched off.
        self.addCleanup(self.set_keepout, True)
        self.assertTrue(toggle(False).success)
        self.assertTrue(self.grid.wait_until(lambda g: g.at(14.0, 8.5) == 0 and g.at(14.5, 1.2) == 0, 20.0),
                        "switching the keepout filter off did not remove its effect")
        self.assertTrue(toggle(True).success)
        self.assertTrue(self.grid.wait_until(lambda g: all(g.at(x, y) == 100 for x, y in dock), 20.0),
                        "switching the keepout filter on again did not restore it")
        # Nav2's name for the same switch, with Nav2's answers.
        nav2_toggle = rospy.ServiceProxy("/costmap_node/keepout_filter/toggle_filter", SetBool)
        nav2_toggle.wait_for_service(10.0)
        answer = nav2_toggle(False)
        self.assertEqual((answer.success, answer.message), (True, "Disabled"))
        self.assertTrue(self.grid.wait_until(lambda g: g.at(14.0, 8.5) == 0, 20.0),
                        "toggle_filter false did not switch the keepout filter off")
        answer = nav2_toggle(True)
        self.assertEqual((answer.success, answer.message), (True, "Enabled"))
        self.assertTrue(self.grid.wait_until(lambda g: all(g.at(x, y) == 100 for x, y in dock), 20.0),
                        "toggle_filter true did not switch the keepout filter on again")

    def test_3_tool_gives_the_nodes_grid(self):
        # Its own state: the robot where the tool is told it stands (--pose, the route's end) and the
        # keepout filter on, as the tool computes it; not what the cases before left.
        self.drive_route()
        self.set_keepout(True)
        example = rospy.get_param("~example")
        tool = roslib.packages.find_node("costmap_layers", "costmap_tool")
        self.assertTrue(tool, "costmap_tool not found")
        with tempfile.TemporaryDirectory() as tmp:
            raw = os.path.join(tmp, "out.raw")
            cmd = [tool[0], "--map", os.path.join(example, "warehouse.yaml"), "--params", rospy.get_param("~params"),
                   "--mask", "keepout_filter=" + os.path.join(example, "keepout_mask.yaml"),
                   "--mask", "speed_filter=" + os.path.join(example, "speed_mask.yaml"),
                   "--mask", "lanes_filter=" + os.path.join(example, "lanes_mask.yaml"),
                   "--mask", "zone_keepout=" + os.path.join(example, "zones.yaml"),
                   "--features", "speed_filter=" + os.path.join(example, "speed_limits.yaml"),
                   "--pose", "9.0,5.1,0.0", "--out-raw", raw]
            proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
            self.assertEqual(proc.returncode, 0, proc.stderr.decode())
            result = json.loads(proc.stdout.decode().strip().splitlines()[-1])
            self.assertEqual(result["max_speed"], {"speed_filter": 1.0})
            with open(raw, "rb") as f:
                expected = [translate(c) for c in f.read()]
        self.assertTrue(self.grid.wait_until(lambda g: g.data == expected, 30.0),
                        "the node's grid differs from costmap_tool's in %d cells" %
                        sum(1 for a, b in zip(self.grid.data, expected) if a != b))
        self.assertEqual(len(expected), 320 * 200)


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "filters", FiltersTest)
