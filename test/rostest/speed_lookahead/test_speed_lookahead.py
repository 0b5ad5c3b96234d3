#!/usr/bin/env python3
"""SpeedFilter's path lookahead through real topics: with a plan on /move_base/NavfnROS/plan and
odometry at 2 m/s (braking distance 2^2 / (2 * 0.5) = 4 m), /max_speed drops to the zone's 0.3 m/s
about 4 m before the zone's boundary (x = 10 m), not at it; a path with a NaN, 10^6 poses, no frame
or an old stamp, and odometry with NaN or infinity, are refused by their keys (the last good path
stays)."""
import os
import sys
import threading
import unittest

import rospy
import rostest
from costmap_layers.msg import MaxSpeed
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import OccupancyGrid, Odometry, Path
from rosgraph_msgs.msg import Log

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from grid_watch import logged_with_key  # noqa: E402
from robot_pose import RobotPose  # noqa: E402

ZONE_X = 10.0
BRAKING = 2.0 ** 2 / (2 * 0.5)
# Path poses at 0.05 + 0.15 k and robot steps of 0.1 m: no pose lies on a mask cell's edge and no
# distance along the path equals the braking distance, so no float rounding decides the outcome.
SPACING = 0.15  # between path poses
STEP = 0.1  # of the robot


def make_mask():
    """20 m x 4 m at 0.1 m: 30 (0.3 m/s with multiplier 0.01) for x >= 10 m, 0 (no limit) before."""
    m = OccupancyGrid()
    m.header.frame_id = "map"
    m.header.stamp = rospy.Time.now()
    m.info.resolution = 0.1
    m.info.width, m.info.height = 200, 40
    m.info.origin.orientation.w = 1.0
    m.data = ([0] * 100 + [30] * 100) * 40
    return m


def make_path(bad=False):
    p = Path()
    p.header.frame_id = "map"
    p.header.stamp = rospy.Time.now()
    for k in range(130):
        ps = PoseStamped()
        ps.header.frame_id = "map"
        ps.pose.position.x = 0.05 + k * SPACING
        ps.pose.position.y = 2.0
        ps.pose.orientation.w = 1.0
        p.poses.append(ps)
    if bad:
        p.poses[42].pose.position.x = float("nan")  # poses[42]
    return p


class SpeedLookaheadTest(unittest.TestCase):
    def test_limit_drops_before_the_zone_by_the_braking_distance(self):
        rospy.init_node("test_speed_lookahead")
        speeds = []
        cond = threading.Condition()

        def on_speed(msg):
            with cond:
                speeds.append(round(msg.max_speed, 6))
                cond.notify_all()

        rospy.Subscriber("/max_speed", MaxSpeed, on_speed)
        logs = []

        def on_log(m):
            with cond:
                logs.append(m.msg)
                cond.notify_all()

        rospy.Subscriber("/rosout", Log, on_log)
        robot = RobotPose("/costmap_node", 4.0, 2.0)
        mask_pub = rospy.Publisher("/speed_mask", OccupancyGrid, queue_size=1, latch=True)
        path_pub = rospy.Publisher("/move_base/NavfnROS/plan", Path, queue_size=1, latch=True)
        odom_pub = rospy.Publisher("/odom", Odometry, queue_size=10)

        def odom_tick(_):
            o = Odometry()
            o.header.stamp = rospy.Time.now()
            o.header.frame_id = "odom"
            o.child_frame_id = "base_link"
            o.twist.twist.linear.x = 2.0
            odom_pub.publish(o)

        rospy.Timer(rospy.Duration(0.05), odom_tick)
        mask_pub.publish(make_mask())
        path_pub.publish(make_path())

        def limit_becomes(value, timeout=10.0):
            with cond:
                return cond.wait_for(lambda: speeds and speeds[-1] == value, timeout)

        self.assertTrue(robot.move_to(4.0, 2.0, cycles=3))
        self.assertTrue(limit_becomes(1.0), "no default limit far from the zone: %s" % speeds)
        # Drive toward the zone in 0.1 m steps; find where the limit drops.
        first = None
        x = 5.0
        while x < ZONE_X:
            self.assertTrue(robot.move_to(x, 2.0, cycles=2))
            with cond:
                cond.wait_for(lambda: speeds[-1] == 0.3, 0.5 if x < ZONE_X - BRAKING - 2 * SPACING else 3.0)
                if speeds[-1] == 0.3:
                    first = x
                    break
            x = round(x + STEP, 3)
        self.assertIsNotNone(first, "the limit did not drop before the zone: %s" % speeds)
        # Nav2's walk starts at the start of the nearest path segment (up to one spacing behind the robot)
        # and samples poses (the first one in the zone lies up to one spacing inside it); the robot moves
        # in steps: the drop comes within those of the braking distance before the zone.
        self.assertGreaterEqual(first, ZONE_X - BRAKING - SPACING)
        self.assertLessEqual(first, ZONE_X - BRAKING + 2 * SPACING + STEP)
        self.assertEqual(speeds, [1.0, 0.3])

        # A path with a NaN position is refused: the last good one stays (still 0.3 here).
        path_pub.publish(make_path(bad=True))
        key = "/costmap_node/speed_filter/path/poses[i].pose.position"
        with cond:
            self.assertTrue(cond.wait_for(lambda: logged_with_key(logs, key, "poses[42].pose.position"), 10.0),
                            "no error keyed %s for the NaN path" % key)
        self.assertTrue(robot.move_to(first + 0.05, 2.0, cycles=5))
        with cond:
            self.assertEqual(speeds, [1.0, 0.3])

        # More hostile paths, each refused by its key with the last good path staying. Each lies behind
        # the robot (x <= 2.9 m): taken, it would put the zone out of sight and lift the limit to 1.0.
        def behind():
            p = make_path()
            p.poses = p.poses[:20]
            return p

        def refused(msg, key, *values):
            path_pub.publish(msg)
            with cond:
                self.assertTrue(cond.wait_for(lambda: logged_with_key(logs, key, *values), 30.0),
                                "no error keyed %s" % key)

        huge = behind()
        huge.poses = huge.poses[:1] * 1000000  # 10^6 poses, 72 MB
        refused(huge, "/costmap_node/speed_filter/path/poses", "1000000")
        no_frame = behind()
        no_frame.header.frame_id = ""
        no_frame.poses[3].pose.orientation.w = 0.0  # a zero quaternion: orientations play no part
        refused(no_frame, "/costmap_node/speed_filter/path/header.frame_id")
        old = behind()
        old.header.stamp = rospy.Time(1)  # older than the path in force
        refused(old, "/costmap_node/speed_filter/path/header.stamp")
        # Odometry with a NaN speed or an infinite turn rate: refused by key.
        for field, key in [("x", "linear"), ("z", "angular")]:
            o = Odometry()
            o.header.stamp = rospy.Time.now()
            o.header.frame_id = "odom"
            o.child_frame_id = "base_link"
            if field == "x":
                o.twist.twist.linear.x = float("nan")
            else:
                o.twist.twist.angular.z = float("inf")
            odom_pub.publish(o)
            with cond:
                self.assertTrue(cond.wait_for(lambda: logged_with_key(
                    logs, "/costmap_node/speed_filter/odom/twist.twist." + key), 30.0), "no odom/%s error" % key)
        self.assertTrue(robot.move_to(first + 0.05, 2.0, cycles=5))
        with cond:
            self.assertEqual(speeds, [1.0, 0.3])


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "speed_lookahead", SpeedLookaheadTest)
