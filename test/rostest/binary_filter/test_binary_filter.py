#!/usr/bin/env python3
"""BinaryFilter through real topics: the test publishes a mask (latched) and drives the robot in tf
along a route; each filter's std_msgs/Bool must be latched, start at default_state, and change only
where the rule says (unknown cells keep the state, leaving the mask restores default_state)."""
import os
import sys
import threading
import unittest

import rospy
import rostest
from nav_msgs.msg import OccupancyGrid
from std_msgs.msg import Bool

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from robot_pose import RobotPose  # noqa: E402


def make_mask():
    """10 m x 4 m at 0.1 m: x in [3, 5) holds 80, [5, 6) -1 (unknown), [6, 7) 80, [8, 10) 30, else 0."""
    m = OccupancyGrid()
    m.header.frame_id = "map"
    m.header.stamp = rospy.Time.now()
    m.info.resolution = 0.1
    m.info.width, m.info.height = 100, 40
    m.info.origin.orientation.w = 1.0
    row = []
    for i in range(100):
        x = (i + 0.5) * 0.1
        row.append(80 if 3 <= x < 5 or 6 <= x < 7 else -1 if 5 <= x < 6 else 30 if 8 <= x < 10 else 0)
    m.data = row * 40
    return m


class Recorder:
    def __init__(self, topic):
        self.values = []
        self.cond = threading.Condition()
        rospy.Subscriber(topic, Bool, self._on)

    def _on(self, msg):
        with self.cond:
            self.values.append(msg.data)
            self.cond.notify_all()

    def wait_for(self, n, timeout=20.0):
        with self.cond:
            return self.cond.wait_for(lambda: len(self.values) >= n, timeout)


class BinaryFilterTest(unittest.TestCase):
    def test_state_sequence_along_a_route(self):
        rospy.init_node("test_binary_filter")
        camera = Recorder("/camera_off")
        headlights = Recorder("/headlights")
        robot = RobotPose("/costmap_node", 1.0, 2.0)  # on a 0 cell: the default states
        # Latched initial states, before any mask: the default states.
        self.assertTrue(camera.wait_for(1) and headlights.wait_for(1), "no initial (latched) state")
        self.assertEqual(camera.values[:1], [False])
        self.assertEqual(headlights.values[:1], [True])
        mask_pub = rospy.Publisher("/binary_mask", OccupancyGrid, queue_size=1, latch=True)
        mask_pub.publish(make_mask())
        # camera_filter: 80 > 50 flips to True; 30 and 0 do not. nav2_binary (default True, threshold 20):
        # 80 and 30 flip to False. Unknown keeps both; off the mask both return to their defaults.
        # (x, what is there, camera state, headlights state)
        route = [(4.0, "80", True, False), (7.5, "0", False, True), (5.5, "-1", False, True),
                 (6.5, "80", True, False), (5.5, "-1", True, False), (9.0, "30", False, False),
                 (11.0, "off the mask", False, True), (4.0, "80", True, False)]
        for x, what, cam, lights in route:
            self.assertTrue(robot.move_to(x, 2.0, cycles=3), "the node ran no cycles at x=%.1f (%s)" % (x, what))
            with camera.cond:
                self.assertTrue(camera.cond.wait_for(lambda: camera.values[-1] == cam, 10.0),
                                "camera_off at x=%.1f (%s): %s" % (x, what, camera.values))
            with headlights.cond:
                self.assertTrue(headlights.cond.wait_for(lambda: headlights.values[-1] == lights, 10.0),
                                "headlights at x=%.1f (%s): %s" % (x, what, headlights.values))
        # Published on change only: exactly one message per change.
        self.assertEqual(camera.values, [False, True, False, True, False, True])
        self.assertEqual(headlights.values, [True, False, True, False, True, False])

if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "binary_filter", BinaryFilterTest)
