#!/usr/bin/env python3
"""RViz, headless, on the shipped launch/costmap.rviz with the demo's nodes (rviz.test): every display
is Ok, and a screenshot shows zone_server's shapes in their colours where example/zones.yaml puts them,
their names and handle labels beside them, the two speed zones in different colours and the lanes
mask's "no opinion" cells leaving the floor white; RViz logs no error.

RViz runs in this process through its Python bindings (python3-rviz): VisualizationFrame.initialize()
on the config is what `rviz -d` does, and the bindings let the test read each display's status, which
RViz shows in its Displays panel but does not log. The X server is an Xvfb started here (a free display
number, chosen by Xvfb); the screenshot is read from it through Qt."""
import ctypes
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import unittest

import rospkg
import rostest
import yaml

PKG_DIR = rospkg.RosPack().get_path("costmap_layers")
CONFIG = os.path.join(PKG_DIR, "launch", "costmap.rviz")
ZONES = os.path.join(PKG_DIR, "example", "zones.yaml")
STATUS_TIMEOUT = 40.0  # [s] from the start of RViz until every display is Ok
VIEW_TIMEOUT = 15.0  # [s] more until a rendered frame shows everything

# The view the config sets (checked against it): top-down orthographic, 50 pixels a metre, centred on
# (8, 5), unrotated. A point (x, y) [m] is at pixel (cx + 50 (x - 8), cy - 50 (y - 5)) of the render
# panel, (cx, cy) being the panel's middle.
SCALE, FOCUS_X, FOCUS_Y = 50.0, 8.0, 5.0

# Every topic the demo serves for RViz, each on an enabled display that must come up Ok.
TOPICS = {"/map", "/costmap_node/costmap", "/keepout_filter_mask", "/speed_zones_view", "/lanes_filter_mask",
          "/binary_filter_mask", "/zone_filter_mask", "/zone_server/update", "/costmap_node/footprint"}

# From example/zones.yaml (checked against it below), by hand.
ZONE_FILE_SHAPES = {
    "corner_keepout": {"type": "polygon", "value": 100, "points": [[12.8, 5.4], [15.4, 5.4], [15.4, 6.6]]},
    "fence": {"type": "polygon", "value": 100, "fill": False,
              "points": [[8.0, 2.4], [10.5, 2.4], [10.5, 3.3], [8.0, 3.3]]},
    "puddle": {"type": "circle", "value": 50, "center": [14.2, 3.4], "radius": 0.5},
}
RED_LINE, BLUE_LINE = (230, 77, 51), (51, 77, 230)  # outlines: value 100 (0.9, 0.3, 0.2), else (0.2, 0.3, 0.9)
# Points on the outlines, clear of the names and labels: edge midpoints, a point 3/4 along the
# triangle's long edge, the circle at 90, 160 and 180 degrees (14.2 + 0.5 cos a, 3.4 + 0.5 sin a).
OUTLINE_POINTS = [
    ("corner_keepout", (14.1, 5.4), RED_LINE), ("corner_keepout", (15.4, 6.0), RED_LINE),
    ("corner_keepout", (14.75, 6.3), RED_LINE),
    ("fence", (9.25, 2.4), RED_LINE), ("fence", (10.5, 2.85), RED_LINE), ("fence", (9.25, 3.3), RED_LINE),
    ("fence", (8.0, 2.85), RED_LINE),
    ("puddle", (14.2, 3.9), BLUE_LINE), ("puddle", (13.73015, 3.57101), BLUE_LINE), ("puddle", (13.7, 3.4), BLUE_LINE),
]
# Names: a polygon's at its centroid, the circle's 0.325 m below its centre; text 0.3 m tall.
NAMES = {"corner_keepout": (14.5333, 5.8), "fence": (9.25, 2.85), "puddle": (14.2, 3.075)}
# Handle labels, 0.25 m tall, beside their handles (worked out in test_zone_labels.py): a polygon
# vertex's outside its corner, the circle centre's 0.3 m above it, the radius handle's 0.625 m right.
LABELS = {"corner_keepout/0": (12.5313, 5.341), "corner_keepout/1": (15.6237, 5.1763),
          "corner_keepout/2": (15.5728, 6.8701), "fence/0": (7.7763, 2.1763), "fence/1": (10.7237, 2.1763),
          "fence/2": (10.7237, 3.5237), "fence/3": (7.7763, 3.5237), "puddle/center": (14.2, 3.7),
          "puddle/radius": (15.325, 3.4)}


