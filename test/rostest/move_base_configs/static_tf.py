#!/usr/bin/env python3
"""A latched static transform: static_tf.py parent child x y z yaw (Debian packages no
tf2_ros static_transform_publisher binary)."""
import math
import sys

import rospy
import tf2_ros
from geometry_msgs.msg import TransformStamped


def main():
    argv = rospy.myargv(sys.argv)
    parent, child = argv[1], argv[2]
    x, y, z, yaw = (float(v) for v in argv[3:7])
    rospy.init_node("static_tf", anonymous=True)
    t = TransformStamped()
    t.header.stamp = rospy.Time.now()
    t.header.frame_id = parent
    t.child_frame_id = child
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = x, y, z
    t.transform.rotation.z = math.sin(yaw / 2.0)
    t.transform.rotation.w = math.cos(yaw / 2.0)
    broadcaster = tf2_ros.StaticTransformBroadcaster()
    broadcaster.sendTransform(t)
    rospy.spin()


if __name__ == "__main__":
    main()
