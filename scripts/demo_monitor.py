#!/usr/bin/env python3
"""Watches the demo: prints every /max_speed change and every binary state change (/camera_off) with
the robot's position, counts the lone obstacle cells in each local costmap (/local_costmap/costmap,
where the DenoiseLayer should have left none of the lidar's false returns), and when the robot has
finished its route prints a summary and exits (which ends the demo launch)."""
import math

import rospy
import tf2_ros
from costmap_layers.msg import MaxSpeed
from nav_msgs.msg import OccupancyGrid
from std_msgs.msg import Bool


def lone_cells(msg):
    """(obstacle cells, those with no obstacle among their 8 neighbours) of an OccupancyGrid."""
    w, h, d = msg.info.width, msg.info.height, msg.data
    lethal = [i for i, v in enumerate(d) if v == 100]
    lone = 0
    for i in lethal:
        x, y = i % w, i // w
        if not any(d[(y + dy) * w + x + dx] == 100
                   for dy in (-1, 0, 1) for dx in (-1, 0, 1)
                   if (dx or dy) and 0 <= x + dx < w and 0 <= y + dy < h):
            lone += 1
    return len(lethal), lone


def main():
    rospy.init_node("demo_monitor")
    global_frame = rospy.get_param("~global_frame", "map")
    base_frame = rospy.get_param("~robot_base_frame", "base_link")
    route = [tuple(float(v) for v in p.split(",")) for p in rospy.get_param("~route").split(";") if p.strip()]
    timeout = float(rospy.get_param("~timeout", 120.0))
    pictures = rospy.get_param("~pictures", "")
    buffer = tf2_ros.Buffer()
    tf2_ros.TransformListener(buffer)
    changes = []

    def pose():
        try:
            t = buffer.lookup_transform(global_frame, base_frame, rospy.Time(0), rospy.Duration(0.5))
            return t.transform.translation.x, t.transform.translation.y
        except tf2_ros.TransformException:
            return float("nan"), float("nan")

    def on_speed(msg):
        x, y = pose()
        limit = "no limit" if msg.max_speed == 0.0 else "%.2f m/s" % msg.max_speed
        changes.append((msg.max_speed, x, y))
        print("demo: max_speed -> %-9s at robot position (%.2f, %.2f)" % (limit, x, y), flush=True)

    rospy.Subscriber(rospy.get_param("~max_speed_topic", "/max_speed"), MaxSpeed, on_speed)
    states = []

    def on_state(msg):
        x, y = pose()
        states.append(msg.data)
        print("demo: camera_off -> %-5s at robot position (%.2f, %.2f)" % (msg.data, x, y), flush=True)

    rospy.Subscriber(rospy.get_param("~binary_state_topic", "/camera_off"), Bool, on_state)
    local = {"maps": 0, "lone": 0, "obstacles": 0}

    def on_local(msg):
        obstacles, lone = lone_cells(msg)
        local["maps"] += 1
        local["lone"] = max(local["lone"], lone)
        local["obstacles"] = obstacles

    rospy.Subscriber(rospy.get_param("~local_costmap_topic", "/local_costmap/costmap"), OccupancyGrid, on_local)
    start = rospy.Time.now()
    at_goal_since = None
    goal = route[-1]
    while not rospy.is_shutdown():
        x, y = pose()
        if not math.isnan(x) and math.hypot(x - goal[0], y - goal[1]) < 0.05:
            at_goal_since = at_goal_since or rospy.Time.now()
            if (rospy.Time.now() - at_goal_since).to_sec() > 1.5:
                break
        if (rospy.Time.now() - start).to_sec() > timeout:
            print("demo: the robot did not finish its route within %.0f s" % timeout, flush=True)
            break
        rospy.sleep(0.1)
    print("demo: summary: the robot drove %d waypoints; /max_speed changed %d times: %s" % (
        len(route), len(changes), " -> ".join("%.2f" % c[0] for c in changes)), flush=True)
    print("demo: summary: /camera_off changed %d times: %s" % (
        len(states), " -> ".join(str(s) for s in states)), flush=True)
    print("demo: summary: the lidar sent %d false returns; the local costmap had at most %d lone obstacle "
          "cells in %d maps (its denoise_layer removes them; %d obstacle cells, walls, in the last)" % (
              int(rospy.get_param("/fake_scan/speckles_sent", 0)), local["lone"], local["maps"],
              local["obstacles"]), flush=True)
    if pictures:
        print("demo: pictures of the published costmap: %s" % pictures, flush=True)


if __name__ == "__main__":
    main()
