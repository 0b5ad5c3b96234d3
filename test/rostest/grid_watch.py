"""Shared by the Python rostests: follows a costmap node's ~costmap and ~costmap_updates, and
translates costs the way costmap_2d publishes them."""
import threading

import rospy
from geometry_msgs.msg import PoseStamped
from map_msgs.msg import OccupancyGridUpdate
from nav_msgs.msg import OccupancyGrid


def translate(cost):
    """costmap_2d's cost -> OccupancyGrid value: 0 -> 0, 1..252 -> 1..98, 253 -> 99, 254 -> 100, 255 -> -1."""
    if cost == 0:
        return 0
    if cost == 253:
        return 99
    if cost == 254:
        return 100
    if cost == 255:
        return -1
    return 1 + (97 * (cost - 1)) // 251


class GridWatcher:
    """Keeps the latest costmap of a node, applying its updates."""

    def __init__(self, ns):
        self.cond = threading.Condition()
        self.data = None
        self.width = self.height = 0
        self.resolution = 0.0
        self.origin = (0.0, 0.0)
        self.count = 0  # grids and updates received, to wait for one that came after an action
        rospy.Subscriber(ns + "/costmap", OccupancyGrid, self._on_grid)
        rospy.Subscriber(ns + "/costmap_updates", OccupancyGridUpdate, self._on_update)

    def _on_grid(self, msg):
        with self.cond:
            self.data = list(msg.data)
            self.width = msg.info.width
            self.height = msg.info.height
            # info.resolution is a float32: 0.1 arrives as 0.10000000149, which would put 5.0 m in cell 49.
            self.resolution = round(msg.info.resolution, 6)
            self.origin = (msg.info.origin.position.x, msg.info.origin.position.y)
            self.count += 1
            self.cond.notify_all()

    def _on_update(self, msg):
        with self.cond:
            if self.data is None:
                return
            for j in range(msg.height):
                row = (msg.y + j) * self.width + msg.x
                self.data[row:row + msg.width] = msg.data[j * msg.width:(j + 1) * msg.width]
            self.count += 1
            self.cond.notify_all()

    def at(self, x, y):
        """The value of the cell containing (x, y) [m], for a grid with its origin at (0, 0)."""
        return self.data[int(y / self.resolution) * self.width + int(x / self.resolution)]

    def wait_until(self, predicate, timeout):
        """Waits (on arrivals, not on a fixed sleep) until predicate(self) holds; returns whether it does."""
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        with self.cond:
            while not rospy.is_shutdown() and rospy.Time.now() < deadline:
                if self.data is not None and predicate(self):
                    return True
                self.cond.wait(0.5)
            return self.data is not None and predicate(self)

    def snapshot(self):
        with self.cond:
            return None if self.data is None else list(self.data)


class CycleWatcher:
    """Counts a costmap node's update cycles (it publishes ~footprint once a cycle), so that a test can
    wait for the node to have run N more cycles instead of sleeping for a guessed time."""

    def __init__(self, ns):
        from geometry_msgs.msg import PolygonStamped
        self.cond = threading.Condition()
        self.cycles = 0
        rospy.Subscriber(ns + "/footprint", PolygonStamped, self._on_cycle)

    def _on_cycle(self, _):
        with self.cond:
            self.cycles += 1
            self.cond.notify_all()

    def wait(self, n, timeout=30.0):
        """Waits until n more cycles ran; returns whether they did within timeout [s]."""
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        with self.cond:
            target = self.cycles + n
            while self.cycles < target and not rospy.is_shutdown() and rospy.Time.now() < deadline:
                self.cond.wait(0.5)
            return self.cycles >= target


def logged_with_key(lines, key, *values):
    """The log lines that end with the stable key "[key]" and contain each value as a whole token."""
    import re
    pats = [re.compile(r"(?<![\w.])" + re.escape(v) + r"(?![\w])") for v in values]
    tag = "[" + key + "]"
    return [m for m in lines if m.rstrip().endswith(tag) and all(p.search(m) for p in pats)]


class ErrorLog:
    """Collects the error lines (and worse; from `level` on when given, e.g. Log.WARN) one node writes
    to /rosout, and waits, as they arrive (no fixed sleep), for one that carries a key and values
    (logged_with_key)."""

    def __init__(self, node, level=None):
        from rosgraph_msgs.msg import Log
        self.node, self.error = node, Log.ERROR if level is None else level
        self.lines = []
        self.cond = threading.Condition()
        self.sub = rospy.Subscriber("/rosout", Log, self._on_log)

    def _on_log(self, m):
        if m.name == self.node and m.level >= self.error:
            with self.cond:
                self.lines.append(m.msg)
                self.cond.notify_all()

    def wait(self, key, values, timeout):
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        with self.cond:
            while not logged_with_key(self.lines, key, *values) and not rospy.is_shutdown() \
                    and rospy.Time.now() < deadline:
                self.cond.wait(0.2)
            return logged_with_key(self.lines, key, *values)


class Latest:
    """The latest message on a topic (and how many came), with a wait on a condition of it."""

    def __init__(self, topic, cls):
        self.cond = threading.Condition()
        self.msg = None
        self.count = 0
        rospy.Subscriber(topic, cls, self._on_msg)

    def _on_msg(self, m):
        with self.cond:
            self.msg = m
            self.count += 1
            self.cond.notify_all()

    def wait(self, predicate, timeout):
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        with self.cond:
            while not (self.msg is not None and predicate(self.msg)) and not rospy.is_shutdown() \
                    and rospy.Time.now() < deadline:
                self.cond.wait(0.2)
            return self.msg is not None and predicate(self.msg)


def occupancy_grid(width, height, resolution, data, frame="map", ox=0.0, oy=0.0, stamp=None):
    """An OccupancyGrid as given, unchecked (the rostests also build malformed ones), origin (ox, oy)
    unrotated, stamped now unless `stamp` is given."""
    g = OccupancyGrid()
    g.header.frame_id = frame
    g.header.stamp = rospy.Time.now() if stamp is None else stamp
    g.info.width, g.info.height, g.info.resolution = width, height, resolution
    g.info.origin.position.x, g.info.origin.position.y = ox, oy
    g.info.origin.orientation.w = 1.0
    g.data = data
    return g


def publish_row_mask(topic, values):
    """Publishes, latched, a mask of one row of 1 m cells in the map frame (values along x from the
    origin, stamp 0); returns the publisher, which must be kept for the latch to last."""
    pub = rospy.Publisher(topic, OccupancyGrid, queue_size=1, latch=True)
    pub.publish(occupancy_grid(len(values), 1, 1.0, values, stamp=rospy.Time()))
    return pub


def map_pose(x, y):
    """A pose at (x, y) in the map frame, facing +x (a make_plan start or goal)."""
    p = PoseStamped()
    p.header.frame_id = "map"
    p.pose.position.x, p.pose.position.y = x, y
    p.pose.orientation.w = 1.0
    return p
