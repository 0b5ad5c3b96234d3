#!/usr/bin/env bash
# Builds (Release) and runs every benchmark in bench/, then prints each result as a ratio to the
# memcpy of the same grid measured in the same run (median and minimum).
#   COSTMAP_LAYERS_BENCH_MAP=/path/map.yaml     benchmarks another map than the synthetic 4000x4000
#                                               one (scripts/dev/make_synthetic_map.py); the inflation
#                                               sweep then reads it at 0.025, 0.05 and 0.1 m
#   COSTMAP_LAYERS_BENCH_MAPS="a.yaml b.yaml"   after that, the whole static + inflation update of
#                                               each of these maps at its own resolution (the sweep
#                                               of radii, factors 3 and 10), e.g. willow and warehouse
#   BENCH_REPETITIONS=5                         repetitions of each benchmark
#   COSTMAP_LAYERS_BENCH_TARGET=AVX3            the inflation benchmarks on that SIMD target only (a
#                                               name the BM_InflationTarget_* rows show), to compare
#                                               two targets with the same binary
# Extra arguments go to every benchmark program (e.g. --benchmark_filter=Sweep).
set -euo pipefail
source "$(dirname "$0")/lib/common.sh"
build_package
OUT="${BENCH_OUTPUT:-$ROOT/log/bench}"
mkdir -p "$OUT"
# The big map: the synthetic 4000x4000 one, written here deterministically, unless a map is given.
if [ -z "${COSTMAP_LAYERS_BENCH_MAP:-}" ]; then
  python3 "$ROOT/scripts/dev/make_synthetic_map.py" "$OUT/maps"
  export COSTMAP_LAYERS_BENCH_MAP="$OUT/maps/synthetic_indoor_4000.yaml"
fi
# bench_move_base and bench_sensor_path (its costmap_2d side, built when costmap_2d is found) read
# parameters from a master: give them one of their own on a free port, stopped on exit.
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
BIN="$ROOT/build/costmap_layers/devel/lib/costmap_layers"
run() {  # run NAME EXE [ARGS...]: one benchmark program, its JSON, its ratios
  local name=$1 exe=$2
  shift 2
  echo "== $name"
  runner=()
  case "$name" in bench_move_base | bench_sensor_path) runner=(with_master) ;; esac
  "${runner[@]}" "$exe" --benchmark_repetitions="${BENCH_REPETITIONS:-5}" --benchmark_report_aggregates_only=true \
    --benchmark_out="$OUT/$name.json" --benchmark_out_format=json "$@"
  if [ "$name" = bench_sensor_path ]; then
    sensor_path_rows "$OUT/$name.json"
  else
    python3 "$ROOT/scripts/dev/bench_ratios.py" "$OUT/$name.json"
  fi
}
# bench_sensor_path times both sides and a memcpy in its own counters: their medians and minima over
# the repetitions, ours / costmap_2d's side by side (issue 38).
sensor_path_rows() {
  python3 - "$1" << 'EOF_PY'
import json, sys
rows = {}
for b in json.load(open(sys.argv[1]))["benchmarks"]:
    agg = b.get("aggregate_name")
    if agg in ("median", "min"):
        rows.setdefault(b["run_name"], {"label": b.get("label", "")})[agg] = b
keys = ["ours_msg_us", "c2d_msg_us", "ratio_msg", "ours_cycle_us", "c2d_cycle_us", "ratio_cycle",
        "ours_cpu_ms_per_s", "c2d_cpu_ms_per_s", "ratio_cpu", "ours_msg_x_memcpy", "lethal_agree_pct"]
for name, r in rows.items():
    print(f"{name}  ({r['label']})")
    for k in keys:
        if k in r.get("median", {}):
            print(f"    {k:20s} median {r['median'][k]:10.4g}   min {r.get('min', {}).get(k, float('nan')):10.4g}")
EOF_PY
}
for exe in "$BIN"/bench_*; do
  [ -x "$exe" ] && [ "${exe%.py}" = "$exe" ] || continue
  run "$(basename "$exe")" "$exe" "$@"
done
for map in ${COSTMAP_LAYERS_BENCH_MAPS:-}; do
  COSTMAP_LAYERS_BENCH_MAP="$map" COSTMAP_LAYERS_BENCH_RESOLUTIONS=native \
    run "bench_inflation_$(basename "${map%.yaml}")" "$BIN/bench_inflation" \
    --benchmark_filter='MemcpyMap|StaticPlus|Sweep' "$@"
done
