#!/usr/bin/env python3
"""The listener of scripts/bench_move_base_cpu.sh (issue 38), in one of two modes.

~mode count: counts the local costmap messages (full grids and updates) each move_base in ~ns (a
space-separated list) publishes between the wall times ~start and ~end (seconds since the epoch),
prints one line per move_base after ~end, and exits. A costmap_node publishing its diagnostics as
<ns>/local_costmap also gets its update cycles in the window (from the "cycles" its costmap status
counts, read once a second) and the longest cycle it reported.

~mode agree: listens to the local costmaps of ~a and ~b (two move_base instances running at once in
the same world) until ~end and, for every grid of ~b published within ~pair_s seconds of ~a's latest,
counts the lethal cells both hold among those either holds, over the cells both windows cover
(cells by their place in the world: rolling windows move in whole cells). Grids published while the
world is paused (/cpu_world/paused, after ~settle_s seconds of it) are tallied apart from those
published while it moves. Prints the mean, minimum and maximum of each tally.
"""
import threading
import time

import rospy
from diagnostic_msgs.msg import DiagnosticArray
from map_msgs.msg import OccupancyGridUpdate
from nav_msgs.msg import OccupancyGrid

LETHAL = 100  # costmap_2d's publisher writes LETHAL_OBSTACLE (254) as 100
LOCK = threading.Lock()  # the subscribers' callbacks run in threads of their own


