#!/usr/bin/env python3
"""What RViz is given to write: zone_server's names at their shapes and its handle labels beside the
handles (read from ~update_full, as RViz reads them), and mask_view.py, the speed zones' copy for RViz.
Expected positions are worked out by hand from example/zones.yaml and far_zones.yaml."""
import math
import os
import subprocess
import sys
import threading
import unittest

import rospkg
import rospy
import rostest
import yaml
from nav_msgs.msg import OccupancyGrid
from visualization_msgs.msg import InteractiveMarkerFeedback, InteractiveMarkerInit, Marker

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from grid_watch import Latest, occupancy_grid  # noqa: E402

ORANGE = (1.0, 0.55, 0.0)  # the handles' colour, which the labels share
HANDLE = 0.25  # [m] a handle's sphere
NAME_HEIGHT = 0.3  # [m]

# example/zones.yaml. Names: a polygon's at its area centroid, a circle's just below its centre handle
# (0.125 sphere radius + 0.05 gap + 0.15 half text height = 0.325 m).
#   corner_keepout (12.8, 5.4) (15.4, 5.4) (15.4, 6.6): a triangle, centroid the vertices' mean,
#     x = (12.8 + 15.4 + 15.4) / 3 = 43.6 / 3, y = (5.4 + 5.4 + 6.6) / 3 = 5.8
#   fence, the rectangle 8.0..10.5 x 2.4..3.3: its middle (9.25, 2.85)
#   puddle, centre (14.2, 3.4): (14.2, 3.4 - 0.325)
NAMES = {
    "corner_keepout": ("corner_keepout (100)", 43.6 / 3, 5.8),
    "fence": ("fence (100)", 9.25, 2.85),
    "puddle": ("puddle (50)", 14.2, 3.075),
}
# Handle labels (0.25 m text, a character estimated 0.6 of the height wide: 0.15 m), beside the handle
# in a direction d, at 0.125 (sphere radius) + 0.05 (gap) + |dx| 0.075 + |dy| 0.125 (half the label's
# box along d) = 0.175 + |dx| 0.075 + |dy| 0.125 from it:
# - a polygon vertex's outside its corner, along the outer bisector of the two edges. The fence's
#   corners and corner_keepout/1 are right angles: d = (+-1, +-1) / sqrt 2, each coordinate moved by
#   0.175 / sqrt 2 + (0.075 + 0.125) / 2 = 0.1237437 + 0.1 = 0.2237437.
#   corner_keepout/0 (12.8, 5.4), edges to (15.4, 6.6) (direction (2.6, 1.2) / sqrt 8.2 = (0.9079594,
#   0.4190582)) and to (15.4, 5.4) (direction (1, 0)): their bisector (1.9079594, 0.4190582) / 1.9534377
#   = (0.9767188, 0.2145234), outward d = (-0.9767188, -0.2145234); distance 0.175 + 0.0732539 +
#   0.0268154 = 0.2750693; label (12.8 - 0.2686654, 5.4 - 0.0590088).
#   corner_keepout/2 (15.4, 6.6), edges to (15.4, 5.4) (0, -1) and to (12.8, 5.4) (-0.9079594,
#   -0.4190582): bisector (-0.9079594, -1.4190582) / 1.6846710, outward d = (0.5389535, 0.8423355);
#   distance 0.175 + 0.0404215 + 0.1052919 = 0.3207135; label (15.4 + 0.1728496, 6.6 + 0.2701483).
# - the circle's centre's above it (d = (0, 1)): 0.175 + 0.125 = 0.3; its radius handle's to the right
#   (d = (1, 0)), out of the circle: 0.175 + 6 characters * 0.075 = 0.625.
C = 0.2237437  # 0.175 / sqrt 2 + 0.1
HANDLES = {
    "corner_keepout/0": ("0", 12.8, 5.4, 12.8 - 0.2686654, 5.4 - 0.0590088),
    "corner_keepout/1": ("1", 15.4, 5.4, 15.4 + C, 5.4 - C),
    "corner_keepout/2": ("2", 15.4, 6.6, 15.4 + 0.1728496, 6.6 + 0.2701483),
    "fence/0": ("0", 8.0, 2.4, 8.0 - C, 2.4 - C),
    "fence/1": ("1", 10.5, 2.4, 10.5 + C, 2.4 - C),
    "fence/2": ("2", 10.5, 3.3, 10.5 + C, 3.3 + C),
    "fence/3": ("3", 8.0, 3.3, 8.0 - C, 3.3 + C),
    "puddle/center": ("center", 14.2, 3.4, 14.2, 3.7),
    "puddle/radius": ("radius", 14.7, 3.4, 15.325, 3.4),
}
# far_zones.yaml. ell: from (1234567.3, 2345678.9), the rectangles 0..4 x 0..1 (area 4, centre (2, 0.5))
# and 0..1 x 1..3 (area 2, centre (0.5, 2)): x = (4 * 2 + 2 * 0.5) / 6 = 1.5, y = (4 * 0.5 + 2 * 2) / 6
# = 1.0 from there (the vertices' mean would be (1.667, 1.333)). cw_square: 1234572.3..1234574.3 x
# 2345678.9..2345680.9, drawn clockwise: its middle.
FAR = {"ell": (1234568.8, 2345679.9), "cw_square": (1234573.3, 2345679.9)}


