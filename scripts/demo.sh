#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the demo (roslaunch), which starts the
# costmap node on the bundled example and writes what it publishes as PNG pictures into demo_output/.
set -euo pipefail
source "$(dirname "$0")/common.sh"
build_package
source_install
OUT="${DEMO_OUTPUT:-$ROOT/demo_output}"
mkdir -p "$OUT"
export ROS_HOME="${ROS_HOME:-$OUT/ros_home}"
echo "demo: starting roslaunch (ends by itself)"
roslaunch --screen costmap_layers gradient_demo.launch output:="$OUT/gradient_costmap.png"

test -s "$OUT/gradient_costmap.png" || { echo "demo: FAILED, no picture was written" >&2; exit 1; }
echo "demo: the published costmap is in $OUT/gradient_costmap.png"