class Grid:
    """The latest local costmap of one move_base: its full grid with the updates applied."""

    def __init__(self, ns, on_grid=None):
        self.ns = ns
        self.full = 0
        self.updates = 0
        self.data = None
        self.info = None
        self.stamp = None
        self.arrivals = []
        self.on_grid = on_grid
        rospy.Subscriber(ns + "/local_costmap/costmap", OccupancyGrid, self.on_full, queue_size=10)
        rospy.Subscriber(ns + "/local_costmap/costmap_updates", OccupancyGridUpdate, self.on_update,
                         queue_size=10)

    def on_full(self, msg):
        with LOCK:
            self.take_full(msg)

    def take_full(self, msg):
        self.full += 1
        self.arrivals.append(time.time())
        self.info = msg.info
        self.data = list(msg.data)
        self.stamp = msg.header.stamp.to_sec()
        if self.on_grid:
            self.on_grid(self)

    def on_update(self, msg):
        with LOCK:
            self.take_update(msg)

    def take_update(self, msg):
        self.updates += 1
        self.arrivals.append(time.time())
        if self.data is None:
            return
        w = self.info.width
        for r in range(msg.height):
            start = (msg.y + r) * w + msg.x
            self.data[start:start + msg.width] = msg.data[r * msg.width:(r + 1) * msg.width]
        self.stamp = msg.header.stamp.to_sec()
        if self.on_grid:
            self.on_grid(self)

    def lethal(self):
        """Lethal cells as (i, j) in the world's lattice of this grid's resolution, and the window."""
        res = self.info.resolution
        oi = int(round(self.info.origin.position.x / res))
        oj = int(round(self.info.origin.position.y / res))
        w = self.info.width
        cells = {(oi + k % w, oj + k // w) for k, v in enumerate(self.data) if v == LETHAL}
        return cells, (oi, oj, oi + w, oj + self.info.height)


class Cycles:
    """A costmap_node's local costmap status: (arrival, cycles) within the window, the longest cycle."""

    def __init__(self, ns, start, end):
        self.name = ns.strip("/") + "/local_costmap: costmap"
        self.start, self.end = start, end
        self.samples = []
        self.longest = 0.0
        rospy.Subscriber("/diagnostics", DiagnosticArray, self.on_diagnostics, queue_size=20)

    def on_diagnostics(self, msg):
        now = time.time()
        if not self.start <= now < self.end:
            return
        for status in msg.status:
            if status.name.strip("/") != self.name:
                continue
            values = {kv.key: kv.value for kv in status.values}
            with LOCK:
                if "cycles" in values:
                    self.samples.append((now, int(values["cycles"])))
                self.longest = max(self.longest, float(values.get("longest cycle since last report [s]", 0.0)))

    def report(self):
        with LOCK:
            if len(self.samples) < 2:
                return
            (t0, c0), (t1, c1) = self.samples[0], self.samples[-1]
        # The cycles between the first and the last report, scaled to the whole window.
        n = (c1 - c0) * (self.end - self.start) / (t1 - t0)
        print("monitor: %s local costmap update cycles in the window: %.0f (%.2f Hz); longest cycle: %.3f s"
              % (self.name, n, n / (self.end - self.start), self.longest), flush=True)


def count(namespaces, start, end):
    grids = [Grid(ns) for ns in namespaces]
    cycles = [Cycles(ns, start, end) for ns in namespaces]
    while not rospy.is_shutdown() and time.time() < end + 0.5:
        time.sleep(0.1)
    for g in grids:
        with LOCK:
            n = sum(1 for t in g.arrivals if start <= t < end)
        print("monitor: %s local costmap messages in the window: %d (%.2f Hz)" % (g.ns, n, n / (end - start)),
              flush=True)
    for c in cycles:
        c.report()


class Agreement:
    def __init__(self, a, b, start, pair_s, settle_s):
        self.start = start
        self.pair_s = pair_s
        self.settle_s = settle_s
        self.paused_since = None
        self.tallies = {"moving": [], "paused": []}
        self.a = Grid(a)
        self.b = Grid(b, self.compare)

    def poll_pause(self):
        paused = rospy.get_param("/cpu_world/paused", False)
        if paused and self.paused_since is None:
            self.paused_since = time.time()
        elif not paused:
            self.paused_since = None

    def compare(self, b):
        a = self.a
        if time.time() < self.start or a.data is None or abs(a.stamp - b.stamp) > self.pair_s:
            return
        if abs(a.info.resolution - b.info.resolution) > 1e-9:
            return
        if self.paused_since is None:
            kind = "moving"
        elif time.time() - self.paused_since >= self.settle_s:
            kind = "paused"
        else:
            return
        la, wa = a.lethal()
        lb, wb = b.lethal()
        lo_i, lo_j = max(wa[0], wb[0]), max(wa[1], wb[1])
        hi_i, hi_j = min(wa[2], wb[2]), min(wa[3], wb[3])

        def inside(c):
            return lo_i <= c[0] < hi_i and lo_j <= c[1] < hi_j

        la = {c for c in la if inside(c)}
        lb = {c for c in lb if inside(c)}
        either = la | lb
        if either:
            self.tallies[kind].append((len(la & lb) / len(either), len(la), len(lb)))

    def report(self):
        for kind, t in self.tallies.items():
            if not t:
                print("monitor: agreement (%s): no pair of grids" % kind, flush=True)
                continue
            with LOCK:
                shares = [x[0] for x in t]
            print("monitor: lethal cells both local costmaps hold among those either holds (%s world, %d pairs): "
                  "mean %.1f %%, min %.1f %%, max %.1f %%; lethal cells A %.0f, B %.0f on average"
                  % (kind, len(t), 100 * sum(shares) / len(t), 100 * min(shares), 100 * max(shares),
                     sum(x[1] for x in t) / len(t), sum(x[2] for x in t) / len(t)), flush=True)


def main():
    rospy.init_node("cpu_monitor")
    mode = rospy.get_param("~mode", "count")
    end = float(rospy.get_param("~end"))
    if mode == "count":
        count(rospy.get_param("~ns").split(), float(rospy.get_param("~start")), end)
        return
    agreement = Agreement(rospy.get_param("~a"), rospy.get_param("~b"), float(rospy.get_param("~start")),
                          float(rospy.get_param("~pair_s", 0.05)),
                          float(rospy.get_param("~settle_s", 3.0)))
    while not rospy.is_shutdown() and time.time() < end:
        agreement.poll_pause()
        time.sleep(0.2)
    agreement.report()


if __name__ == "__main__":
    main()