class Init:
    """The latest ~update_full of a marker server, with a wait on a condition of it."""

    def __init__(self, server):
        self.cond = threading.Condition()
        self.markers = None
        rospy.Subscriber(server + "/update_full", InteractiveMarkerInit, self._on_init)

    def _on_init(self, m):
        with self.cond:
            self.markers = {im.name: im for im in m.markers}
            self.cond.notify_all()

    def wait(self, predicate, timeout=30.0):
        with self.cond:
            self.cond.wait_for(lambda: self.markers is not None and predicate(self.markers), timeout)
            return self.markers


def texts(im):
    """(text marker, its absolute position) of an interactive marker, whose pose is unrotated."""
    return [(m, (im.pose.position.x + m.pose.position.x, im.pose.position.y + m.pose.position.y))
            for c in im.controls for m in c.markers if m.type == Marker.TEXT_VIEW_FACING]


def name_at(markers, shape):
    found = texts(markers[shape + "/outline"]) if shape + "/outline" in markers else []
    return found[0][1] if len(found) == 1 else None


def inside(pts, x, y):
    """Whether (x, y) is inside the polygon (a ray cast to +x, counting crossings)."""
    result = False
    for k in range(len(pts)):
        (x1, y1), (x2, y2) = pts[k], pts[(k + 1) % len(pts)]
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            result = not result
    return result


def segment_meets_box(a, b, box):
    """Whether the segment a-b touches the box (x0, y0, x1, y1): clipped against each slab in turn."""
    t0, t1 = 0.0, 1.0
    for p, d, lo, hi in ((a[0], b[0] - a[0], box[0], box[2]), (a[1], b[1] - a[1], box[1], box[3])):
        if d == 0.0:
            if p < lo or p > hi:
                return False
            continue
        u, v = sorted(((lo - p) / d, (hi - p) / d))
        t0, t1 = max(t0, u), min(t1, v)
        if t0 > t1:
            return False
    return True


class ZoneLabelsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_zone_labels")
        cls.example = Init("/zone_server")
        cls.far = Init("/zone_far")
        cls.feedback = rospy.Publisher("/zone_server/feedback", InteractiveMarkerFeedback, queue_size=10)

    def assertLabel(self, marker, height):
        self.assertEqual(marker.scale.z, height)
        self.assertAlmostEqual(marker.color.r, ORANGE[0], places=6)
        self.assertAlmostEqual(marker.color.g, ORANGE[1], places=6)
        self.assertAlmostEqual(marker.color.b, ORANGE[2], places=6)
        self.assertEqual(marker.color.a, 1.0)
        # Above the masks (z = 0) and the spheres (top at 0.125 m), so neither covers the text.
        self.assertGreater(marker.pose.position.z, HANDLE / 2)

    def test_names_are_at_their_shapes(self):
        markers = self.example.wait(lambda ms: all(s + "/outline" in ms for s in NAMES))
        self.assertIsNotNone(markers, "no ~update_full from /zone_server")
        for shape, (text, x, y) in NAMES.items():
            im = markers[shape + "/outline"]
            # A description is drawn by RViz as a white title at the marker's pose: the origin here.
            self.assertEqual(im.description, "", shape)
            found = texts(im)
            self.assertEqual(len(found), 1, shape)
            marker, (ax, ay) = found[0]
            self.assertEqual(marker.text, text)
            self.assertAlmostEqual(ax, x, places=9, msg=shape)
            self.assertAlmostEqual(ay, y, places=9, msg=shape)
            self.assertLabel(marker, NAME_HEIGHT)

    def test_handle_labels_are_beside_their_handles(self):
        markers = self.example.wait(lambda ms: all(h in ms for h in HANDLES))
        self.assertIsNotNone(markers, "no ~update_full from /zone_server")
        self.assertEqual(sorted(n for n in markers if not n.endswith("/outline")), sorted(HANDLES))
        for name, (text, hx, hy, lx, ly) in HANDLES.items():
            im = markers[name]
            self.assertEqual(im.description, "", name)
            self.assertAlmostEqual(im.pose.position.x, hx, places=9)
            self.assertAlmostEqual(im.pose.position.y, hy, places=9)
            found = texts(im)
            self.assertEqual(len(found), 1, name)
            marker, (ax, ay) = found[0]
            self.assertEqual(marker.text, text)
            self.assertAlmostEqual(ax, lx, delta=1e-6, msg=name)
            self.assertAlmostEqual(ay, ly, delta=1e-6, msg=name)
            self.assertLabel(marker, HANDLE)
            # The label's control takes no mouse input: only the sphere is dragged.
            moving = [c for c in im.controls if any(m.type == Marker.TEXT_VIEW_FACING for m in c.markers)]
            self.assertEqual(moving[0].interaction_mode, moving[0].NONE)

    def test_names_of_far_and_clockwise_polygons(self):
        markers = self.far.wait(lambda ms: all(s + "/outline" in ms for s in FAR))
        self.assertIsNotNone(markers, "no ~update_full from /zone_far")
        for shape, (x, y) in FAR.items():
            at = name_at(markers, shape)
            self.assertIsNotNone(at, shape)
            self.assertAlmostEqual(at[0], x, places=6, msg=shape)
            self.assertAlmostEqual(at[1], y, places=6, msg=shape)

    def test_handle_labels_cross_no_edge_of_their_shape(self):
        # Every polygon of both servers, the concave L (a reflex corner) and the clockwise square of
        # far_zones.yaml among them: each vertex label's box (0.15 m a character by 0.25 m) lies outside
        # its polygon, crosses none of its edges, and is within 0.5 m of its handle.
        with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "far_zones.yaml")) as f:
            far = {s["name"]: s["points"] for s in yaml.safe_load(f)["shapes"]}
        example = {"corner_keepout": [[12.8, 5.4], [15.4, 5.4], [15.4, 6.6]],
                   "fence": [[8.0, 2.4], [10.5, 2.4], [10.5, 3.3], [8.0, 3.3]]}
        for server, polygons in ((self.example, example), (self.far, far)):
            names = ["%s/%d" % (p, k) for p, pts in polygons.items() for k in range(len(pts))]
            markers = server.wait(lambda ms: all(n in ms for n in names))
            self.assertIsNotNone(markers)
            for shape, pts in polygons.items():
                edges = [(pts[k], pts[(k + 1) % len(pts)]) for k in range(len(pts))]
                for k, (hx, hy) in enumerate(pts):
                    name = "%s/%d" % (shape, k)
                    found = texts(markers[name])
                    self.assertEqual(len(found), 1, name)
                    marker, (lx, ly) = found[0]
                    hw, hh = 0.075 * len(marker.text), 0.125
                    box = (lx - hw, ly - hh, lx + hw, ly + hh)
                    self.assertLessEqual(math.hypot(lx - hx, ly - hy), 0.5, name)
                    self.assertFalse(inside(pts, lx, ly), "%s's label (%.3f, %.3f) is inside %s" % (name, lx, ly, shape))
                    for a, b in edges:
                        self.assertFalse(segment_meets_box(a, b, box),
                                         "%s's label box %s crosses the edge %s-%s" % (name, box, a, b))

    def drag(self, marker, x, y):
        f = InteractiveMarkerFeedback()
        f.header.frame_id = "map"
        f.header.stamp = rospy.Time.now()
        f.client_id = "/test_zone_labels"
        f.marker_name = marker
        f.event_type = InteractiveMarkerFeedback.POSE_UPDATE
        f.pose.position.x, f.pose.position.y = x, y
        f.pose.orientation.w = 1.0
        self.feedback.publish(f)

    def test_the_name_follows_a_drag(self):
        self.assertIsNotNone(self.example.wait(lambda ms: name_at(ms, "fence") is not None))
        deadline = rospy.Time.now() + rospy.Duration(30.0)
        while self.feedback.get_num_connections() == 0 and rospy.Time.now() < deadline:
            rospy.sleep(0.05)  # polling a condition (the subscriber's connection), with a deadline
        # fence/2 from (10.5, 3.3) to (11.5, 3.3): the rectangle 8..10.5 x 2.4..3.3 (area 2.25, centre
        # (9.25, 2.85)) plus the triangle (10.5, 2.4) (11.5, 3.3) (10.5, 3.3) (area 0.45, centroid
        # (32.5 / 3, 3.0)): x = (2.25 * 9.25 + 0.45 * 32.5 / 3) / 2.7 = 25.6875 / 2.7,
        # y = (2.25 * 2.85 + 0.45 * 3.0) / 2.7 = 2.875.
        moved = (25.6875 / 2.7, 2.875)

        def near(at, x, y):
            return at is not None and abs(at[0] - x) < 1e-9 and abs(at[1] - y) < 1e-9
        self.addCleanup(lambda: self.example.wait(lambda ms: near(name_at(ms, "fence"), 9.25, 2.85)))
        self.addCleanup(self.drag, "fence/2", 10.5, 3.3)
        self.drag("fence/2", 11.5, 3.3)
        markers = self.example.wait(lambda ms: near(name_at(ms, "fence"), *moved))
        self.assertTrue(near(name_at(markers, "fence"), *moved), "fence's name is at %s" % (name_at(markers, "fence"),))

    def release(self, marker):
        f = InteractiveMarkerFeedback()
        f.header.frame_id = "map"
        f.header.stamp = rospy.Time.now()
        f.client_id = "/test_zone_labels"
        f.marker_name = marker
        f.event_type = InteractiveMarkerFeedback.MOUSE_UP
        f.pose.orientation.w = 1.0
        self.feedback.publish(f)

    def test_labels_move_to_the_new_corners_when_a_drag_ends(self):
        self.assertIsNotNone(self.example.wait(lambda ms: "fence/2" in ms))
        deadline = rospy.Time.now() + rospy.Duration(30.0)
        while self.feedback.get_num_connections() == 0 and rospy.Time.now() < deadline:
            rospy.sleep(0.05)  # polling a condition (the subscriber's connection), with a deadline
        # fence/2 from (10.5, 3.3) to (11.5, 3.3), then released. The edge fence/1 -> fence/2 is now
        # (1, 0.9) / sqrt 1.81 = (0.7432941, 0.6689647).
        # fence/2: edges to (10.5, 2.4) (-0.7432941, -0.6689647) and to (8, 3.3) (-1, 0); outward
        #   bisector (1.7432941, 0.6689647) / 1.8672406 = (0.9336204, 0.3582638); distance 0.175 +
        #   0.0700215 + 0.0447830 = 0.2898045; label (11.5 + 0.2705674, 3.3 + 0.1038265).
        # fence/1: edges to (8, 2.4) (-1, 0) and to (11.5, 3.3) (0.7432941, 0.6689647); outward
        #   bisector (0.2567059, -0.6689647) / 0.7165281 = (0.3582638, -0.9336204); distance 0.175 +
        #   0.0268698 + 0.1167026 = 0.3185723; label (10.5 + 0.1141329, 2.4 - 0.2974256).
        # fence/0 and fence/3 keep their right angles: (8 -+ C, 2.4 -+ C).
        moved = {"fence/2": (11.7705674, 3.4038265), "fence/1": (10.6141329, 2.1025744),
                 "fence/0": (8.0 - C, 2.4 - C), "fence/3": (8.0 - C, 3.3 + C)}
        original = {n: (HANDLES[n][3], HANDLES[n][4]) for n in moved}

        def labels_at(ms, where):
            for name, (x, y) in where.items():
                found = texts(ms[name]) if name in ms else []
                if len(found) != 1 or abs(found[0][1][0] - x) > 1e-6 or abs(found[0][1][1] - y) > 1e-6:
                    return False
            return True
        self.addCleanup(lambda: self.assertTrue(self.example.wait(lambda ms: labels_at(ms, original)),
                                                "the labels did not go back"))
        self.addCleanup(self.release, "fence/2")
        self.addCleanup(self.drag, "fence/2", 10.5, 3.3)
        self.drag("fence/2", 11.5, 3.3)
        self.release("fence/2")
        markers = self.example.wait(lambda ms: labels_at(ms, moved))
        self.assertTrue(labels_at(markers, moved),
                        {n: texts(markers[n])[0][1] for n in moved if n in markers and texts(markers[n])})

    def test_mask_view_replaces_the_listed_values(self):
        out = Latest("/view_out", OccupancyGrid)
        pub = rospy.Publisher("/view_in", OccupancyGrid, queue_size=1, latch=True)
        pub.publish(occupancy_grid(7, 1, 0.5, [0, 1, 2, -1, 100, 50, 3], ox=2.0, oy=-1.0))
        self.assertTrue(out.wait(lambda m: True, 30.0), "nothing on /view_out")
        m = out.msg
        self.assertEqual(list(m.data), [0, 80, 30, 0, 100, 50, 3])  # "1:80, 2:30, -1:0"; others kept
        self.assertEqual((m.info.width, m.info.height, m.info.resolution), (7, 1, 0.5))
        self.assertEqual((m.info.origin.position.x, m.info.origin.position.y), (2.0, -1.0))
        self.assertEqual(m.header.frame_id, "map")

    def test_mask_view_stops_on_bad_values_with_one_line(self):
        script = os.path.join(rospkg.RosPack().get_path("costmap_layers"), "scripts", "mask_view.py")
        # Out of -1..100 at both ends, a value twice, not a pair, nothing; set as strings on the
        # parameter server (on the command line YAML would read "1:30" as the base-60 number 90).
        for values, says in [("1:101", "101 is not a mask value"), ("-2:0, 1:1", "-2 is not a mask value"),
                             ("1:80, 1:30", "value 1 is listed twice"), ("1:2:3, 2:2", "'1:2:3' is not a pair"),
                             (" , ", "lists no pair")]:
            rospy.set_param("/bad_view/values", values)
            run = subprocess.run([script, "__name:=bad_view", "_output:=/bad_view_out"],
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60, text=True)
            self.assertEqual(run.returncode, 1, values)
            fatal = [line for line in run.stderr.splitlines() if "FATAL" in line]
            self.assertEqual(len(fatal), 1, run.stderr)
            self.assertIn('parameter /bad_view/values ("%s")' % values, fatal[0])
            self.assertIn(says, fatal[0])


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "zone_labels", ZoneLabelsTest)
