#!/usr/bin/env python3
"""Floods /scan, /cloud and /sonar at ~RATE Hz each for SECONDS seconds (a separate process, so that
the test's own service calls and subscriptions do not compete with it for Python's lock), then prints
how many of each it sent:  flood_pub.py SECONDS RATE"""
import struct
import sys
import time

import rospy
from sensor_msgs.msg import LaserScan, PointCloud2, PointField, Range


def main():
    seconds, rate = float(sys.argv[1]), float(sys.argv[2])
    rospy.init_node("flood_pub", anonymous=True)
    pubs = {t: rospy.Publisher(t, c, queue_size=100)
            for t, c in (("/scan", LaserScan), ("/cloud", PointCloud2), ("/sonar", Range))}
    deadline = time.time() + 10.0
    while any(p.get_num_connections() == 0 for p in pubs.values()) and time.time() < deadline:
        time.sleep(0.05)
    # Readings in the global frame: tf can always place them, so every one reaches its layer.
    scan = LaserScan()
    scan.header.frame_id = "map"
    scan.angle_min, scan.angle_max, scan.angle_increment = -0.5, 0.5, 0.01
    scan.range_min, scan.range_max = 0.1, 5.0
    scan.ranges = [1.5] * 101
    cloud = PointCloud2()
    cloud.header.frame_id = "map"
    cloud.height, cloud.width = 1, 2
    cloud.fields = [PointField("x", 0, PointField.FLOAT32, 1), PointField("y", 4, PointField.FLOAT32, 1),
                    PointField("z", 8, PointField.FLOAT32, 1)]
    cloud.point_step, cloud.row_step = 12, 24
    cloud.data = struct.pack("<ffffff", 1.0, 1.0, 0.3, 1.2, 1.0, 0.3)
    sonar = Range()
    sonar.header.frame_id = "map"
    # A wide, long cone: each reading touches a quarter million cells of the test's 50 m map.
    sonar.field_of_view, sonar.min_range, sonar.max_range, sonar.range = 1.5, 0.1, 25.0, 20.0
    sent = 0
    start = time.time()
    period = 1.0 / rate
    while not rospy.is_shutdown() and time.time() - start < seconds:
        stamp = rospy.Time.now()
        for msg, topic in ((scan, "/scan"), (cloud, "/cloud"), (sonar, "/sonar")):
            msg.header.stamp = stamp
            pubs[topic].publish(msg)
        sent += 1
        ahead = start + sent * period - time.time()
        if ahead > 0:
            time.sleep(ahead)
    print("flood_pub: sent %d of each in %.1f s" % (sent, time.time() - start), flush=True)


if __name__ == "__main__":
    main()
