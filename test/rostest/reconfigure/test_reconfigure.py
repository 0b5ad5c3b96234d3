#!/usr/bin/env python3
"""dynamic_reconfigure on a running costmap_node: the inflation radius changed through the standard
client changes the published costmap at the next update; a bad value is refused and changes
nothing; switching the layer off removes its costs."""
import os
import sys
import threading
import unittest

import dynamic_reconfigure.client
import rospy
import rostest
from rosgraph_msgs.msg import Log

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from grid_watch import CycleWatcher, GridWatcher  # noqa: E402

# The left wall covers x 0..0.2 m: its innermost cells' centres are at x = 0.175 m. The cell centred
# at x = 0.825 m lies 13 cells (0.65 m) from it: outside a 0.55 m radius (11 cells), inside a 1.0 m
# one, where it costs (uchar)(252 * exp(-10 * (0.65 - inscribed))) > 0.
NEAR = (0.6, 5.0)    # 0.425 m from the wall: inflated either way
FAR = (0.83, 5.0)


class ReconfigureTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_reconfigure")
        cls.grid = GridWatcher("/costmap_node")
        cls.cycles = CycleWatcher("/costmap_node")
        # The node's lines on /rosout, from the start (a subscription made later may miss the first).
        cls.logs = []
        cls.log_lock = threading.Lock()

        def on_log(m):
            if m.name == "/costmap_node":
                with cls.log_lock:
                    cls.logs.append(m)

        rospy.Subscriber("/rosout", Log, on_log)
        assert cls.grid.wait_until(lambda g: g.at(*NEAR) > 0, 30.0), "no inflated costmap published"

    def test_radius_change_bad_value_and_switch_off(self):
        client = dynamic_reconfigure.client.Client("/costmap_node/inflation_layer", timeout=20)
        config = client.get_configuration(timeout=10)
        self.assertAlmostEqual(config["inflation_radius"], 0.55)
        self.assertAlmostEqual(config["cost_scaling_factor"], 10.0)
        self.assertEqual(self.grid.at(*FAR), 0)

        result = client.update_configuration({"inflation_radius": 1.0})
        self.assertAlmostEqual(result["inflation_radius"], 1.0)
        self.assertTrue(self.grid.wait_until(lambda g: g.at(*FAR) > 0, 10.0), "the larger radius did not show")
        cost_far = self.grid.at(*FAR)

        # A negative radius is refused: the answer keeps 1.0 and the costmap stays as it is.
        result = client.update_configuration({"inflation_radius": -2.0})
        self.assertAlmostEqual(result["inflation_radius"], 1.0)
        self.assertTrue(self.cycles.wait(3), "the update loop stopped")  # the refused value had its chance
        self.assertEqual(self.grid.at(*FAR), cost_far)

        result = client.update_configuration({"enabled": False})
        self.assertFalse(result["enabled"])
        self.assertTrue(self.grid.wait_until(lambda g: g.at(*NEAR) == 0 and g.at(*FAR) == 0, 10.0),
                        "switching the inflation layer off did not remove its costs")
        client.update_configuration({"enabled": True, "inflation_radius": 0.55})
        self.assertTrue(self.grid.wait_until(lambda g: g.at(*NEAR) > 0 and g.at(*FAR) == 0, 10.0))

    def test_a_flood_of_unknown_names_is_one_short_line_per_second(self):
        # 200 names of 10^4 characters each, 10 calls in a row: the node answers every call, names the
        # first few clipped with the count, and logs at most one line per layer per second.
        from dynamic_reconfigure.msg import Config, DoubleParameter
        from dynamic_reconfigure.srv import Reconfigure
        rospy.wait_for_service("/costmap_node/inflation_layer/set_parameters", timeout=20)
        call = rospy.ServiceProxy("/costmap_node/inflation_layer/set_parameters", Reconfigure)
        names = [("x%03d" % k) * 2500 for k in range(200)]

        def said():
            with self.log_lock:
                return [m.msg for m in self.logs if "ignored parameters" in m.msg]

        # Bursts of 10 calls until a line has come through /rosout (a line the node logs before this
        # test's /rosout connection is up is lost: the bound below only gets easier then).
        start = rospy.get_time()
        deadline = start + 30.0
        while True:
            for _ in range(10):
                answer = call(Config(doubles=[DoubleParameter(n, 1.0) for n in names]))
                self.assertAlmostEqual({p.name: p.value for p in answer.config.doubles}["inflation_radius"], 0.55)
            burst_end = rospy.get_time() + 2.0
            while not said() and rospy.get_time() < burst_end:
                rospy.sleep(0.1)  # polled with a deadline: /rosout relays the node's lines
            if said() or rospy.get_time() > deadline:
                break
        elapsed = rospy.get_time() - start
        self.assertTrue(self.cycles.wait(3), "the update loop stopped")  # and whatever else was said arrives
        lines = said()
        self.assertGreaterEqual(len(lines), 1, "the ignored names were not reported")
        self.assertLessEqual(len(lines), int(elapsed) + 1, "%d lines in %.1f s" % (len(lines), elapsed))
        self.assertLess(len(lines[0]), 1500, lines[0][:300])
        self.assertIn("(200 in all)", lines[0])

if __name__ == "__main__":
    rostest.rosrun("costmap_layers", "reconfigure", ReconfigureTest)
