#!/usr/bin/env bash
# The whole package (libraries, plugins, node, tool, tests) built with sanitizers in its own workspace
# folders, then tested:
#   scripts/dev/sanitize_package.sh                 ASan + UBSan: every unit test (core, io) and the tool's
#                                               tests (they run the real, instrumented costmap_tool)
#   SANITIZE=thread scripts/dev/sanitize_package.sh TSan: the node-level rostests, with the node's
#                                               callbacks on spinner threads while its update loop runs
#   ROSTESTS="hostile filters" ...              TSan: only these rostests
#   ROSTESTS="zone_params zone_server" scripts/dev/sanitize_package.sh
#                                               ASan + UBSan: these rostests (their nodes instrumented)
#                                               in place of the unit tests
#   TARGETS="costmap_node costmap_layers_plugins zone_server" ...
#                                               build only these programs (for the rostests chosen)
#   ROSTESTS=move_base TARGETS="costmap_node costmap_layers_plugins mask_server costmap_layers_move_base" ...
#                                               test/move_base/move_base.test: move_base from the
#                                               navigation underlay (not instrumented) with the
#                                               instrumented plugins, the sanitizer runtime preloaded
# A ROSTESTS name is a folder of test/rostest/ or test/move_base/, or a file of test/move_base/ (without
# .test), exactly.
# Either run fails when a test fails or when a sanitizer reports anything (leaks included) that
# test/tsan.supp or test/lsan.supp does not suppress. The reports are kept in build_<kind>/reports/.
set -euo pipefail
source "$(dirname "$0")/../lib/common.sh"
bash "$ROOT/scripts/lib/install_deps.sh"
SAN="${SANITIZE:-address,undefined}"
case "$SAN" in
  thread) KIND=tsan; PRELOAD=(tsan) ;;
  address,undefined) KIND=asan; PRELOAD=(asan ubsan) ;;
  address) KIND=asan; PRELOAD=(asan) ;;
  *) echo "sanitize_package.sh: SANITIZE must be 'address,undefined' or 'thread', not '$SAN'" >&2; exit 2 ;;
esac
BUILD_BASE="$ROOT/build_$KIND"
INSTALL_BASE="$ROOT/install_$KIND"
REPORTS="$BUILD_BASE/reports"
# The tests to run (checked before the build).
if [ "$KIND" = asan ] && [ -z "${ROSTESTS:-}" ]; then
  tests_regex='gtest_test_(core|io|ros)$'
