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
for exe in "$ROOT"/build/costmap_layers/devel/lib/costmap_layers/bench_*; do
  [ -x "$exe" ] && [ "${exe%.py}" = "$exe" ] || continue
  name=$(basename "$exe")
  echo "== $name"
  "$exe" --benchmark_repetitions="${BENCH_REPETITIONS:-5}" --benchmark_report_aggregates_only=true \
    --benchmark_out="$OUT/$name.json" --benchmark_out_format=json "$@"
  python3 "$ROOT/scripts/bench_ratios.py" "$OUT/$name.json"
done
