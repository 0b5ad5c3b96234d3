#!/usr/bin/env bash
# Redraws the README's pictures: runs costmap_tool on the bundled example (example/) once per
# picture and writes docs/pictures/<name>.png. Each picture has its params file in
# docs/pictures/params/ (the "all filters" one uses params/costmap_example.yaml, the demo's own).
# Needs a built package (install/); no ROS master. Deterministic: same inputs, same pictures.
#   scripts/dev/make_pictures.sh [OUTPUT_DIR]     (default: docs/pictures)
set -euo pipefail
export PATH=/usr/bin:/bin:$PATH
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
OUT="${1:-$ROOT/docs/pictures}"
PARAMS="$ROOT/docs/pictures/params"
EX="$ROOT/example"

if [ ! -f "$ROOT/install/setup.bash" ]; then
  echo "make_pictures: $ROOT/install/setup.bash not found: build the package first (scripts/dev/build.sh)" >&2
  exit 1
fi
# setup.bash reads unset variables: relax -u while sourcing it.
set +u
# shellcheck disable=SC1091
source "$ROOT/install/setup.bash"
set -u
mkdir -p "$OUT"

# picture NAME MAP PARAMS [costmap_tool options...]: one costmap_tool run, its JSON line echoed.
picture() {
  local name="$1" map="$2" params="$3"
  shift 3
  local json
  json="$(rosrun costmap_layers costmap_tool --map "$map" --params "$params" "$@" --out-png "$OUT/$name.png" | tail -n 1)"
  test -s "$OUT/$name.png" || { echo "make_pictures: $name.png was not written" >&2; exit 1; }
  echo "make_pictures: $name.png  $json"
}

picture static "$EX/warehouse.yaml" "$PARAMS/static.yaml"
picture inflation "$EX/warehouse.yaml" "$PARAMS/inflation.yaml"
picture keepout "$EX/warehouse.yaml" "$PARAMS/keepout.yaml" \
  --mask keepout_filter="$EX/keepout_mask.yaml"
# The robot half inside the loading dock: escape mode writes the dock as a ramp toward the way out.
picture keepout_escape "$EX/warehouse.yaml" "$PARAMS/keepout_escape.yaml" \
  --mask keepout_filter="$EX/keepout_mask.yaml" --pose 14.0,6.95,1.5708
picture lanes "$EX/warehouse.yaml" "$PARAMS/lanes.yaml" \
  --mask lanes_filter="$EX/lanes_mask.yaml"
picture speed_mask "$EX/speed_mask.yaml" "$PARAMS/speed_mask_as_map.yaml"
# The binary mask, as a map; the office labelled (example/binary_mask.pgm: 3-8 x 4.4-5.8 m).
picture binary_mask "$EX/binary_mask.yaml" "$PARAMS/binary_mask_as_map.yaml" --zoom 2 \
  --label "5.5,6.3,office: cameras off (mask 100)"
# The demo's configuration; the robot stands in speed area 1, so the JSON line reports its limit.
picture all_filters "$EX/warehouse.yaml" "$ROOT/params/costmap_example.yaml" \
  --mask keepout_filter="$EX/keepout_mask.yaml" --mask speed_filter="$EX/speed_mask.yaml" \
  --mask lanes_filter="$EX/lanes_mask.yaml" --features speed_filter="$EX/speed_limits.yaml" \
  --mask zone_keepout="$EX/zones.yaml" --mask binary_filter="$EX/binary_mask.yaml" \
  --pose 5.0,1.5,0.0
# The README's picture: the same at zoom 3, each zone, lane and speed area labelled where its file puts it
# (example/keepout_mask.pgm: the dock 12-15.8 x 7-9.8 m, the wet floor 13-15.8 x 0.2-2.6 m;
# speed_mask.pgm: area 1 x 4-7 m, area 2 x 9-12 m, y 0.2-3 m; binary_mask.pgm: the office 3-8 x 4.4-5.8 m;
# lanes_mask.pgm: 1-12.5 x 3.6-6.6 m; example/zones.yaml: the triangle, the fence, the puddle).
picture overview "$EX/warehouse.yaml" "$ROOT/params/costmap_example.yaml" \
  --mask keepout_filter="$EX/keepout_mask.yaml" --mask speed_filter="$EX/speed_mask.yaml" \
  --mask lanes_filter="$EX/lanes_mask.yaml" --features speed_filter="$EX/speed_limits.yaml" \
  --mask zone_keepout="$EX/zones.yaml" --mask binary_filter="$EX/binary_mask.yaml" \
  --pose 5.0,1.5,0.0 --zoom 3 \
  --label "13.9,8.4,loading dock: keepout" --label "14.4,1.0,wet floor: cost 127" \
  --label "5.5,0.7,speed area 1: 0.3 m/s" --label "10.5,0.7,area 2: 0.6 m/s" \
  --label "9.25,2.85,fence" --label "14.6,5.2,corner" --label "12.95,3.4,puddle" \
  --label "5.5,5.1,office: cameras off" --label "10.3,5.1,lanes"
# zone_server's mask (example/zones.yaml, rasterised as zone_server publishes it) in a KeepoutFilter.
picture zones "$EX/warehouse.yaml" "$PARAMS/zones.yaml" --mask zone_keepout="$EX/zones.yaml"
picture gradient "$EX/warehouse.yaml" "$PARAMS/gradient.yaml"
echo "make_pictures: done, pictures in $OUT"
