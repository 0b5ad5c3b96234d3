#!/usr/bin/env bash
# Builds the core and its unit tests with sanitizers and runs them.
#   scripts/dev/sanitize.sh                 ASan + UBSan (what scripts/test.sh runs)
#   SANITIZE=thread scripts/dev/sanitize.sh TSan
set -euo pipefail
source "$(dirname "$0")/../lib/common.sh"
bash "$ROOT/scripts/lib/install_deps.sh"
SAN="${SANITIZE:-address,undefined}"
BUILD="$ROOT/build/sanitize-${SAN//,/-}"
mkdir -p "$ROOT/build"
cmake -S "$ROOT/test/sanitize" -B "$BUILD" -DSANITIZE="$SAN" -DCMAKE_BUILD_TYPE=RelWithDebInfo > "$BUILD.configure.log" 2>&1 \
  || { cat "$BUILD.configure.log"; exit 1; }
cmake --build "$BUILD" -j2
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
mkdir -p "$ROOT/build/costmap_layers/test_results/costmap_layers"
"$BUILD/test_core_sanitized" --gtest_output="xml:$ROOT/build/costmap_layers/test_results/costmap_layers/gtest-core-sanitized-${SAN//,/-}.xml" "$@"
