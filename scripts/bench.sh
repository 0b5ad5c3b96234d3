#!/usr/bin/env bash
# Builds (Release) and runs every benchmark in bench/, then prints each result as a ratio to the
# memcpy of the same 4000x4000 grid measured in the same run. COSTMAP_LAYERS_BENCH_MAP=/path/map.yaml
# benchmarks another map than the synthetic one (scripts/make_synthetic_map.py).
set -euo pipefail
source "$(dirname "$0")/common.sh"
build_package
OUT="${BENCH_OUTPUT:-$ROOT/log/bench}"
mkdir -p "$OUT"
# The big map: the synthetic 4000x4000 one, written here deterministically, unless a map is given.
if [ -z "${COSTMAP_LAYERS_BENCH_MAP:-}" ]; then
  python3 "$ROOT/scripts/make_synthetic_map.py" "$OUT/maps"
  export COSTMAP_LAYERS_BENCH_MAP="$OUT/maps/synthetic_indoor_4000.yaml"
fi
# bench_move_base (built when costmap_2d is found) hosts the bridge, which reads parameters: give it a
# master of its own on a free port, stopped on exit.
with_master() {
  local port pid rc
  port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
  ROS_MASTER_URI="http://127.0.0.1:$port" rosmaster --core -p "$port" > "$OUT/rosmaster.log" 2>&1 &
  pid=$!
  for _ in $(seq 100); do
    ROS_MASTER_URI="http://127.0.0.1:$port" python3 -c 'import rosgraph, sys; sys.exit(0 if rosgraph.is_master_online() else 1)' \
      2> /dev/null && break
    sleep 0.1
  done
  set +e
  ROS_MASTER_URI="http://127.0.0.1:$port" "$@"
  rc=$?
  set -e
  kill "$pid" 2> /dev/null || true
  wait "$pid" 2> /dev/null || true
  return $rc
}
source_install
for exe in "$ROOT"/build/costmap_layers/devel/lib/costmap_layers/bench_*; do
  [ -x "$exe" ] && [ "${exe%.py}" = "$exe" ] || continue
  name=$(basename "$exe")
  echo "== $name"
  runner=()
  [ "$name" = bench_move_base ] && runner=(with_master)
  "${runner[@]}" "$exe" --benchmark_repetitions="${BENCH_REPETITIONS:-5}" --benchmark_report_aggregates_only=true \
    --benchmark_out="$OUT/$name.json" --benchmark_out_format=json "$@"
  python3 "$ROOT/scripts/bench_ratios.py" "$OUT/$name.json"
done