else
  names="${ROSTESTS:-hostile filters sensors speed_limiter reconfigure plugin_loading}"
  # Each name is a folder test/rostest/<name> or test/move_base/<name> (all its .test files) or a file
  # test/move_base/<name>.test; catkin names their tests rostest_test_rostest_<name>_<file>,
  # rostest_test_move_base_<name>_<file> and rostest_test_move_base_<file>.
  alternatives=()
  for name in $names; do
    found=0
    for f in "$ROOT/test/rostest/$name"/*.test "$ROOT/test/move_base/$name"/*.test "$ROOT/test/move_base/$name.test"; do
      [ -f "$f" ] || continue
      found=1
      rel="${f#"$ROOT/"}"
      alternatives+=("$(echo "${rel//\//_}" | sed 's/\./\\./g')")
    done
    if [ "$found" -eq 0 ]; then
      echo "sanitize_package.sh: no rostest named '$name' (test/rostest/$name/, test/move_base/$name/ or test/move_base/$name.test)" >&2
      exit 2
    fi
  done
  tests_regex="rostest_($(IFS='|'; echo "${alternatives[*]}"))\$"
fi
cd "$ROOT"
# costmap_2d and move_base (the bridge, its plugins and the move_base rostests) come from the navigation
# underlay when it is built, as in scripts/dev/build.sh; a build folder configured without it is configured
# afresh.
if source_navigation_underlay; then
  echo "sanitize_package.sh: with the navigation underlay in $(navigation_underlay_dir)"
fi
fresh="$(navigation_underlay_configure_args "$BUILD_BASE")"
# TARGETS="costmap_node zone_server ...": build only these (and the messages the Python tests import) in
# place of the whole package, for rostests that run only those programs; the rostests run from the
# build's devel space, so nothing is installed then.
targets=()
if [ -n "${TARGETS:-}" ]; then
  read -r -a targets <<< "$TARGETS costmap_layers_generate_messages"
  target_args=(--cmake-target "${targets[0]}")
else
  target_args=()
fi
colcon --log-base "$ROOT/log" build --base-paths "$ROOT" --build-base "$BUILD_BASE" --install-base "$INSTALL_BASE" \
  --event-handlers console_cohesion- "${target_args[@]}" $fresh --cmake-args -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCOSTMAP_LAYERS_SANITIZE="$SAN" -DCATKIN_ENABLE_TESTING=ON
if [ "${#targets[@]}" -gt 1 ]; then
  make -C "$BUILD_BASE/costmap_layers" -j2 "${targets[@]:1}"
fi
navigation_underlay_stamp "$BUILD_BASE"
rm -rf "$REPORTS" "$BUILD_BASE/costmap_layers/test_results"
mkdir -p "$REPORTS"
export ROS_HOME="$BUILD_BASE/ros_home"
# Every instrumented process writes its reports to REPORTS/<kind>.<pid> instead of stderr, so a
# report from a node that roslaunch started is not lost in a log file nobody reads.
export ASAN_OPTIONS="detect_leaks=1:log_path=$REPORTS/asan"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:log_path=$REPORTS/ubsan"
export LSAN_OPTIONS="suppressions=$ROOT/test/lsan.supp"
# move_base comes from the navigation underlay and is not instrumented: the sanitizer runtime must be
# loaded before anything else for the instrumented plugins it loads, so the move_base rostests start it
# with this prefix (their launch-prefix, empty by default). With the runtime preloaded, its interceptors
# see every allocation of move_base, so leaks and races inside move_base's own libraries can show up;
# test/lsan.supp and test/tsan.supp name those libraries.
preload=""
for rt in "${PRELOAD[@]}"; do
  preload="$preload${preload:+:}$(gcc -print-file-name="lib$rt.so")"
done
export COSTMAP_LAYERS_MOVE_BASE_PREFIX="env LD_PRELOAD=$preload"
export TSAN_OPTIONS="suppressions=$ROOT/test/tsan.supp:print_suppressions=1:second_deadlock_stack=1:history_size=4:log_path=$REPORTS/tsan"

set +e
colcon --log-base "$ROOT/log" test --base-paths "$ROOT" --build-base "$BUILD_BASE" --install-base "$INSTALL_BASE" \
  --event-handlers console_cohesion+ --return-code-on-test-failure --ctest-args -R "$tests_regex"
test_rc=$?
colcon test-result --test-result-base "$BUILD_BASE" --verbose
result_rc=$?
set -e
ran=$(find "$BUILD_BASE/costmap_layers/test_results" -name '*.xml' | wc -l)
# A file holds a report when a sanitizer warned; TSan also writes the suppressions it matched.
report_pattern='WARNING: ThreadSanitizer|ERROR: AddressSanitizer|ERROR: LeakSanitizer|runtime error:'
reported=$(grep -l -E "$report_pattern" -r "$REPORTS" || true)
reports=$({ grep -h -c -E "$report_pattern" -r "$REPORTS" || true; } | awk '{n += $1} END {print n + 0}')
for f in $reported; do
  echo "=== $f"
  head -n 100 "$f"
done
if [ "$KIND" = tsan ]; then
  echo "suppressed (test/tsan.supp), summed over every process:"
  { grep -h -E '^ *[0-9]+ (race|deadlock|thread|mutex|signal|called_from_lib):' -r "$REPORTS" || true; } \
    | awk '{n[$2] += $1} END {for (k in n) printf "  %6d %s\n", n[k], k}' | sort -k2
fi
echo "sanitize_package.sh ($SAN): $ran test result files, $reports sanitizer reports, colcon test rc=$test_rc"
if [ "$ran" -eq 0 ] || [ "$reports" -ne 0 ] || [ "$test_rc" -ne 0 ] || [ "$result_rc" -ne 0 ]; then
  echo "sanitize_package.sh: FAILED" >&2
  exit 1
fi
echo "sanitize_package.sh: passed, no sanitizer report"
