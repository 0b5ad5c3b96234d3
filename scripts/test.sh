#!/usr/bin/env bash
# Every test: installs what is missing, builds (Release), runs the unit tests, the tool tests and the
# rostests through colcon, then the core's unit tests under ASan + UBSan and a replay of every fuzz
# target's committed seeds and regression inputs (deterministic: random fuzzing is scripts/dev/fuzz.sh's
# own job), prints every failure, and exits non-zero when any test fails.
set -euo pipefail
source "$(dirname "$0")/lib/common.sh"
build_package
cd "$ROOT"
export ROS_HOME="${ROS_HOME:-$ROOT/log/ros_home}"
rm -rf "$ROOT/build/costmap_layers/test_results"
set +e
colcon --log-base "$ROOT/log" test --base-paths "$ROOT" --build-base "$ROOT/build" --install-base "$ROOT/install" \
  --event-handlers console_cohesion+ --return-code-on-test-failure
test_rc=$?
# The core's unit tests again under AddressSanitizer + UndefinedBehaviorSanitizer (own small build).
bash "$ROOT/scripts/dev/sanitize.sh" > "$ROOT/log/sanitize.log" 2>&1
sanitize_rc=$?
tail -n 3 "$ROOT/log/sanitize.log"
[ "$sanitize_rc" -eq 0 ] || { echo "test.sh: the sanitizer run failed, see log/sanitize.log:"; tail -n 60 "$ROOT/log/sanitize.log"; }
# Every libFuzzer target on its committed seeds and regression inputs, each run once.
FUZZ_SECONDS=0 bash "$ROOT/scripts/dev/fuzz.sh" > "$ROOT/log/fuzz.log" 2>&1
fuzz_rc=$?
tail -n 12 "$ROOT/log/fuzz.log"
[ "$fuzz_rc" -eq 0 ] || { echo "test.sh: a fuzz target failed, see log/fuzz.log:"; tail -n 60 "$ROOT/log/fuzz.log"; }
# The package as a ROS 1 user builds it: a clone in a fresh catkin workspace, built with catkin_make.
bash "$ROOT/scripts/dev/catkin_make_check.sh" > "$ROOT/log/catkin_make_check.log" 2>&1
catkin_make_rc=$?
tail -n 2 "$ROOT/log/catkin_make_check.log"
[ "$catkin_make_rc" -eq 0 ] || { echo "test.sh: the catkin_make build failed, see log/catkin_make_check.log:"; tail -n 40 "$ROOT/log/catkin_make_check.log"; }
colcon test-result --test-result-base "$ROOT/build" --verbose > "$ROOT/log/test-result.txt" 2>&1
result_rc=$?
set -e
cat "$ROOT/log/test-result.txt"
# One plain closing line: count the test cases in the JUnit files.
python3 - "$ROOT/build/costmap_layers/test_results" <<'PY'
import glob, sys, xml.etree.ElementTree as ET
passed = failed = skipped = 0
for f in glob.glob(sys.argv[1] + "/**/*.xml", recursive=True):
    try:
        root = ET.parse(f).getroot()
    except ET.ParseError:
        failed += 1
        continue
    for case in root.iter("testcase"):
        if case.find("failure") is not None or case.find("error") is not None:
            failed += 1
        elif case.find("skipped") is not None:
            skipped += 1
        else:
            passed += 1
print(f"tests: {passed} passed, {failed} failed, {skipped} skipped")
PY
# Say plainly whether the move_base integration ran.
move_base_rc=0
if costmap_2d_at="$(ros_package_prefix costmap_2d)"; then
  if ros_package_prefix move_base > /dev/null; then
    n=$(python3 - "$ROOT/build/costmap_layers/test_results" <<'PY'
import glob, sys, xml.etree.ElementTree as ET
def cases(pattern):
    return sum(sum(1 for _ in ET.parse(f).getroot().iter("testcase"))
               for f in glob.glob(sys.argv[1] + "/**/" + pattern, recursive=True))
n = cases("rosunit-move_base_integration.xml")
# move_base beside costmap_2d's own plugins in every order, the asymmetric inflation on navfn's plans,
# and launch/move_base.launch
m = cases("rosunit-move_base_mixed_*.xml") + cases("rosunit-move_base_asymmetric.xml") \
    + cases("rosunit-move_base_launch_file.xml")
b = cases("rosunit-bridge.xml")  # LayerBridge in costmap_2d's own LayeredCostmap (test/move_base/bridge)
print(n, m, b)
PY
)
    read -r n m b <<< "$n"
    if [ "$n" -gt 0 ] && [ "$m" -gt 0 ] && [ "$b" -gt 0 ]; then
      echo "move_base integration: $n test cases run, $m in the mixed-order, asymmetric-inflation and launch-file scenarios, and $b of" \
        "LayerBridge in costmap_2d's LayeredCostmap (costmap_2d from $costmap_2d_at)"
    else
      echo "move_base integration: FAILED to run: costmap_2d and move_base are there but no move_base test result" >&2
      move_base_rc=1
    fi
  else
    echo "move_base integration: not run, move_base not found (costmap_2d is, in $costmap_2d_at); see README.md," \
      "\"Use it inside move_base\""
  fi
else
  echo "move_base integration: not run, costmap_2d not found; see README.md, \"Use it inside move_base\"" \
    "(on Debian 12: scripts/build_navigation.sh SOURCES)"
fi
# Say plainly whether the RViz view test ran (test/rostest/rviz/rviz.test: RViz headless on the shipped
# config; CMake registers it only where Xvfb and RViz's Python bindings are).
rviz_rc=0
n=$(python3 - "$ROOT/build/costmap_layers/test_results" <<'PY'
import glob, sys, xml.etree.ElementTree as ET
print(sum(sum(1 for _ in ET.parse(f).getroot().iter("testcase"))
          for f in glob.glob(sys.argv[1] + "/**/rosunit-rviz_view_test.xml", recursive=True)))
PY
)
if [ "$n" -gt 0 ]; then
  echo "RViz view test: $n test cases run (RViz under Xvfb on launch/costmap.rviz with the demo's nodes)"
elif command -v Xvfb > /dev/null && python3 -c "from rviz import bindings" 2> /dev/null; then
  echo "RViz view test: FAILED to run: Xvfb and RViz's Python bindings are there but no result" >&2
  rviz_rc=1
else
  echo "RViz view test: not run, needs Xvfb and RViz's Python bindings (apt-get install xvfb python3-rviz rviz)"
fi
if [ "$test_rc" -ne 0 ] || [ "$move_base_rc" -ne 0 ] || [ "$result_rc" -ne 0 ] || [ "$sanitize_rc" -ne 0 ] || [ "$fuzz_rc" -ne 0 ] || [ "$catkin_make_rc" -ne 0 ] || [ "$rviz_rc" -ne 0 ]; then
  echo "test.sh: FAILED (colcon test rc=$test_rc, test-result rc=$result_rc, sanitizers rc=$sanitize_rc," \
    "fuzzing rc=$fuzz_rc, catkin_make rc=$catkin_make_rc, move_base integration rc=$move_base_rc, RViz view test rc=$rviz_rc)" >&2
  exit 1
fi
echo "test.sh: all tests passed"
