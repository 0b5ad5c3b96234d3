#!/usr/bin/env python3
"""Each program the package installs, started with a bad value of each kind (a name, a number, a type,
a file): it must exit non-zero and say why in exactly one FATAL line, on stderr and on /rosout, naming
the parameter and its value. costmap_tool, which has no master, must print one error line and exit 1.

The programs are run one at a time under unique node names, their parameters set here on the master
just before; the expected texts are the parameter names and the values this test wrote."""
import os
import subprocess
import tempfile
import threading
import time
import unittest

import rospy
import rostest
import roslib.packages
from rosgraph_msgs.msg import Log

PKG = "costmap_layers"


def program(name):
    found = roslib.packages.find_node(PKG, name)
    if not found:
        raise AssertionError("%s not found in package %s" % (name, PKG))
    return found[0]


class StartupErrorsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_startup_errors")
        cls.lock = threading.Lock()
        cls.logs = []
        # /rosout itself: rostest starts no rosout node, so nothing relays to /rosout_agg. Each program
        # waits (up to 2 s) for a subscriber of /rosout before its FATAL line; this test is that one.
        cls.sub = rospy.Subscriber("/rosout", Log, cls.on_log, queue_size=1000)
        cls.tmp = tempfile.TemporaryDirectory()
        cls.counter = 0
        # A zone file and a mask that load, so that each case has one bad value only.
        cls.mask_png = os.path.join(cls.tmp.name, "mask.pgm")
        with open(cls.mask_png, "wb") as f:
            f.write(b"P5\n4 4\n255\n" + bytes([254] * 16))
        cls.mask_yaml = os.path.join(cls.tmp.name, "mask.yaml")
        with open(cls.mask_yaml, "w") as f:
            f.write("image: mask.pgm\nresolution: 0.5\norigin: [0.0, 0.0, 0.0]\n"
                    "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: scale\n")
        cls.zones_yaml = os.path.join(cls.tmp.name, "zones.yaml")
        with open(cls.zones_yaml, "w") as f:
            f.write("frame_id: map\nresolution: 0.5\n"
                    "shapes:\n  - name: box\n    type: polygon\n    value: 100\n"
                    "    points: [[0.5, 0.5], [2.0, 0.5], [2.0, 2.0]]\n")
        cls.features_yaml = os.path.join(cls.tmp.name, "features.yaml")
        with open(cls.features_yaml, "w") as f:
            f.write("limits:\n  - {area_id: 1, max_speed: 0.3}\n")

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    @classmethod
    def on_log(cls, msg):
        with cls.lock:
            cls.logs.append(msg)

    def run_program(self, prog, params, args=()):
        """Starts prog under a fresh name with params (a dict) set in its private namespace; returns
        (node name, exit code, stderr text)."""
        type(self).counter += 1
        name = "%s_bad_%d" % (prog, self.counter)
        for key, value in params.items():
            rospy.set_param("/%s/%s" % (name, key), value)
        proc = subprocess.run([program(prog), "__name:=" + name] + list(args), stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, timeout=60, cwd=self.tmp.name)
        return "/" + name, proc.returncode, proc.stderr.decode(errors="replace"), proc.stdout.decode(
            errors="replace")

    def fatal_on_rosout(self, node, timeout=10.0):
        deadline = time.time() + timeout
        while time.time() < deadline:
            with self.lock:
                found = [m for m in self.logs if m.name == node and m.level == Log.FATAL]
            if found:
                return found
            time.sleep(0.05)
        return []

    def check(self, prog, params, needles, args=()):
        node, code, err, out = self.run_program(prog, params, args)
        what = "%s with %r" % (prog, params)
        self.assertNotEqual(code, 0, "%s exited 0; stderr: %s" % (what, err))
        self.assertGreater(code, 0, "%s was killed by signal %d (an abort?); stderr: %s" % (what, -code, err))
        fatal_lines = [line for line in (err + out).splitlines() if "FATAL" in line]
        self.assertEqual(len(fatal_lines), 1, "%s: want one FATAL line, got:\n%s%s" % (what, err, out))
        for needle in needles:
            self.assertIn(needle, fatal_lines[0], what)
        # The stable key is the program's, whatever name the node runs under.
        self.assertIn("[%s/startup]" % prog, fatal_lines[0], what)
        logs = self.fatal_on_rosout(node)
        with self.lock:
            seen = sorted(set("%s:%d" % (m.name, m.level) for m in self.logs))
        self.assertEqual(len(logs), 1, "%s: want one FATAL on /rosout from %s, got %d (seen: %s)" %
                         (what, node, len(logs), ", ".join(seen)))
        for needle in needles:
            self.assertIn(needle, logs[0].msg, what)

    # --- zone_server: a file, a type, a name, a number.
    def test_zone_server(self):
        self.check("zone_server", {"yaml_filename": "no_such_zones.yaml"}, ["yaml_filename", "no_such_zones.yaml"])
        self.check("zone_server", {"yaml_filename": self.zones_yaml, "markers": "false"}, ["markers", "false"])
        self.check("zone_server", {"yaml_filename": self.zones_yaml, "topic": "9 lives"}, ["topic", "9 lives"])
        self.check("zone_server", {"yaml_filename": self.zones_yaml, "publish_rate": -2.0}, ["publish_rate", "-2"])
        self.check("zone_server", {}, ["yaml_filename"])

    # --- mask_server
    def test_mask_server(self):
        self.check("mask_server", {"yaml_filename": "missing_mask.yaml"}, ["yaml_filename", "missing_mask.yaml"])
        self.check("mask_server", {"yaml_filename": self.mask_yaml, "topic": "map filter"},
                   ["topic", "map filter"])
        self.check("mask_server", {"yaml_filename": self.mask_yaml, "frame_id": "map\nodom"}, ["frame_id"])
        self.check("mask_server", {"yaml_filename": self.mask_yaml, "topic": u"kart\u00e9"}, ["topic"])
        self.check("mask_server", {"yaml_filename": 5}, ["yaml_filename", "5"])

    # --- features_server
    def test_features_server(self):
        self.check("features_server", {"yaml_filename": "missing_features.yaml"},
                   ["yaml_filename", "missing_features.yaml"])
        self.check("features_server", {"yaml_filename": self.features_yaml, "topic": 7}, ["topic", "7"])
        self.check("features_server", {"yaml_filename": self.features_yaml, "frame_id": "ma p"},
                   ["frame_id", "ma p"])
        self.check("features_server", {"yaml_filename": self.features_yaml, "topic": u"/f\u00fchrer"}, ["topic"])

    # --- speed_limiter: strings where a number or a bool is expected, a range, a name.
    def test_speed_limiter(self):
        self.check("speed_limiter", {"command_timeout": "fast"}, ["command_timeout", "fast"])
        self.check("speed_limiter", {"publish_zero_when_stale": "no"}, ["publish_zero_when_stale", "no"])
        self.check("speed_limiter", {"command_timeout": -1.0}, ["command_timeout", "-1"])
        self.check("speed_limiter", {"max_speed_topic": "max speed"}, ["max_speed_topic", "max speed"])

    # --- costmap_filter_info_server: the filters' own rule for mask_topic.
    def test_costmap_filter_info_server(self):
        self.check("costmap_filter_info_server", {"mask_topic": "~private_mask"}, ["mask_topic", "~private_mask"])
        self.check("costmap_filter_info_server", {"mask_topic": "/mask", "type": 9}, ["type", "9"])
        self.check("costmap_filter_info_server", {"mask_topic": "/mask", "base": "zero"}, ["base", "zero"])
        self.check("costmap_filter_info_server", {"mask_topic": "/mask", "filter_info_topic": "a b"},
                   ["filter_info_topic", "a b"])

    # --- costmap_snapshot
    def test_costmap_snapshot(self):
        out = os.path.join(self.tmp.name, "snap.png")
        self.check("costmap_snapshot", {"timeout": -5.0, "output": out}, ["timeout", "-5"])
        self.check("costmap_snapshot", {"topic": "a b", "output": out}, ["topic", "a b"])
        self.check("costmap_snapshot", {"wait": "long", "output": out}, ["wait", "long"])

    # --- costmap_node
    def test_costmap_node(self):
        plugins = [{"name": "gradient", "type": "costmap_layers/GradientLayer"}]
        self.check("costmap_node", {"plugins": plugins, "update_frequency": "fast"}, ["update_frequency", "fast"])
        self.check("costmap_node", {"plugins": [{"name": "static layer", "type": "costmap_layers/StaticLayer"}]},
                   ["static layer"])
        self.check("costmap_node", {"plugins": plugins, "global_frame": "map odom"}, ["global_frame", "map odom"])
        self.check("costmap_node", {"plugins": plugins, "width": "wide"}, ["width", "wide"])

    # --- costmap_node with a PluginContainerLayer: its own plugin list, refused as the costmap's is.
    def test_costmap_node_container(self):
        group = [{"name": "group", "type": "costmap_layers/PluginContainerLayer"}]
        inflation = {"plugin": "costmap_layers/InflationLayer"}

        def nested(levels):
            inner = {"plugins": ["inflation"], "inflation": inflation}
            for k in range(levels, 1, -1):
                inner = {"plugins": ["c%d" % k], "c%d" % k: dict(inner, plugin="costmap_layers/PluginContainerLayer")}
            return inner

        self.check("costmap_node", {"plugins": group, "group": {"plugins": ["bogus"],
                                                                "bogus": {"plugin": "costmap_layers/NoSuchLayer"}}},
                   ["group/bogus", "costmap_layers/NoSuchLayer"])
        self.check("costmap_node", {"plugins": group, "group": {"plugins": ["a", "a"], "a": inflation}},
                   ["group", "'a'", "twice"])
        self.check("costmap_node", {"plugins": group, "group": {"plugins": []}}, ["group", "'plugins'", "[]"])
        self.check("costmap_node", {"plugins": group, "group": {"plugins": ["9lives"], "9lives": inflation}},
                   ["group", "'plugins'", "9lives"])
        self.check("costmap_node", {"plugins": group,
                                    "group": {"plugins": ["group"],
                                              "group": dict(nested(1), plugin="costmap_layers/PluginContainerLayer")}},
                   ["group", "'plugins'", "itself"])
        self.check("costmap_node", {"plugins": group, "group": nested(5)},
                   ["group/c2/c3/c4/c5", "nested 5 deep, at most 4"])
        self.check("costmap_node", {"plugins": group, "group": dict(nested(1), combination_method=7)},
                   ["group", "'combination_method'", "7"])

    # --- costmap_tool: no master; one error line and exit code 1.
    def test_costmap_tool(self):
        params = os.path.join(self.tmp.name, "bad_name.yaml")
        with open(params, "w") as f:
            f.write("plugins:\n  - {name: 'static layer', type: 'costmap_layers/StaticLayer'}\n")
        container = os.path.join(self.tmp.name, "container.yaml")
        with open(container, "w") as f:
            f.write("plugins: [group]\ngroup:\n  plugin: costmap_layers/PluginContainerLayer\n  plugins: [bogus]\n"
                    "  bogus: {plugin: costmap_layers/NoSuchLayer}\n")
        cases = [
            (["--map", self.mask_yaml, "--params", os.path.join(self.tmp.name, "none.yaml")], ["none.yaml"]),
            (["--map", self.mask_yaml, "--params", params], ["static layer"]),
            (["--map", self.mask_yaml, "--params", container], ["group/bogus", "costmap_layers/NoSuchLayer"]),
        ]
        for args, needles in cases:
            proc = subprocess.run([program("costmap_tool")] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                  timeout=60, cwd=self.tmp.name)
            err = proc.stderr.decode(errors="replace")
            self.assertEqual(proc.returncode, 1, "%r: %s" % (args, err))
            lines = [line for line in err.splitlines() if line.strip()]
            self.assertEqual(len(lines), 1, "%r: want one error line, got:\n%s" % (args, err))
            for needle in needles:
                self.assertIn(needle, lines[0])
            self.assertEqual(proc.stdout, b"", args)


if __name__ == "__main__":
    rostest.rosrun(PKG, "startup_errors", StartupErrorsTest)
