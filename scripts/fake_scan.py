#!/usr/bin/env python3
"""A simulated 2-D lidar for the demo's local costmap. Casts ~beams rays (all around) over the map on
~map_topic from the robot's pose in tf (~global_frame -> ~frame) and publishes sensor_msgs/LaserScan on
~topic at ~rate Hz. To show the DenoiseLayer at work, ~speckles beams of each scan return a false short
range, as dust or a dirty window does: a single obstacle cell in free space. Which beams and how short
comes from a generator seeded with ~seed, so that every run sends the same speckles. The running count
of false returns is the parameter ~speckles_sent."""
import math
import random

import rospy
import tf2_ros
from nav_msgs.msg import OccupancyGrid
from sensor_msgs.msg import LaserScan


class Grid:
    """The map's occupied cells (value >= ~occupied, default 65) for ray casting."""

    def __init__(self, msg, occupied):
        info = msg.info
        self.res = info.resolution
        self.ox, self.oy = info.origin.position.x, info.origin.position.y
        self.w, self.h = info.width, info.height
        self.blocked = bytes(1 if v >= occupied or v < 0 else 0 for v in msg.data)

    def cast(self, x, y, angle, range_max):
        """The distance [m] to the first blocked cell along the ray, or inf within range_max; steps of
        half a cell."""
        step = self.res * 0.5
        dx, dy = math.cos(angle) * step, math.sin(angle) * step
        n = int(range_max / step)
        px, py = x, y
        for k in range(1, n + 1):
            px += dx
            py += dy
            i = int((px - self.ox) / self.res)
            j = int((py - self.oy) / self.res)
            if i < 0 or j < 0 or i >= self.w or j >= self.h or self.blocked[j * self.w + i]:
                return k * step
        return float("inf")


def main():
    rospy.init_node("fake_scan")
    global_frame = rospy.get_param("~global_frame", "map")
    frame = rospy.get_param("~frame", "base_link")
    beams = int(rospy.get_param("~beams", 360))
    range_max = float(rospy.get_param("~range_max", 3.0))
    speckles = int(rospy.get_param("~speckles", 3))
    occupied = int(rospy.get_param("~occupied", 65))
    rate_hz = float(rospy.get_param("~rate", 5.0))
    rng = random.Random(int(rospy.get_param("~seed", 1)))
    if beams < 1 or beams > 4096 or not 0.1 <= range_max <= 100.0 or speckles < 0 or not 0.1 <= rate_hz <= 50.0:
        rospy.logfatal("fake_scan: ~beams (1..4096), ~range_max (0.1..100 m), ~speckles (>= 0) or ~rate "
                       "(0.1..50 Hz) out of range: %d, %g, %d, %g", beams, range_max, speckles, rate_hz)
        raise SystemExit(1)
    grid = []
    rospy.Subscriber(rospy.get_param("~map_topic", "/map"), OccupancyGrid,
                     lambda m: grid.append(Grid(m, occupied)) if not grid else None)
    buffer = tf2_ros.Buffer()
    tf2_ros.TransformListener(buffer)
    pub = rospy.Publisher(rospy.get_param("~topic", "/scan"), LaserScan, queue_size=1)
    increment = 2.0 * math.pi / beams
    sent = 0
    rate = rospy.Rate(rate_hz)
    while not rospy.is_shutdown():
        rate.sleep()
        if not grid:
            rospy.logwarn_throttle(5.0, "fake_scan: no map on %s yet", rospy.get_param("~map_topic", "/map"))
            continue
        try:
            t = buffer.lookup_transform(global_frame, frame, rospy.Time(0), rospy.Duration(0.2))
        except tf2_ros.TransformException as e:
            rospy.logwarn_throttle(5.0, "fake_scan: no pose of %s in %s: %s", frame, global_frame, e)
            continue
        q = t.transform.rotation
        yaw = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
        x, y = t.transform.translation.x, t.transform.translation.y
        ranges = [grid[0].cast(x, y, yaw - math.pi + k * increment, range_max) for k in range(beams)]
        # False returns well short of what the beam sees, so that each stays a cell on its own.
        for _ in range(speckles):
            k = rng.randrange(beams)
            r = rng.uniform(0.5, 2.0)
            if r < min(ranges[k], range_max) - 0.3:
                ranges[k] = r
                sent += 1
        scan = LaserScan()
        scan.header.stamp = t.header.stamp
        scan.header.frame_id = frame
        scan.angle_min = -math.pi
        scan.angle_increment = increment
        scan.angle_max = -math.pi + (beams - 1) * increment
        scan.range_min = 0.05
        scan.range_max = range_max
        scan.ranges = ranges
        pub.publish(scan)
        rospy.set_param("~speckles_sent", sent)


if __name__ == "__main__":
    main()
