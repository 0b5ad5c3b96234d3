#!/usr/bin/env bash
# The soak test (minutes long, not part of scripts/test.sh): costmap_node at 20 Hz on the 4000x4000
# synthetic map with three filters and two sensor sources at 40 Hz, masks and features republished
# every second, tf jumps, bursts of malformed messages. Checks memory growth after warm-up, update
# overruns, and that /max_speed and the costmap still answer.   SOAK_SECONDS=600 scripts/dev/soak.sh
set -euo pipefail
source "$(dirname "$0")/../lib/common.sh"
build_package
source_install
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
python3 "$ROOT/scripts/dev/make_synthetic_map.py" "$TMP"
export ROS_HOME="${ROS_HOME:-$ROOT/log/soak_ros_home}"
set +e
roslaunch --screen "$ROOT/test/soak/soak.launch" map:="$TMP/synthetic_indoor_4000.yaml" \
  seconds:="${SOAK_SECONDS:-300}" example:="$ROOT/example" params:="$ROOT/test/soak/soak.yaml" 2>&1 | tee "$TMP/soak.log" | grep --line-buffered -E "^soak:|FATAL|ERROR"
set -e
grep -q "^soak: PASSED" "$TMP/soak.log"
