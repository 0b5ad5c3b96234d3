#!/usr/bin/env python3
"""zone_server through real topics and services. The expected masks are computed here from the
documented rules with another method than the server's (a same-side test for convex polygons, the
distance to the centre for circles, the extent from the shapes' bounding boxes): the initial mask; a
marker feedback message (as RViz sends it when a vertex is dragged) that moves a vertex changes the
mask to the one of the moved polygon; the save service writes a file that another zone_server
loads to the very same mask; bad shapes and a self-intersecting drag are refused and change nothing."""
import math
import os
import shutil
import sys
import tempfile
import threading
import time
import unittest

import rospy
import rostest
from costmap_layers.msg import ZoneShapeDescription as ZoneShape
from costmap_layers.srv import LoadZones, RemoveZoneShape, SaveZones, SetZoneShape
from geometry_msgs.msg import Point
from nav_msgs.msg import OccupancyGrid
from rosgraph_msgs.msg import Log
from visualization_msgs.msg import InteractiveMarkerFeedback, InteractiveMarkerInit

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from grid_watch import ErrorLog, Latest, logged_with_key  # noqa: E402

RES = 0.1
DOCK = [(1.02, 1.03), (2.97, 1.03), (2.97, 2.04), (1.02, 2.04)]
SLOW = ((4.0, 1.5), 0.72)


def expected_mask(polygons, circles, res=RES):
    """(origin_x, origin_y, width, height, data) for filled convex counter-clockwise polygons and
    filled circles applied in order, later ones winning (overlay last), default 0."""
    xs, ys = [], []
    for pts, _ in polygons:
        xs += [p[0] for p in pts]
        ys += [p[1] for p in pts]
    for (c, r), _ in circles:
        xs += [c[0] - r, c[0] + r]
        ys += [c[1] - r, c[1] + r]
    i0, i1 = math.floor(min(xs) / res) - 1, math.floor(max(xs) / res) + 1
    j0, j1 = math.floor(min(ys) / res) - 1, math.floor(max(ys) / res) + 1
    w, h = i1 - i0 + 1, j1 - j0 + 1
    data = [0] * (w * h)
    for j in range(h):
        y = (j0 + j + 0.5) * res
        for i in range(w):
            x = (i0 + i + 0.5) * res
            for pts, value in polygons:
                n = len(pts)
                if all((pts[(k + 1) % n][0] - pts[k][0]) * (y - pts[k][1]) -
                       (pts[(k + 1) % n][1] - pts[k][1]) * (x - pts[k][0]) > 0 for k in range(n)):
                    data[j * w + i] = value
            for (c, r), value in circles:
                if (x - c[0]) ** 2 + (y - c[1]) ** 2 <= r * r:
                    data[j * w + i] = value
    return i0 * res, j0 * res, w, h, data


def matches(expected):
    ox, oy, w, h, data = expected

    def check(m):
        return (m.info.width == w and m.info.height == h and abs(m.info.origin.position.x - ox) < 1e-9
                and abs(m.info.origin.position.y - oy) < 1e-9 and list(m.data) == data
                and m.header.frame_id == "map")
    return check


class ZoneServerTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_zone_server")
        cls.log = ErrorLog("/zone_server", Log.WARN)  # warnings too
        cls.info = ErrorLog("/zone_server", Log.INFO)  # every line, to count the mask's INFO lines
        cls.mask = Latest("/zone_mask", OccupancyGrid)
        cls.reloaded = Latest("/zone_mask_reloaded", OccupancyGrid)
        # A queue for a whole burst: rospy drops what does not fit, and the burst case sends 300.
        cls.feedback = rospy.Publisher("/zone_server/feedback", InteractiveMarkerFeedback, queue_size=1000)
        for name in ["set_shape", "remove_shape", "save", "load"]:
            rospy.wait_for_service("/zone_server/" + name, 30.0)
        rospy.wait_for_service("/zone_reloaded/load", 30.0)
        cls.set_shape = rospy.ServiceProxy("/zone_server/set_shape", SetZoneShape)
        cls.remove_shape = rospy.ServiceProxy("/zone_server/remove_shape", RemoveZoneShape)
        cls.save = rospy.ServiceProxy("/zone_server/save", SaveZones)
        cls.load_reloaded = rospy.ServiceProxy("/zone_reloaded/load", LoadZones)
        deadline = rospy.Time.now() + rospy.Duration(30.0)
        while cls.feedback.get_num_connections() == 0 and rospy.Time.now() < deadline:
            rospy.sleep(0.05)  # polling a condition (the subscriber's connection), with a deadline
        cls.tmp = tempfile.mkdtemp(prefix="zone_server_test_")  # outside the save directory
        cls.save_dir = rospy.get_param("/zone_server/save_directory")
        os.makedirs(cls.save_dir)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)
        shutil.rmtree(cls.save_dir, ignore_errors=True)

    def drag(self, marker, x, y):
        f = InteractiveMarkerFeedback()
        f.header.frame_id = "map"
        f.header.stamp = rospy.Time.now()
        f.client_id = "/test_zone_server"
        f.marker_name = marker
        f.event_type = InteractiveMarkerFeedback.POSE_UPDATE
        f.pose.position.x = x
        f.pose.position.y = y
        f.pose.orientation.w = 1.0
        self.feedback.publish(f)

    def test_drag_a_vertex_then_save_and_reload(self):
        initial = expected_mask([(DOCK, 100)], [(SLOW, 40)])
        self.assertTrue(self.mask.wait(matches(initial), 30.0), "the initial mask is not the expected one")
        self.assertGreater(initial[4].count(100), 150)  # 19 x 10 cells
        # Drag dock's vertex 2 from (2.97, 2.04) to (3.46, 2.57), as RViz would; dock is put back as the
        # file has it at the end, and the case ends only once the mask shows it back: the next case then
        # starts on a settled mask (test_handles_are_capped compares its end with its start, and saw the
        # put-back arrive in between).
        def put_dock_back():
            self.set_shape(ZoneShape(name="dock", type="polygon", value=100, fill=True,
                                     points=[Point(x, y, 0.0) for x, y in DOCK]))
            self.assertTrue(self.mask.wait(matches(initial), 20.0), "dock was not put back")

        self.addCleanup(put_dock_back)
        moved = [DOCK[0], DOCK[1], (3.46, 2.57), DOCK[3]]
        expected = expected_mask([(moved, 100)], [(SLOW, 40)])
        self.assertNotEqual(expected[4], initial[4])
        self.drag("dock/2", 3.46, 2.57)
        self.assertTrue(self.mask.wait(matches(expected), 20.0), "the dragged vertex did not move the zone")
        # Save, and make the other server load the file: the same mask, cell for cell.
        path = os.path.join(self.save_dir, "saved.yaml")
        res = self.save(path)
        self.assertTrue(res.success, res.message)
        self.assertTrue(os.path.isfile(path))
        res = self.load_reloaded(path)
        self.assertTrue(res.success, res.message)
        self.assertTrue(self.reloaded.wait(matches(expected), 20.0), "the saved file did not reload to the same mask")
        a, b = self.mask.msg, self.reloaded.msg
        self.assertEqual(a.info.resolution, b.info.resolution)
        self.assertEqual(list(a.data), list(b.data))

    def test_bad_input_changes_nothing(self):
        self.assertTrue(self.mask.wait(lambda m: True, 30.0))
        before = self.mask.msg  # whatever the other case left: this one only checks that nothing changes
        bad = ZoneShape(name="tri", type="polygon", value=100, fill=True,
                        points=[Point(0.0, 0.0, 0.0), Point(1.0, 0.0, 0.0)])
        res = self.set_shape(bad)
        self.assertFalse(res.success)
        self.assertIn("at least 3 points", res.message)
        bow = ZoneShape(name="bow", type="polygon", value=100, fill=True,
                        points=[Point(0, 0, 0), Point(1, 1, 0), Point(1, 0, 0), Point(0, 1, 0)])
        res = self.set_shape(bow)
        self.assertFalse(res.success)
        self.assertIn("self-intersecting", res.message)
        nan = ZoneShape(name="nan", type="circle", value=100, fill=True, center=Point(float("nan"), 0, 0),
                        radius=1.0)
        self.assertFalse(self.set_shape(nan).success)
        huge = ZoneShape(name="huge", type="circle", value=100, fill=True, center=Point(0, 0, 0), radius=5e6)
        res = self.set_shape(huge)
        self.assertFalse(res.success)
        self.assertIn("cells a mask may have", res.message)
        self.assertFalse(self.set_shape(ZoneShape(name="x", type="ellipse", value=1)).success)
        self.assertFalse(self.remove_shape("no_such_shape").success)
        # A drag that makes dock self-intersecting (vertex 0 above the top edge, with or without the
        # other case's drag): refused, reported, the handle put back, the mask unchanged.
        self.drag("dock/0", 2.0, 3.0)
        self.assertTrue(self.log.wait("/zone_server/shapes/dock/points", [], 20.0),
                        "the self-intersecting drag was not reported")
        self.assertEqual(list(self.mask.msg.data), list(before.data))
        # A good shape appears, and goes again when removed.
        extra = ZoneShape(name="extra", type="circle", value=55, fill=True, center=Point(-3.0, -3.0, 0), radius=0.5)
        res = self.set_shape(extra)
        self.assertTrue(res.success, res.message)
        self.assertTrue(self.mask.wait(lambda m: 55 in m.data, 20.0))
        self.assertTrue(self.remove_shape("extra").success)
        self.assertTrue(self.mask.wait(lambda m: 55 not in m.data and list(m.data) == list(before.data), 20.0))

    def test_hostile_requests_are_refused_briefly(self):
        """Huge arrays, huge names, NaN and infinity, feedback in no frame: each refused with a short
        answer or a keyed error, the mask unchanged; the test's own square is removed at the end."""
        self.assertTrue(self.mask.wait(lambda m: True, 30.0))
        before = list(self.mask.msg.data)
        square = ZoneShape(name="hostile_sq", type="polygon", value=77, fill=True,
                           points=[Point(-2.0, -2.0, 0), Point(-1.0, -2.0, 0), Point(-1.0, -1.0, 0),
                                   Point(-2.0, -1.0, 0)])
        res = self.set_shape(square)
        self.assertTrue(res.success, res.message)
        self.addCleanup(self.remove_shape, "hostile_sq")  # gone even when a check fails: no order dependence
        self.assertTrue(self.mask.wait(lambda m: 77 in m.data, 20.0))
        with_square = list(self.mask.msg.data)
        count = self.mask.count

        # 10^6 vertices: refused by count.
        many = ZoneShape(name="many", type="polygon", value=10, fill=True,
                         points=[Point(math.cos(k * 1e-6), math.sin(k * 1e-6), 0) for k in range(1000000)])
        res = self.set_shape(many)
        self.assertFalse(res.success)
        self.assertIn("at most 1000 points", res.message)
        # A name of 10^6 characters: refused; neither the answer nor the key carries it whole.
        res = self.set_shape(ZoneShape(name="n" * 1000000, type="circle", value=10, center=Point(0, 0, 0), radius=1.0))
        self.assertFalse(res.success)
        self.assertLess(len(res.message), 300)
        self.assertTrue(self.log.wait("/zone_server/shapes/(bad name)/name", ["1000000"], 20.0),
                        "the huge name was not reported by its fixed key")
        self.assertTrue(all(len(m) < 1000 for m in self.log.lines), "a log line carries the huge name")
        # NaN and infinity in every number.
        for shape in [ZoneShape(name="c", type="circle", value=10, center=Point(0, float("inf"), 0), radius=1.0),
                      ZoneShape(name="c", type="circle", value=10, center=Point(0, 0, 0), radius=float("nan")),
                      ZoneShape(name="c", type="circle", value=10, center=Point(0, 0, 0), radius=float("inf")),
                      ZoneShape(name="p", type="polygon", value=10,
                                points=[Point(0, 0, 0), Point(float("nan"), 0, 0), Point(1, 1, 0)])]:
            res = self.set_shape(shape)
            self.assertFalse(res.success, "accepted %s" % shape)
        # A polygon of 1000 vertices 400 km tall at 0.1 m/cell: a grid within the cell limit, but
        # 4e9 crossing searches to draw: refused at once instead of holding the server for minutes.
        tall = [Point(1.0, 4e5 * k / 997.0, 0) for k in range(998)] + [Point(0.0, 4e5, 0), Point(0.0, 0.0, 0)]
        res = self.set_shape(ZoneShape(name="tall", type="polygon", value=10, fill=True, points=tall))
        self.assertFalse(res.success)
        self.assertIn("cell visits", res.message)
        # File names longer than any path: refused, answered briefly.
        long_name = "/tmp/" + "f" * 100000
        for call in (self.save, rospy.ServiceProxy("/zone_server/load", LoadZones)):
            res = call(long_name)
            self.assertFalse(res.success)
            self.assertLess(len(res.message), 300)
        # Files that are not YAML by their name are neither read nor written: a peer could otherwise
        # overwrite any file the server may write, or read back the first line of any it may read.
        load = rospy.ServiceProxy("/zone_server/load", LoadZones)
        for name in ["/etc/hostname", "/etc/passwd", os.path.join(self.tmp, "zones.yaml.bak")]:
            res = load(name)
            self.assertFalse(res.success, name)
            self.assertIn(".yaml or .yml", res.message)
        target = os.path.join(self.tmp, "not_yaml.txt")
        with open(target, "w") as f:
            f.write("keep me\n")
        res = self.save(target)
        self.assertFalse(res.success)
        self.assertIn(".yaml or .yml", res.message)
        with open(target) as f:
            self.assertEqual(f.read(), "keep me\n")
        # A YAML file that is not a zone file: refused without quoting it.
        secret = os.path.join(self.save_dir, "secret.yaml")
        with open(secret, "w") as f:
            f.write("token: hunter2\n")
        res = load(secret)
        self.assertFalse(res.success)
        self.assertIn("not a zone file", res.message)
        self.assertNotIn("hunter2", res.message)
        self.assertNotIn("token", res.message)
        # Marker feedback: a drag of the square's vertex 2 to a valid place, but in no frame; then to a
        # NaN position. Each refused by its key; the mask is still the one with the square.
        f = InteractiveMarkerFeedback()
        f.client_id = "/test_zone_server"
        f.marker_name = "hostile_sq/2"
        f.event_type = InteractiveMarkerFeedback.POSE_UPDATE
        f.pose.position.x, f.pose.position.y = -0.5, -0.5
        f.pose.orientation.w = 1.0
        f.header.frame_id = ""
        self.feedback.publish(f)
        self.assertTrue(self.log.wait("/zone_server/feedback/header.frame_id", [], 20.0),
                        "feedback in no frame was not refused")
        # A NaN position, stamped far in the future with a zero quaternion (neither plays a part).
        f.header.frame_id = "map"
        f.header.stamp = rospy.Time(2 ** 31)
        f.pose.position.x = float("nan")
        f.pose.orientation.w = 0.0
        self.feedback.publish(f)
        self.assertTrue(self.log.wait("/zone_server/shapes/hostile_sq/points", ["nan"], 20.0),
                        "the NaN drag was not refused")
        self.assertEqual(self.mask.count, count, "a refused request republished the mask")
        self.assertEqual(list(self.mask.msg.data), with_square)
        self.assertTrue(self.remove_shape("hostile_sq").success)
        self.assertTrue(self.mask.wait(lambda m: list(m.data) == before, 20.0))

    def test_handles_are_capped(self):
        """Ten shapes of 1000 vertices: handles are offered for whole shapes in order up to 10 000
        (limits::kMaxZoneHandles), the rest is left out with a keyed warning; removed at the end."""
        self.assertTrue(self.mask.wait(lambda m: True, 30.0))
        before = list(self.mask.msg.data)
        inits = []
        cond = threading.Condition()

        def on_init(m):
            with cond:
                inits.append(set(mk.name for mk in m.markers))
                cond.notify_all()

        def handles(names):
            return sorted(h for h in names if "/" in h and not h.endswith("/outline"))
        sub = rospy.Subscriber("/zone_server/update_full", InteractiveMarkerInit, on_init)
        with cond:
            self.assertTrue(cond.wait_for(lambda: inits, 30.0), "no update_full")
            handles_before = len(handles(inits[-1]))
        names = ["big%d" % k for k in range(10)]
        for k, name in enumerate(names):
            ring = [Point(-30.0 + 2.0 * k + 0.5 * math.cos(2 * math.pi * v / 1000),
                          10.0 + 0.5 * math.sin(2 * math.pi * v / 1000), 0) for v in range(1000)]
            res = self.set_shape(ZoneShape(name=name, type="polygon", value=20, fill=True, points=ring))
            self.assertTrue(res.success, res.message)
            self.addCleanup(self.remove_shape, name)  # gone even when a check fails: no order dependence
        offered = (10000 - handles_before) // 1000  # whole shapes, in order, after those already there
        self.assertLess(offered, len(names))
        with cond:  # the markers after the last shape came: its outline is drawn, with or without handles
            self.assertTrue(cond.wait_for(lambda: names[-1] + "/outline" in inits[-1], 30.0),
                            "no update_full with big9")
            last = handles(inits[-1])
        self.assertIn("big%d/999" % (offered - 1), last)
        self.assertFalse([h for h in last if h.startswith("big%d/" % offered)], "a shape past the limit has handles")
        self.assertLessEqual(len(last), 10000)
        self.assertTrue(self.log.wait("/zone_server/markers", ["10000"], 20.0), "no keyed warning")
        sub.unregister()
        for name in names:
            self.assertTrue(self.remove_shape(name).success)
        self.assertTrue(self.mask.wait(lambda m: list(m.data) == before, 20.0))

    def test_save_stays_in_its_directory(self):
        """~save and ~load name files only inside ~save_directory; a file there that is not a zone file
        is not replaced. Issue 34: '<dir>/sub/../robot/params.yaml' replaced a robot's parameters."""
        robot = os.path.join(self.tmp, "robot")
        os.makedirs(robot, exist_ok=True)
        params = os.path.join(robot, "params.yaml")
        with open(params, "w") as f:
            f.write("robot_radius: 0.3\n")
        escape = os.path.join(self.save_dir, "escape")
        if not os.path.islink(escape):
            os.symlink(robot, escape)
        os.makedirs(os.path.join(self.save_dir, "sub"), exist_ok=True)
        load = rospy.ServiceProxy("/zone_server/load", LoadZones)
        rel = os.path.relpath(params, os.path.join(self.save_dir, "sub"))  # ../../<tmp>/robot/params.yaml
        for name, why in [(os.path.join(self.save_dir, "sub", rel), "'..'"), (rel, "'..'"),
                          (params, "outside the save directory"), ("escape/params.yaml", "outside the save directory"),
                          ("escape/new.yaml", "outside the save directory"), ("bad\nname.yaml", "character code 10")]:
            res = self.save(name)
            self.assertFalse(res.success, name)
            self.assertIn(why, res.message)
            self.assertNotIn("\n", res.message)
            res = load(name)
            self.assertFalse(res.success, name)
            self.assertIn(why, res.message)
        with open(params) as f:
            self.assertEqual(f.read(), "robot_radius: 0.3\n")
        self.assertFalse(os.path.exists(os.path.join(robot, "new.yaml")))
        self.assertTrue(self.log.wait("/zone_server/save/filename", [], 20.0), "the refusal was not logged")
        # Inside the folder, but not a zone file: the name is fine, the file is not replaced.
        other = os.path.join(self.save_dir, "params.yaml")
        with open(other, "w") as f:
            f.write("robot_radius: 0.3\n")
        res = self.save("params.yaml")
        self.assertFalse(res.success)
        self.assertIn("not a zone file", res.message)
        with open(other) as f:
            self.assertEqual(f.read(), "robot_radius: 0.3\n")
        # Inside, by a relative and by an absolute name: saved, and loads again.
        for name in ["inside.yaml", os.path.join(self.save_dir, "sub", "inside.yaml")]:
            res = self.save(name)
            self.assertTrue(res.success, res.message)
            self.assertTrue(os.path.isfile(os.path.join(self.save_dir, name)))
            self.assertTrue(load(name).success)

    def test_a_burst_of_drags_is_coalesced(self):
        """300 drags as fast as they can be sent: the mask is republished at most publish_rate times a
        second (plus the tick in progress), its INFO line at most once a second, and the mask that
        stays is the last drag's."""
        initial = expected_mask([(DOCK, 100)], [(SLOW, 40)])
        self.assertTrue(self.mask.wait(matches(initial), 30.0), "the mask did not settle")
        rate = rospy.get_param("/zone_server/publish_rate", 10.0)

        def put_dock_back():
            self.set_shape(ZoneShape(name="dock", type="polygon", value=100, fill=True,
                                     points=[Point(x, y, 0.0) for x, y in DOCK]))
            self.assertTrue(self.mask.wait(matches(initial), 20.0), "dock was not put back")

        self.addCleanup(put_dock_back)
        n = 300
        last = (3.46, 2.57)
        expected = expected_mask([([DOCK[0], DOCK[1], last, DOCK[3]], 100)], [(SLOW, 40)])
        masks_before = self.mask.count
        with self.info.cond:
            lines_before = len(logged_with_key(self.info.lines, "/zone_server/published"))
        start = time.monotonic()
        for k in range(1, n + 1):  # up and right of the square's corner: every step keeps it convex
            self.drag("dock/2", DOCK[2][0] + (last[0] - DOCK[2][0]) * k / n, DOCK[2][1] + (last[1] - DOCK[2][1]) * k / n)
        self.assertTrue(self.mask.wait(matches(expected), 20.0), "the last drag's mask was not published")
        elapsed = time.monotonic() - start
        masks = self.mask.count - masks_before
        with self.info.cond:
            lines = len(logged_with_key(self.info.lines, "/zone_server/published")) - lines_before
        print("[figures] %d drags: %d masks and %d INFO lines in %.2f s" % (n, masks, lines, elapsed))
        self.assertGreaterEqual(masks, 1)
        self.assertLessEqual(masks, int(elapsed * rate) + 2,
                             "%d masks in %.2f s for %d drags at publish_rate %g" % (masks, elapsed, n, rate))
        self.assertTrue(matches(expected)(self.mask.msg))
        self.assertLessEqual(lines, int(elapsed) + 2, "%d INFO lines in %.2f s" % (lines, elapsed))


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "zone_server", ZoneServerTest)
