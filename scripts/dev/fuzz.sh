#!/usr/bin/env bash
# Builds the libFuzzer targets (test/fuzz, clang + ASan + UBSan) into build/fuzz and runs each one:
# first every input kept in test/fuzz/regressions/<target>/ (inputs that once crashed), then
# FUZZ_SECONDS of fuzzing from the seed corpus test/fuzz/corpus/<target>/. Fails when any target
# crashes, leaks, times out or breaks an invariant; the input is saved in build/fuzz/artifacts/<target>/.
#   FUZZ_SECONDS=0 scripts/dev/fuzz.sh        replay only: every regression input and every committed seed,
#                                         each run once (deterministic: what scripts/test.sh runs)
#   scripts/dev/fuzz.sh                       every target for 10 s of random fuzzing
#   FUZZ_SECONDS=600 scripts/dev/fuzz.sh      the long run
#   FUZZ_TARGETS="mask params" scripts/dev/fuzz.sh   some targets only
# New inputs the fuzzer finds go to build/fuzz/corpus/<target>/ (kept between runs, not committed).
# To reproduce a crash: build/fuzz/fuzz_<target> <input file>
set -euo pipefail
source "$(dirname "$0")/../lib/common.sh"
bash "$ROOT/scripts/lib/install_deps.sh"
SECONDS_PER_TARGET="${FUZZ_SECONDS:-10}"
BUILD="$ROOT/build/fuzz"
mkdir -p "$BUILD"
cmake -S "$ROOT/test/fuzz" -B "$BUILD" -DCMAKE_CXX_COMPILER=clang++ > "$BUILD/configure.log" 2>&1 \
  || { cat "$BUILD/configure.log"; exit 1; }
cmake --build "$BUILD" -j2 > "$BUILD/build.log" 2>&1 || { tail -n 40 "$BUILD/build.log"; exit 1; }

TARGETS="${FUZZ_TARGETS:-$(cd "$ROOT/test/fuzz" && ls fuzz_*.cpp | sed 's/^fuzz_//; s/\.cpp$//' | tr '\n' ' ')}"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
failed=()
for t in $TARGETS; do
  exe="$BUILD/fuzz_$t"
  [ -x "$exe" ] || { echo "fuzz.sh: no target fuzz_$t"; failed+=("$t"); continue; }
  log="$BUILD/fuzz_$t.log"
  mkdir -p "$BUILD/corpus/$t" "$BUILD/artifacts/$t"
  # 1. The regressions, each run once.
  shopt -s nullglob
  regressions=("$ROOT/test/fuzz/regressions/$t"/*)
  shopt -u nullglob
  if [ ${#regressions[@]} -gt 0 ]; then
    if ! "$exe" -artifact_prefix="$BUILD/artifacts/$t/" "${regressions[@]}" > "$log.regressions" 2>&1; then
      echo "fuzz.sh: $t: a regression input fails again:"; tail -n 40 "$log.regressions"; failed+=("$t"); continue
    fi
  fi
  # 2a. Replay only: every committed seed once, nothing random (-runs=0 stops after reading the corpus).
  if [ "$SECONDS_PER_TARGET" = 0 ]; then
    seeds=$(find "$ROOT/test/fuzz/corpus/$t" -type f | wc -l)
    if "$exe" -runs=0 -timeout=10 -rss_limit_mb=2048 -artifact_prefix="$BUILD/artifacts/$t/" \
        "$ROOT/test/fuzz/corpus/$t" > "$log" 2>&1; then
      echo "fuzz.sh: $t: ok, replayed $seeds seed(s) and ${#regressions[@]} regression input(s)"
    else
      echo "fuzz.sh: $t: FAILED replaying the seeds (log $log):"
      grep -E "ERROR|invariant|runtime error|SUMMARY|Test unit written" "$log" | head -n 20
      failed+=("$t")
    fi
    continue
  fi
  # 2b. Fuzzing: new units go to the first (work) corpus folder, the committed seeds are read only.
  if "$exe" -max_total_time="$SECONDS_PER_TARGET" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$BUILD/artifacts/$t/" "$BUILD/corpus/$t" "$ROOT/test/fuzz/corpus/$t" > "$log" 2>&1; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -n 1)
    echo "fuzz.sh: $t: ok, ${runs:-?} runs in ${SECONDS_PER_TARGET}s (${rate:-?}/s), ${cov:-cov: ?}, ${#regressions[@]} regression input(s)"
  else
    echo "fuzz.sh: $t: FAILED (log $log):"; grep -E "ERROR|invariant|runtime error|SUMMARY|Test unit written" "$log" | head -n 20
    failed+=("$t")
  fi
done
if [ ${#failed[@]} -ne 0 ]; then
  echo "fuzz.sh: FAILED: ${failed[*]}" >&2
  exit 1
fi
echo "fuzz.sh: all targets passed"
