#!/usr/bin/env python3
"""Republishes a mask with some cell values replaced, for RViz only (no filter reads the copy).

RViz's Map display colours a cell through a fixed palette (map, costmap or raw), in which neighbouring
values look alike: the demo's speed mask holds the area ids 1 and 2, which every palette draws in the
same colour. The copy gives each listed value another one, e.g. ~values "1:90, 2:10" draws area 1
red and area 2 blue in the costmap palette; the other values pass unchanged.

Parameters: ~input and ~output (nav_msgs/OccupancyGrid topics; the copy is latched), ~values ("from:to"
pairs, comma-separated, each a mask value -1..100). A bad parameter stops the node with one FATAL line
naming it and its value, exit 1."""
import array
import sys

import rospy
from nav_msgs.msg import OccupancyGrid


def shown(text, limit=80):
    """text clipped for an error message, control characters as '?'."""
    text = "".join(c if c.isprintable() else "?" for c in str(text))
    return text if len(text) <= limit else text[:limit] + "..."


def parse_values(text):
    """'1:80, 2:30' -> a 256-byte translation table over the cells' bytes (int8 as uint8)."""
    table = bytearray(range(256))
    seen = set()
    for part in str(text).split(","):
        if not part.strip():
            continue
        pair = part.split(":")
        try:
            if len(pair) != 2:
                raise ValueError
            source, target = int(pair[0]), int(pair[1])
        except ValueError:
            raise ValueError("'%s' is not a pair from:to of whole numbers" % shown(part.strip()))
        for v in (source, target):
            if not -1 <= v <= 100:
                raise ValueError("%d is not a mask value (-1..100)" % v)
        if source in seen:
            raise ValueError("value %d is listed twice" % source)
        seen.add(source)
        table[source & 0xFF] = target & 0xFF
    if not seen:
        raise ValueError("lists no pair from:to")
    return bytes(table)


def main():
    rospy.init_node("mask_view")
    node = rospy.get_name()
    text = rospy.get_param("~values", "")
    text = "" if text is None else text
    try:
        table = parse_values(text)
    except ValueError as e:
        rospy.logfatal("%s: parameter %s/values (\"%s\") %s" % (node, node, shown(text), e))
        # rospy sends the line to /rosout from another thread: let it go out before the process ends.
        rospy.sleep(0.5)
        sys.exit(1)
    pub = rospy.Publisher(rospy.get_param("~output", "mask_view"), OccupancyGrid, queue_size=1, latch=True)

    def on_mask(msg):
        cells = array.array("b", msg.data).tobytes().translate(table)
        msg.data = array.array("b", cells).tolist()
        pub.publish(msg)

    rospy.Subscriber(rospy.get_param("~input", "mask"), OccupancyGrid, on_mask, queue_size=1)
    rospy.spin()


if __name__ == "__main__":
    main()