def is_orange(p):  # the labels' (1.0, 0.55, 0.0)
    r, g, b = p
    return r >= 215 and 110 <= g <= 170 and b <= 60


def near_colour(c):
    return lambda p: all(abs(a - b) <= 40 for a, b in zip(p, c))


def die_with_parent():
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG


class Screen:
    """A screenshot as RGB bytes, with the panel's world-to-pixel map."""

    def __init__(self, image, panel):
        from python_qt_binding.QtGui import QImage
        self.image = image.convertToFormat(QImage.Format_RGB32)
        self.width, self.height = self.image.width(), self.image.height()
        ptr = self.image.constBits()
        ptr.setsize(self.image.byteCount())
        self.bytes = bytes(ptr)
        self.stride = self.image.bytesPerLine()
        self.left, self.top, self.panel_w, self.panel_h = panel

    def pixel(self, u, v):
        o = v * self.stride + 4 * u  # 0xAARRGGBB, little-endian
        return self.bytes[o + 2], self.bytes[o + 1], self.bytes[o]

    def at(self, x, y):
        """The pixel (column, row) of the world point (x, y) [m]."""
        u = self.left + self.panel_w / 2.0 + (x - FOCUS_X) * SCALE
        v = self.top + self.panel_h / 2.0 - (y - FOCUS_Y) * SCALE
        return int(u), int(v)

    def find(self, x, y, predicate, radius_px=2):
        """Whether a pixel within radius_px of the point (x, y) satisfies predicate; the pixels seen."""
        u0, v0 = self.at(x, y)
        seen = []
        for v in range(v0 - radius_px, v0 + radius_px + 1):
            for u in range(u0 - radius_px, u0 + radius_px + 1):
                p = self.pixel(u, v)
                if predicate(p):
                    return True, [p]
                seen.append(p)
        return False, seen[len(seen) // 2:len(seen) // 2 + 1]

    def count(self, x, y, half_w, half_h, predicate):
        """The pixels satisfying predicate in the box (x, y) +- (half_w, half_h) [m]."""
        u0, v0 = self.at(x - half_w, y + half_h)
        u1, v1 = self.at(x + half_w, y - half_h)
        return sum(1 for v in range(v0, v1 + 1) for u in range(u0, u1 + 1) if predicate(self.pixel(u, v)))


def view_failures(s):
    """What the screenshot does not show; empty when it shows everything."""
    failures = []
    for shape, (x, y), colour in OUTLINE_POINTS:
        ok, seen = s.find(x, y, near_colour(colour))
        if not ok:
            failures.append("%s's outline is not drawn %s at (%g, %g): %s" % (shape, colour, x, y, seen))
    # Inside: the filled triangle in lethal magenta (the zone mask and the costmap's keepout, both 100),
    # the circle in purple (value 50: cost 127, the middle of the blue-red palette).
    ok, seen = s.find(15.0, 5.55, lambda p: p[0] >= 150 and p[2] >= 150 and p[1] <= 110)
    if not ok:
        failures.append("corner_keepout's inside at (15.0, 5.55) is not magenta: %s" % seen)
    ok, seen = s.find(13.95, 3.45, lambda p: p[0] >= p[1] + 40 and p[2] >= p[1] + 40 and p[0] <= 220)
    if not ok:
        failures.append("puddle's inside at (13.95, 3.45) is not purple: %s" % seen)
    for shape, (x, y) in NAMES.items():
        n = s.count(x, y, 0.5, 0.1, is_orange)
        if n < 10:
            failures.append("%s's name: %d orange pixels in (%g, %g) +- (0.5, 0.1) m" % (shape, n, x, y))
    for handle, (x, y) in LABELS.items():
        n = s.count(x, y, 0.3 if handle.startswith("puddle") else 0.15, 0.1, is_orange)
        if n < 4:
            failures.append("%s's label: %d orange pixels in (%g, %g) +- (0.15, 0.1) m" % (handle, n, x, y))
    # The speed zones: area 1 (0.3 m/s) red, area 2 (0.6 m/s) blue, away from walls and the route.
    ok, seen = s.find(5.5, 1.0, lambda p: p[0] >= p[2] + 40)
    if not ok:
        failures.append("speed area 1 at (5.5, 1.0) is not red: %s" % seen)
    ok, seen = s.find(10.8, 1.0, lambda p: p[2] >= p[0] + 40)
    if not ok:
        failures.append("speed area 2 at (10.8, 1.0) is not blue: %s" % seen)
    # Free floor under the lanes mask's "no opinion" cells (-1), in no zone: white, not greyed out.
    ok, seen = s.find(12.8, 2.2, lambda p: min(p) >= 235)
    if not ok:
        failures.append("the free floor at (12.8, 2.2) is not white: %s" % seen)
    return failures


def topic_of(display):
    """The topic a display reads, None for one that reads none (TF)."""
    for i in range(display.numChildren()):
        child = display.childAt(i)
        if child.getName() in ("Topic", "Update Topic"):
            return child.getValue()
    return None


def status_of(display):
    """('Ok' | 'Warn' | 'Error', [child status lines]) of an RViz display."""
    for i in range(display.numChildren()):
        child = display.childAt(i)
        name = child.getName()
        if name.startswith("Status: "):
            lines = ["%s: %s" % (child.childAt(k).getName(), child.childAt(k).getValue())
                     for k in range(child.numChildren())]
            return name[len("Status: "):], lines
    return "Ok", []  # no status yet


# RViz's own shader for the Map display fails Mesa's link-time sampler check on software rendering
# (llvmpipe), which RViz logs as an error at start; the map is drawn all the same (the colour checks
# above read it). That one message is expected; any other error fails the test.
MESA_SAMPLER_ERROR = re.compile(r"rviz/glsl120/indexed_8bit_image\.vert\s+rviz/glsl120/indexed_8bit_image\.frag\s+"
                                r"GLSL link result :\s+active samplers with a different type refer to the same "
                                r"texture image unit\s*$")


def logged_errors(text):
    """The ERROR and FATAL messages of roscpp's console output, each whole (they may span lines)."""
    text = re.sub(r"\x1b\[[0-9;]*m", "\x00", text)  # the colour codes end each message
    return [m.strip() for m in re.findall(r"\[(?:ERROR|FATAL)\] \[[0-9.]+\]: ([^\x00]*)", text)]


class RvizViewTest(unittest.TestCase):
    maxDiff = None  # every failure listed in full

    @classmethod
    def setUpClass(cls):
        cls.failures, cls.statuses, cls.errors, cls.shot = [], {}, [], None
        cls.topics = set()
        tmp = tempfile.mkdtemp(prefix="rviz_view_test_")
        os.environ["XDG_RUNTIME_DIR"] = tmp
        os.chmod(tmp, 0o700)
        # RViz keeps its recent files in ~/.rviz: this run's go to the temporary folder.
        os.environ.setdefault("ROS_HOME", os.path.join(os.path.expanduser("~"), ".ros"))
        os.environ["HOME"] = tmp
        cls.tmp = tmp
        # The screenshot outlives the run (each run replaces it): $ROS_HOME/rviz_view_test.png, which
        # scripts/test.sh puts in log/ros_home.
        os.makedirs(os.environ["ROS_HOME"], exist_ok=True)
        cls.shot_path = os.path.join(os.environ["ROS_HOME"], "rviz_view_test.png")
        try:
            import rviz  # noqa: F401  (python3-rviz)
        except ImportError as e:
            raise RuntimeError("rviz view test: NOT RUN, RViz's Python bindings are missing (%s); "
                               "scripts/lib/install_deps.sh installs python3-rviz, rviz and xvfb" % e)
        read_fd, write_fd = os.pipe()
        try:
            cls.xvfb = subprocess.Popen(["Xvfb", "-displayfd", str(write_fd), "-screen", "0", "1600x1000x24",
                                         "-nolisten", "tcp", "-noreset"], pass_fds=[write_fd],
                                        preexec_fn=die_with_parent, stdout=subprocess.DEVNULL,
                                        stderr=subprocess.DEVNULL)
        except OSError as e:
            raise RuntimeError("rviz view test: NOT RUN, Xvfb cannot start (%s); scripts/lib/install_deps.sh "
                               "installs xvfb" % e)
        os.close(write_fd)
        display = b""
        while not display.endswith(b"\n"):  # Xvfb writes its display number once it accepts clients
            chunk = os.read(read_fd, 16)
            if not chunk:
                raise RuntimeError("rviz view test: NOT RUN, Xvfb exited before accepting clients")
            display += chunk
        os.close(read_fd)
        os.environ["DISPLAY"] = ":" + display.decode().strip()
        print("rviz view test: running RViz on %s under Xvfb %s" % (CONFIG, os.environ["DISPLAY"]), flush=True)
        # roscpp inside RViz writes its errors to file descriptor 2: keep them to check.
        log = tempfile.TemporaryFile(dir=tmp)
        saved_stderr = os.dup(2)
        os.dup2(log.fileno(), 2)
        try:
            cls.run_rviz()
        finally:
            os.dup2(saved_stderr, 2)
            os.close(saved_stderr)
            log.seek(0)
            text = log.read().decode(errors="replace")
            sys.stderr.write(text)
            cls.errors = [e for e in logged_errors(text) if not MESA_SAMPLER_ERROR.search(e)]

    @classmethod
    def run_rviz(cls):
        import time

        from python_qt_binding.QtCore import QEventLoop, QTimer
        from python_qt_binding.QtWidgets import QApplication, QWidget
        from rviz import bindings as rviz

        cls.app = QApplication([sys.argv[0]])
        frame = rviz.VisualizationFrame()
        frame.setSplashPath("")
        frame.initialize(CONFIG)
        frame.show()
        cls.frame = frame  # kept for the process's life: Qt tears it down at exit, after the checks
        root = frame.getManager().getRootDisplayGroup()
        displays = [root.getDisplayAt(i) for i in range(root.numDisplays())]
        panels = [w for w in frame.findChildren(QWidget) if w.metaObject().className() == "rviz::RenderPanel"]

        def run_events(ms):  # RViz's update and render timers run in this loop
            loop = QEventLoop()
            QTimer.singleShot(ms, loop.quit)
            loop.exec_()

        start = time.monotonic()
        while True:
            run_events(200)
            cls.statuses = {d.getName(): (d.isEnabled(), topic_of(d)) + status_of(d) for d in displays}
            # Ok with details: a display that has not subscribed yet has no status at all.
            if all(s[2] == "Ok" and s[3] for s in cls.statuses.values()) or time.monotonic() - start > STATUS_TIMEOUT:
                break
        # Every display Ok: each has its first message. The frame drawn after that shows them.
        deadline = time.monotonic() + VIEW_TIMEOUT
        while True:
            run_events(200)
            panel = panels[0]
            corner = panel.mapToGlobal(panel.rect().topLeft())
            cls.shot = Screen(cls.app.primaryScreen().grabWindow(0).toImage(),
                              (corner.x(), corner.y(), panel.width(), panel.height()))
            cls.failures = view_failures(cls.shot)
            if not cls.failures or time.monotonic() > deadline:
                break
        cls.shot.image.save(cls.shot_path)
        print("rviz view test: ran RViz for %.1f s; screenshot in %s" % (time.monotonic() - start, cls.shot_path),
              flush=True)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_the_config_is_the_view_the_test_maps(self):
        with open(CONFIG) as f:
            config = yaml.safe_load(f)
        view = config["Visualization Manager"]["Views"]["Current"]
        self.assertEqual((view["Class"], view["Scale"], view["X"], view["Y"], view["Angle"]),
                         ("rviz/TopDownOrtho", SCALE, FOCUS_X, FOCUS_Y, 0))
        with open(ZONES) as f:
            shapes = {s.pop("name"): s for s in yaml.safe_load(f)["shapes"]}
        self.assertEqual(shapes, ZONE_FILE_SHAPES, "example/zones.yaml changed: update this test's points")

    def test_every_display_is_enabled_and_ok(self):
        self.assertTrue(self.statuses, "RViz loaded no display")
        bad = {name: s for name, s in self.statuses.items() if not s[0] or s[2] != "Ok" or not s[3]}
        self.assertEqual(bad, {}, "displays not enabled or not Ok (enabled, topic, status, details)")
        self.assertEqual(TOPICS - {s[1] for s in self.statuses.values()}, set(), "topics with no display")

    def test_the_screenshot_shows_the_zones_labels_and_masks(self):
        self.assertIsNotNone(self.shot, "no screenshot")
        self.assertEqual(self.failures, [], "see the screenshot %s" % self.shot_path)

    def test_rviz_logs_no_error(self):
        self.assertEqual(self.errors, [])


if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "rviz_view", RvizViewTest)
