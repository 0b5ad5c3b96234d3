#!/usr/bin/env python3
"""Publishes the robot pose as tf (global_frame -> robot_base_frame) so that a costmap node can run
without a robot: either a fixed pose (~x, ~y, ~yaw) or, with ~route, a route of waypoints
"x,y;x,y;..." driven at ~speed m/s, once, after which it stays at the last waypoint. The parameter
~done is set to true at the last waypoint."""
import math

import rospy
import tf2_ros
from geometry_msgs.msg import TransformStamped


def parse_route(text):
    points = []
    for part in text.split(";"):
        part = part.strip()
        if not part:
            continue
        x, y = (float(v) for v in part.split(","))
        points.append((x, y))
    return points


def make_tf(parent, child, x, y, yaw):
    t = TransformStamped()
    t.header.stamp = rospy.Time.now()
    t.header.frame_id = parent
    t.child_frame_id = child
    t.transform.translation.x = x
    t.transform.translation.y = y
    t.transform.rotation.z = math.sin(yaw / 2.0)
    t.transform.rotation.w = math.cos(yaw / 2.0)
    return t


def main():
    rospy.init_node("fake_robot")
    parent = rospy.get_param("~global_frame", "map")
    child = rospy.get_param("~robot_base_frame", "base_link")
    rate_hz = float(rospy.get_param("~rate", 20.0))
    speed = float(rospy.get_param("~speed", 0.5))
    route = parse_route(rospy.get_param("~route", ""))
    x = float(rospy.get_param("~x", 0.0))
    y = float(rospy.get_param("~y", 0.0))
    yaw = float(rospy.get_param("~yaw", 0.0))
    if route:
        x, y = route[0]
    # With ~wait_for_start the robot holds its first pose until the parameter ~start is true (tests
    # use it to begin driving once they listen).
    waiting = bool(rospy.get_param("~wait_for_start", False))
    broadcaster = tf2_ros.TransformBroadcaster()
    rate = rospy.Rate(rate_hz)
    target = 1
    while not rospy.is_shutdown():
        if waiting:
            waiting = not rospy.get_param("~start", False)
        elif target < len(route):
            tx, ty = route[target]
            dx, dy = tx - x, ty - y
            dist = math.hypot(dx, dy)
            step = speed / rate_hz
            if dist <= step:
                x, y = tx, ty
                target += 1
                if target == len(route):
                    rospy.set_param("~done", True)
            else:
                yaw = math.atan2(dy, dx)
                x += dx / dist * step
                y += dy / dist * step
        broadcaster.sendTransform(make_tf(parent, child, x, y, yaw))
        rate.sleep()


if __name__ == "__main__":
    main()
