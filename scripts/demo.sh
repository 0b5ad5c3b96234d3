#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the demo (launch/demo.launch): a warehouse
# with a keepout zone, two speed zones, a lane network and zones drawn as shapes (zone_server), a scripted robot driving through them,
# every /max_speed change printed with the robot's position, and the published costmap written as a
# PNG into demo_output/. Ends by itself.
set -euo pipefail
source "$(dirname "$0")/lib/common.sh"
build_package
source_install
OUT="${DEMO_OUTPUT:-$ROOT/demo_output}"
mkdir -p "$OUT"
rm -f "$OUT/demo_costmap.png"
export ROS_HOME="${ROS_HOME:-$OUT/ros_home}"
echo "demo: starting roslaunch (about a minute; ends by itself)"
roslaunch --screen costmap_layers demo.launch output_dir:="$OUT" 2>&1 | grep --line-buffered -E "^demo:|costmap_snapshot|ERROR|FATAL|WARN" || true
test -s "$OUT/demo_costmap.png" || { echo "demo: FAILED, no picture was written" >&2; exit 1; }
rosrun costmap_layers costmap_tool --map "$ROOT/example/warehouse.yaml" --params "$ROOT/params/costmap_example.yaml" \
  --mask keepout_filter="$ROOT/example/keepout_mask.yaml" --mask lanes_filter="$ROOT/example/lanes_mask.yaml" \
  --mask speed_filter="$ROOT/example/speed_mask.yaml" --features speed_filter="$ROOT/example/speed_limits.yaml" \
  --mask zone_keepout="$ROOT/example/zones.yaml" --mask binary_filter="$ROOT/example/binary_mask.yaml" \
  --pose 5.0,1.5,0.0 --out-png "$OUT/tool_costmap.png" > "$OUT/tool.json"
echo "demo: costmap_tool on the same inputs, robot at (5.0, 1.5) in area 1: $(tail -n 1 "$OUT/tool.json")"
echo "demo: pictures: $OUT/demo_costmap.png (published by the node), $OUT/tool_costmap.png (costmap_tool)"
