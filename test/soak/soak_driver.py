#!/usr/bin/env python3
"""Drives the soak test: robot tf at 50 Hz (with a jump every 20 s), a LaserScan and a PointCloud2 at
40 Hz each, the three masks and the speed limits republished every second, and a burst of malformed
messages (stale stamps among them) every 10 s. Samples costmap_node's resident memory every second. At the end it checks that
memory did not grow after the warm-up, reports how many update cycles overran their period, and that
/max_speed and the costmap still answer correctly; exits non-zero when a check fails."""
import math
import os
import struct
import sys
import threading
import time
import xmlrpc.client

import rosgraph
import rospy
import tf2_ros
from costmap_layers.msg import MaxSpeed, SpeedLimit, SpeedLimits
from geometry_msgs.msg import TransformStamped
from map_msgs.msg import OccupancyGridUpdate
from nav_msgs.msg import OccupancyGrid
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import LaserScan, PointCloud2, PointField
from std_msgs.msg import Header


def load_pgm_mask(path):
    """A raw-mode example mask as an OccupancyGrid (pixel value = cell value, 255 = -1)."""
    with open(path, "rb") as f:
        data = f.read()
    parts = data.split(b"\n", 3)
    w, h = (int(v) for v in parts[1].split())
    pixels = parts[3]
    g = OccupancyGrid()
    g.header.frame_id = "map"
    g.info.width, g.info.height, g.info.resolution = w, h, 0.05
    g.info.origin.orientation.w = 1.0
    rows = [pixels[r * w:(r + 1) * w] for r in range(h)]
    g.data = [v if v < 128 else v - 256 for row in reversed(rows) for v in row]
    return g


def node_pid(name):
    master = rosgraph.Master("/soak_driver")
    api = master.lookupNode(name)
    return xmlrpc.client.ServerProxy(api).getPid("/soak_driver")[2]


def rss_kib(pid):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


