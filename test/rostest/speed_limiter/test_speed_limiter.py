#!/usr/bin/env python3
"""speed_limiter with the real SpeedFilter: planner commands at 1.0 m/s (turning at 0.5 rad/s) are
limited to 0.3 m/s with the same curvature while the robot is in the 0.3 m/s zone, pass unchanged
before and after it, and when commands stop, one zero command is published and then nothing."""
import threading
import unittest

import rospy
import rostest
from costmap_layers.msg import MaxSpeed
from geometry_msgs.msg import Twist


class SpeedLimiterTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_speed_limiter")
        cls.lock = threading.Lock()
        cls.limit = None  # the latest /max_speed
        cls.outputs = []  # (limit in force when the command went out, output Twist, time)

        def on_limit(msg):
            with cls.lock:
                cls.limit = msg.max_speed

        def on_out(msg):
            with cls.lock:
                cls.outputs.append((cls.sent_under, msg, rospy.Time.now()))

        cls.sent_under = None
        rospy.Subscriber("/max_speed", MaxSpeed, on_limit)
        rospy.Subscriber("/cmd_vel", Twist, on_out)
        cls.cmd = rospy.Publisher("/cmd_vel_in", Twist, queue_size=10)

    def send(self, duration):
        """Planner commands at 20 Hz: 1.0 m/s forward, turning at 0.5 rad/s."""
        t = Twist()
        t.linear.x = 1.0
        t.angular.z = 0.5
        r = rospy.Rate(20)
        end = rospy.Time.now() + rospy.Duration(duration)
        while rospy.Time.now() < end and not rospy.is_shutdown():
            with self.lock:
                self.__class__.sent_under = self.limit
            self.cmd.publish(t)
            r.sleep()

    def test_zone_limits_and_recovers_then_stale_stops(self):
        deadline = rospy.Time.now() + rospy.Duration(30.0)
        while self.limit is None and rospy.Time.now() < deadline:
            rospy.sleep(0.1)
        self.assertEqual(self.limit, 0.0, "the speed filter published no initial limit")
        rospy.set_param("/fake_robot/start", True)
        end = rospy.Time.now() + rospy.Duration(25.0)
        while not rospy.get_param("/fake_robot/done", False) and rospy.Time.now() < end:
            self.send(0.5)
        self.send(1.0)
        with self.lock:
            outputs = list(self.outputs)
        # Judge only commands sent well inside a phase (the limit may change while one is in flight).
        zone = [o for o in outputs if o[0] == 0.3]
        free = [o for o in outputs if o[0] == 0.0]
        self.assertGreater(len(zone), 10, "no commands went out while the robot was in the 0.3 m/s zone")
        self.assertGreater(len(free), 10)
        in_zone = [o[1] for o in zone[3:-3]]
        for t in in_zone:
            self.assertAlmostEqual(t.linear.x, 0.3, places=6)
            self.assertAlmostEqual(t.angular.z, 0.15, places=6)  # the same curvature: 0.5 rad/m
        after = [o[1] for o in free[-10:]]
        for t in after:
            self.assertAlmostEqual(t.linear.x, 1.0, places=6)
            self.assertAlmostEqual(t.angular.z, 0.5, places=6)
        # Stale input: one zero command about command_timeout after the last one, then silence.
        with self.lock:
            n = len(self.outputs)
        rospy.sleep(1.5)  # an observation window (3 x command_timeout): silence can only be seen by waiting
        with self.lock:
            late = self.outputs[n:]
        self.assertEqual(len(late), 1, "expected exactly one command after the input stopped, got %d" % len(late))
        zero = late[0][1]
        self.assertEqual((zero.linear.x, zero.linear.y, zero.angular.z), (0.0, 0.0, 0.0))


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "speed_limiter", SpeedLimiterTest)