def main():
    rospy.init_node("soak_driver")
    seconds = float(rospy.get_param("~seconds", 300))
    example = rospy.get_param("~example")
    masks = {t: load_pgm_mask(os.path.join(example, f)) for t, f in [
        ("/keepout_filter_mask", "keepout_mask.pgm"), ("/speed_filter_mask", "speed_mask.pgm"),
        ("/lanes_filter_mask", "lanes_mask.pgm")]}
    mask_pubs = {t: rospy.Publisher(t, OccupancyGrid, queue_size=1, latch=True) for t in masks}
    features_pub = rospy.Publisher("/features", SpeedLimits, queue_size=1, latch=True)
    scan_pub = rospy.Publisher("/scan", LaserScan, queue_size=5)
    cloud_pub = rospy.Publisher("/cloud", PointCloud2, queue_size=5)
    update_pub = rospy.Publisher("/map_updates", OccupancyGridUpdate, queue_size=5)
    tf = tf2_ros.TransformBroadcaster()
    lock = threading.Lock()
    state = {"speeds": [], "overruns": 0, "errors": 0, "updates": 0}

    def on_log(m):
        if m.name != "/costmap_node":
            return
        with lock:
            if "missed its desired rate" in m.msg:
                state["overruns"] += 1
            if m.level >= Log.ERROR:
                state["errors"] += 1

    rospy.Subscriber("/rosout", Log, on_log)
    rospy.Subscriber("/max_speed", MaxSpeed, lambda m: state["speeds"].append(m.max_speed))
    rospy.Subscriber("/costmap_node/costmap_updates", OccupancyGridUpdate,
                     lambda m: state.__setitem__("updates", state["updates"] + 1))
    features = SpeedLimits()
    features.header.frame_id = "map"
    features.limits = [SpeedLimit(1, 0.3), SpeedLimit(2, 0.6)]

    pid = None
    deadline = time.time() + 60
    while pid is None and time.time() < deadline and not rospy.is_shutdown():
        try:
            pid = node_pid("/costmap_node")
        except Exception:
            time.sleep(0.5)
    if pid is None:
        print("soak: costmap_node did not start", flush=True)
        sys.exit(1)

    ranges = [2.0 + 0.5 * math.sin(i * 0.1) for i in range(360)]
    points = [(1.5 * math.cos(a * 0.05), 1.5 * math.sin(a * 0.05), 0.3) for a in range(120)]
    cloud_data = b"".join(struct.pack("<fff", *p) for p in points)
    start = time.time()
    last_second = -1
    rss = []
    rate = rospy.Rate(40)
    k = 0
    while not rospy.is_shutdown():
        now = time.time() - start
        if now > seconds:
            break
        # The robot drives a 6 m circle in speed area 1's neighbourhood; every 20 s it jumps 50 m and back.
        jump = 50.0 if int(now) % 20 == 10 else 0.0
        x, y, yaw = 5.5 + 1.0 * math.cos(now * 0.2) + jump, 1.5 + 0.8 * math.sin(now * 0.2), now * 0.2
        t = TransformStamped()
        t.header.stamp = rospy.Time.now()
        t.header.frame_id, t.child_frame_id = "map", "base_link"
        t.transform.translation.x, t.transform.translation.y = x, y
        t.transform.rotation.z, t.transform.rotation.w = math.sin(yaw / 2), math.cos(yaw / 2)
        tf.sendTransform(t)
        stamp = rospy.Time.now() - rospy.Duration(0.02)
        s = LaserScan()
        s.header.frame_id, s.header.stamp = "base_link", stamp
        s.angle_min, s.angle_increment = -math.pi, 2 * math.pi / 360
        s.angle_max = s.angle_min + s.angle_increment * 359
        s.range_min, s.range_max, s.ranges = 0.1, 10.0, ranges
        scan_pub.publish(s)
        c = PointCloud2()
        c.header.frame_id, c.header.stamp = "base_link", stamp
        c.height, c.width, c.point_step, c.row_step = 1, len(points), 12, 12 * len(points)
        c.fields = [PointField("x", 0, 7, 1), PointField("y", 4, 7, 1), PointField("z", 8, 7, 1)]
        c.data = cloud_data
        cloud_pub.publish(c)
        if int(now) != last_second:
            last_second = int(now)
            for topic, m in masks.items():
                m.header.stamp = rospy.Time.now()
                mask_pubs[topic].publish(m)
            features.header.stamp = rospy.Time.now()
            features_pub.publish(features)
            rss.append((now, rss_kib(pid)))
            if last_second % 10 == 5:  # a burst of malformed input
                bad = OccupancyGrid()
                bad.header.frame_id = "map"
                bad.info.width, bad.info.height, bad.info.resolution = 100000, 100000, 0.0
                bad.data = [0] * 10
                for _ in range(20):
                    mask_pubs["/keepout_filter_mask"].publish(bad)
                    scan_pub.publish(LaserScan(header=s.header, angle_increment=float("nan"), ranges=[1.0] * 5))
                    u = OccupancyGridUpdate(header=t.header, x=-5, y=3999, width=100, height=100, data=[100] * 7)
                    update_pub.publish(u)
                # Stale stamps: a mask and speed limits from long ago, a scan from an hour ago.
                for topic, m in masks.items():
                    mask_pubs[topic].publish(OccupancyGrid(header=Header(stamp=rospy.Time(1), frame_id="map"),
                                                           info=m.info, data=m.data))
                features_pub.publish(SpeedLimits(header=Header(stamp=rospy.Time(1), frame_id="map"),
                                                 limits=features.limits))
                old_scan = LaserScan(header=Header(stamp=stamp - rospy.Duration(3600), frame_id="base_link"),
                                     angle_min=s.angle_min, angle_max=s.angle_max, angle_increment=s.angle_increment,
                                     range_min=s.range_min, range_max=s.range_max, ranges=s.ranges)
                scan_pub.publish(old_scan)
                for topic, m in masks.items():  # and the good masks again
                    mask_pubs[topic].publish(m)
            if last_second % 30 == 0:
                print("soak: %4d s, resident memory %d MiB, overruns %d, /max_speed %s" % (
                    last_second, rss[-1][1] // 1024, state["overruns"],
                    state["speeds"][-1] if state["speeds"] else None), flush=True)
        k += 1
        rate.sleep()

    # Checks. Memory: the mean of the last quarter against the mean just after warm-up (20 %..35 % of
    # the run): allocator noise is a few MiB; a leak of readings or masks would grow steadily.
    n = len(rss)
    warm = [v for t_, v in rss if 0.2 * seconds <= t_ <= 0.35 * seconds]
    late = [v for t_, v in rss[int(0.75 * n):]]
    growth = (sum(late) / len(late) - sum(warm) / len(warm)) / 1024.0 if warm and late else float("nan")
    # /max_speed at a known pose: park in area 1 and wait for the limit.
    deadline = time.time() + 5
    while time.time() < deadline:
        t.header.stamp = rospy.Time.now()
        t.transform.translation.x, t.transform.translation.y = 5.5, 1.5
        tf.sendTransform(t)
        time.sleep(0.05)
    speed = state["speeds"][-1] if state["speeds"] else None
    cycles = int(seconds * 20)
    print("soak: %d s at 20 Hz (%d cycles): resident memory %d -> %d MiB (growth after warm-up %.1f MiB), "
          "%d rate warnings (throttled: each stands for at least one cycle over its period within 5 s), "
          "%d costmap updates received, /max_speed in area 1: %s" % (
              seconds, cycles, rss[0][1] // 1024, rss[-1][1] // 1024, growth, state["overruns"], state["updates"],
              speed), flush=True)
    ok = True
    if not (growth < 16.0):
        print("soak: FAILED: resident memory grew by %.1f MiB after warm-up" % growth, flush=True)
        ok = False
    if speed != 0.3:
        print("soak: FAILED: /max_speed in area 1 is %s, expected 0.3" % speed, flush=True)
        ok = False
    if state["updates"] < seconds:  # at 2 Hz publishing, far fewer than expected means it stopped
        print("soak: FAILED: only %d costmap updates received" % state["updates"], flush=True)
        ok = False
    print("soak: %s" % ("PASSED" if ok else "FAILED"), flush=True)
    rospy.signal_shutdown("done")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
