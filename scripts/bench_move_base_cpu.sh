#!/usr/bin/env bash
# What the robot's CPU feels (issue 38): move_base (navfn + DWA, no goal) in a world of its own, with
# costmap_2d's own layers (A) and with this package's layers through the bridge (B), the same
# parameters (bench/move_base/move_base_cpu.yaml), run in turns A, B, C, A, B, C, ...; C is no
# move_base but one costmap_node on the same inputs: the local costmap's parameters with the global
# one's static layer under its sensor layers (static + obstacle + voxel + inflation, rolling, 10 Hz).
# Prints the CPU seconds (utime + stime from /proc/<pid>/stat) over the same window of each run, after
# a warm-up, and B / A and C / A per round with the spread. Then A and B at once for a while: how many of the lethal
# cells of the two local costmaps agree, with the world moving and paused.
#
# The world (bench/move_base/cpu_world.cpp): Willow Garage's map (test/data/maps/willow-full-0.1.yaml)
# latched on /map by mask_server; a robot driving a 1.5 m circle at 0.3 m/s (tf map -> odom ->
# base_link); a 720-beam LaserScan (10 m) at 40 Hz and an organised 160x125 PointCloud2 at 15 Hz
# seeing the walls, three boxes not in the map and one moving box. Global costmap: static + inflation
# (0.55 m, factor 3), 5 Hz. Local costmap: rolling 6 x 6 m at 0.05 m, obstacle layer on the scan,
# voxel layer on the cloud, inflation (0.55 m, factor 3), 10 Hz, published at 5 Hz.
#
# Builds nothing: it runs the package's build (install/ at the package root, as scripts/dev/build.sh
# makes it, or the setup file in COSTMAP_LAYERS_SETUP, e.g. a catkin devel space) and the navigation
# underlay scripts/build_navigation.sh made. Its own ROS master on a free port.
#   BENCH_PAIRS=3            rounds of A, B (and C)
#   BENCH_SIDES="A B C"      what each round runs, in this order; N: move_base with costmap_2d's static
#                            and inflation layers and no sensor layer (move_base's own share); R: no
#                            move_base, a process that only receives the scan and the cloud
#                            (move_base_receive_only: what any sensor layer pays before it reads a point);
#                            I: that process subscribed to nothing (its own idle cost)
#   BENCH_SECONDS=60         the measured window of each run [s]
#   BENCH_WARMUP=20          from move_base's start to the window [s]
#   BENCH_AGREE_SECONDS=40   both at once: this long with the world moving, then 15 s paused; 0 = skip
#   BENCH_PERF=1             perf record -g of every B run's window (perf costs CPU: not for the figures)
#   BENCH_OUTPUT=dir         logs (default log/bench_move_base_cpu at the package root)
set -euo pipefail
source "$(dirname "$0")/lib/common.sh"
PAIRS="${BENCH_PAIRS:-3}"
SIDES="${BENCH_SIDES:-A B C}"
WINDOW="${BENCH_SECONDS:-60}"
WARMUP="${BENCH_WARMUP:-20}"
AGREE="${BENCH_AGREE_SECONDS:-40}"
OUT="${BENCH_OUTPUT:-$ROOT/log/bench_move_base_cpu}"

die() {
  echo "bench_move_base_cpu: $*" >&2
  exit 1
}
SETUP="${COSTMAP_LAYERS_SETUP:-$ROOT/install/setup.bash}"
[ -f "$SETUP" ] || die "no build at $SETUP: run scripts/dev/build.sh first (or set COSTMAP_LAYERS_SETUP)"
set +u
# shellcheck disable=SC1090
source "$SETUP"
set -u
# After the package's setup: a catkin devel space's setup does not chain to the (colcon) underlay.
source_navigation_underlay || die "no navigation underlay in $(navigation_underlay_dir): run scripts/build_navigation.sh"
find_exe() {  # find_exe PACKAGE NAME
  catkin_find --first-only --libexec "$1" "$2" 2> /dev/null | grep . || die "$1's $2 not found (is the build complete?)"
}
MOVE_BASE="$(find_exe move_base move_base)"
WORLD="$(find_exe costmap_layers move_base_cpu_world)"
MASK_SERVER="$(find_exe costmap_layers mask_server)"
COSTMAP_NODE="$(find_exe costmap_layers costmap_node)"
RECEIVE_ONLY="$(find_exe costmap_layers move_base_receive_only)"
MONITOR="$ROOT/bench/move_base/cpu_monitor.py"
PARAMS="$ROOT/bench/move_base/move_base_cpu.yaml"
TICKS="$(getconf CLK_TCK)"

mkdir -p "$OUT"
rm -f "$OUT"/*.log
export ROS_HOME="$OUT/ros_home" ROS_LOG_DIR="$OUT/ros_home/log"
# Each log line written when it is logged (the missed-rate warnings below are counted from the logs).
export ROSCONSOLE_STDOUT_LINE_BUFFERED=1
PORT=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI="http://127.0.0.1:$PORT"

# Every process this script starts, stopped on exit (by pid).
PIDS=()
stop_all() {
  local p
  for p in "${PIDS[@]}"; do kill "$p" 2> /dev/null || true; done
  for p in "${PIDS[@]}"; do wait "$p" 2> /dev/null || true; done
}
trap stop_all EXIT
start() {  # start LOG COMMAND...: in the background; its pid in STARTED
  local log=$1
  shift
  "$@" > "$log" 2>&1 &
  STARTED=$!
  PIDS+=("$STARTED")
}
stop() {  # stop PID: SIGTERM, SIGKILL after 10 s
  local p=$1
  kill "$p" 2> /dev/null || return 0
  for _ in $(seq 100); do
    kill -0 "$p" 2> /dev/null || break
    sleep 0.1
  done
  kill -9 "$p" 2> /dev/null || true
  wait "$p" 2> /dev/null || true
}
cpu_ticks() { # utime + stime of the PIDs, summed (fields 14 and 15 of /proc/PID/stat, after the command's parentheses)
  local p
  for p in "$@"; do cat "/proc/$p/stat"; done | awk '{ sub(/^.*\) /, ""); n += $12 + $13 } END { print n }'
}
user_ticks() { # utime alone: this VM's kernel time swings from run to run (hypervisor exits), user time less
  local p
  for p in "$@"; do cat "/proc/$p/stat"; done | awk '{ sub(/^.*\) /, ""); n += $12 } END { print n }'
}
switches() { # context switches (voluntary and not) of every thread of the PIDs, summed
  local p
  for p in "$@"; do cat /proc/"$p"/task/*/status 2> /dev/null; done | awk '/ctxt_switches:/ { n += $2 } END { print n + 0 }'
}
rss_mb() { local p; for p in "$@"; do cat "/proc/$p/status"; done | awk '/^VmRSS:/ { n += $2 } END { printf "%.0f", n / 1024 }'; }
load1() { cut -d' ' -f1 /proc/loadavg; }
sleep_until() { # sleep_until EPOCH_SECONDS (fractional)
  local d
  d=$(python3 -c "import sys, time; print(max(0.0, float(sys.argv[1]) - time.time()))" "$1")
  sleep "$d"
}

# The plugin lists: A costmap_2d's layers, B this package's through the bridge, C this package's in
# costmap_node; same names, so the same parameter namespaces.
plugins() { # plugins A|B|C: the YAML of both costmaps' plugin lists
  local p
  case "$1" in
    A) p="costmap_2d::" ;;
    B) p="costmap_layers::move_base::" ;;
    C) p="costmap_layers/" ;;
    N) p="costmap_2d::" ;;
  esac
  if [ "$1" = C ]; then # one costmap: the local one with the static layer under the sensor layers
    cat << EOF
local_costmap:
  plugins:
    - {name: static, type: "${p}StaticLayer"}
    - {name: obstacles, type: "${p}ObstacleLayer"}
    - {name: voxels, type: "${p}VoxelLayer"}
    - {name: inflation, type: "${p}InflationLayer"}
EOF
    return
  fi
  if [ "$1" = N ]; then # move_base's own share: no sensor layer
    cat << EOF
global_costmap:
  plugins:
    - {name: static, type: "${p}StaticLayer"}
    - {name: inflation, type: "${p}InflationLayer"}
local_costmap:
  plugins:
    - {name: inflation, type: "${p}InflationLayer"}
EOF
    return
  fi
  cat << EOF
global_costmap:
  plugins:
    - {name: static, type: "${p}StaticLayer"}
    - {name: inflation, type: "${p}InflationLayer"}
local_costmap:
  plugins:
    - {name: obstacles, type: "${p}ObstacleLayer"}
    - {name: voxels, type: "${p}VoxelLayer"}
    - {name: inflation, type: "${p}InflationLayer"}
EOF
}
plugins A > "$OUT/plugins_A.yaml"
plugins B > "$OUT/plugins_B.yaml"
plugins C > "$OUT/plugins_C.yaml"
plugins N > "$OUT/plugins_N.yaml"
load_params() { # load_params NAMESPACE A|B|C
  rosparam delete "/$1" > /dev/null 2>&1 || true
  rosparam load "$PARAMS" "/$1"
  rosparam load "$OUT/plugins_$2.yaml" "/$1"
}

start "$OUT/rosmaster.log" rosmaster --core -p "$PORT"
for _ in $(seq 100); do
  python3 -c 'import rosgraph, sys; sys.exit(0 if rosgraph.is_master_online() else 1)' 2> /dev/null && break
  sleep 0.1
done
start "$OUT/map_server.log" "$MASK_SERVER" __name:=map_server _yaml_filename:="$ROOT/test/data/maps/willow-full-0.1.yaml" _topic:=/map
start "$OUT/world.log" "$WORLD" __name:=cpu_world
WORLD_PID=$STARTED
for _ in $(seq 300); do
  grep -q "cpu_world: map" "$OUT/world.log" && break
  sleep 0.1
done
grep -q "cpu_world: map" "$OUT/world.log" || die "the world did not start: $(tail -n 5 "$OUT/world.log")"
echo "bench_move_base_cpu: $PAIRS pairs, warm-up ${WARMUP} s, window ${WINDOW} s; $(nproc) cores;" \
  "move_base from $MOVE_BASE; costmap_layers from $SETUP; logs in $OUT"

RESULTS="$OUT/results.txt"
: > "$RESULTS"
run() { # run PAIR A|B|C|N: one run (move_base, or C's costmap_node), one result line
  local pair=$1 side=$2 log pids t0 t_start t_end c0 c1 u0 u1 w0 w1 cpu user world rss msgs cycles missed_local missed_global
  local perf_pid="" what ns s0 s1
  log="$OUT/move_base_${pair}_${side}.log"
  t0=$(date +%s.%N)
  if [ "$side" = C ]; then
    what="costmap_node"
    ns=/c
    load_params c C
    # The global costmap's static layer parameters for the static layer of this one.
    rosparam set /c/local_costmap/static "$(rosparam get /c/global_costmap/static)"
    log="$OUT/costmap_node_${pair}.log"
    start "$log" "$COSTMAP_NODE" __ns:=/c __name:=local_costmap
    pids=("$STARTED")
  elif [ "$side" = R ] || [ "$side" = I ]; then
    what="receive_only"
    ns=/receive_only
    log="$OUT/receive_only_${pair}_${side}.log"
    start "$log" "$RECEIVE_ONLY" __name:=receive_only _subscribe:="$([ "$side" = R ] && echo true || echo false)"
    pids=("$STARTED")
  else
    what="move_base"
    ns=/move_base
    load_params move_base "$side"
    start "$log" "$MOVE_BASE" __name:=move_base
    pids=("$STARTED")
  fi
  t_start=$(python3 -c "print($t0 + $WARMUP)")
  t_end=$(python3 -c "print($t_start + $WINDOW)")
  start "$OUT/monitor_${pair}_${side}.log" python3 "$MONITOR" __name:=cpu_monitor _mode:=count _ns:="$ns" \
    _start:="$t_start" _end:="$t_end"
  local mon=$STARTED
  sleep_until "$t_start"
  local p
  for p in "${pids[@]}"; do
    kill -0 "$p" 2> /dev/null || die "$what ($side) died: $(tail -n 20 "$log")"
  done
  c0=$(cpu_ticks "${pids[@]}")
  u0=$(user_ticks "${pids[@]}")
  s0=$(switches "${pids[@]}")
  w0=$(cpu_ticks "$WORLD_PID")
  local l0
  l0=$(load1)
  if [ "${BENCH_PERF:-0}" = 1 ] && [ "$side" != A ]; then
    perf record -F 499 -g -p "$(IFS=,; echo "${pids[*]}")" -o "$OUT/perf_${pair}_${side}.data" -- sleep "$WINDOW" \
      > "$OUT/perf_${pair}_${side}.log" 2>&1 &
    perf_pid=$!
  fi
  sleep_until "$t_end"
  c1=$(cpu_ticks "${pids[@]}")
  u1=$(user_ticks "${pids[@]}")
  s1=$(switches "${pids[@]}")
  w1=$(cpu_ticks "$WORLD_PID")
  rss=$(rss_mb "${pids[@]}")
  [ -z "$perf_pid" ] || wait "$perf_pid" || true
  wait "$mon" || true
  for p in "${pids[@]}"; do stop "$p"; done
  cpu=$(python3 -c "print('%.2f' % (($c1 - $c0) / $TICKS))")
  world=$(python3 -c "print('%.2f' % (($w1 - $w0) / $TICKS))")
  user=$(python3 -c "print('%.2f' % (($u1 - $u0) / $TICKS))")
  msgs=$(sed -n 's/^monitor: .*messages in the window: \([0-9]*\) .*/\1/p' "$OUT/monitor_${pair}_${side}.log")
  # The local costmap's update cycles in the window (from its diagnostics, costmap_node only) and the
  # cycles of each costmap that took longer than their period (costmap_2d warns of every one, naming the
  # rate; costmap_node's warning is throttled, its diagnostics give the longest cycle instead).
  cycles=$(sed -n 's/^monitor: .*local costmap update cycles in the window: \([0-9]*\).*/\1/p' "$OUT/monitor_${pair}_${side}.log")
  if [ "$side" = R ] || [ "$side" = I ]; then
    missed_local="-"
    missed_global="-"
  elif [ "$side" = C ]; then
    missed_local=$(sed -n 's/^monitor: .*longest cycle: \([0-9.]*\) s.*/\1 s longest/p' "$OUT/monitor_${pair}_${side}.log")
    missed_global="-"
  else
    missed_local=$(awk -v a="$t_start" -v b="$t_end" -F'[][]' \
      '/missed its desired rate of 10.0000Hz/ { t = $4 + 0; if (t >= a && t < b) n++ } END { print n + 0 }' "$log")
    missed_global=$(awk -v a="$t_start" -v b="$t_end" -F'[][]' \
      '/missed its desired rate of 5.0000Hz/ { t = $4 + 0; if (t >= a && t < b) n++ } END { print n + 0 }' "$log")
  fi
  echo "$pair $side $cpu $world $user" >> "$RESULTS"
  printf 'round %d %s: %-16s %6.2f s CPU (user %.2f s) in %d s (%4.1f %% of a core), RSS %s MB; local costmap published %s times%s;' \
    "$pair" "$side" "$what" "$cpu" "$user" "$WINDOW" "$(python3 -c "print(100 * $cpu / $WINDOW)")" "$rss" "${msgs:-?}" \
    "${cycles:+, $cycles update cycles}"
  printf ' cycles over their period: local %s, global %s; %d context switches/s; world %.2f s CPU; load %s -> %s\n' \
    "${missed_local:-?}" "$missed_global" "$(((s1 - s0) / WINDOW))" "$world" "$l0" "$(load1)"
}

for pair in $(seq "$PAIRS"); do
  for side in $SIDES; do run "$pair" "$side"; done
done

python3 - "$RESULTS" "$WINDOW" << 'PY'
import sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
cpu = {}
world = {}  # the world process's CPU in the same window: the same work every time, so a gauge of the host
user = {}  # user time alone
for p, s, c, w, u in rows:
    cpu.setdefault(s, {})[int(p)] = float(c)
    world.setdefault(s, {})[int(p)] = float(w)
    user.setdefault(s, {})[int(p)] = float(u)
def span(v):
    return "mean %.2f, min %.2f, max %.2f" % (sum(v) / len(v), min(v), max(v)) if v else "none"
names = {"A": "A (move_base, costmap_2d's layers):    ", "B": "B (move_base, costmap_layers bridged):",
         "C": "C (costmap_node, costmap_layers):      ", "N": "N (move_base, no sensor layer):        ",
         "R": "R (a process receiving scan + cloud):  ", "I": "I (that process, subscribed to nothing):"}
for s in sorted(cpu):
    print("%s CPU s per %s s: %s (%s)" % (names.get(s, s), sys.argv[2], span(list(cpu[s].values())),
                                          " ".join("%.2f" % cpu[s][p] for p in sorted(cpu[s]))))
for s in ("B", "C", "N", "R", "I"):
    if s not in cpu or "A" not in cpu:
        continue
    rounds = sorted(set(cpu["A"]) & set(cpu[s]))
    ratios = [cpu[s][p] / cpu["A"][p] for p in rounds]
    if ratios:
        print("%s / A per round: %s; %s" % (s, " ".join("%.3f" % r for r in ratios), span(ratios)))
    # The same with each side's CPU divided by the world's in its own window: the world does the same
    # work in every run, so when the host slows down (steal, other guests) its CPU grows with the side's.
    # A gauge, not a correction: printed beside the plain ratios, never instead of them.
    scaled = [cpu[s][p] / world[s][p] / (cpu["A"][p] / world["A"][p]) for p in rounds
              if world[s][p] > 0 and world["A"][p] > 0 and cpu["A"][p] > 0]
    if scaled:
        print("%s / A per round, each over the world's CPU in its window: %s; %s" % (
            s, " ".join("%.3f" % r for r in scaled), span(scaled)))
    # User time alone: on this kind of VM the kernel's share (IRQ enabling through the hypervisor, in
    # every wake-up and socket call) swings by 2x from run to run whatever the process does.
    users = [user[s][p] / user["A"][p] for p in rounds if user["A"][p] > 0]
    if users:
        print("%s / A per round, user time only: %s; %s" % (s, " ".join("%.3f" % r for r in users), span(users)))
# The least any move_base with sensor layers can take: its own share (N) and the receiving of the
# sensor data (R less the receiving process's idle cost I), whatever its layers do with the data.
if all(k in cpu for k in ("A", "N", "R")):
    rounds = sorted(set(cpu["A"]) & set(cpu["N"]) & set(cpu["R"]))
    floor = [(cpu["N"][p] + cpu["R"][p] - cpu.get("I", {}).get(p, 0.0)) / cpu["A"][p] for p in rounds]
    if floor:
        print("(N + R%s) / A per round, the floor of B / A: %s; %s" % (
            " - I" if "I" in cpu else "", " ".join("%.3f" % r for r in floor), span(floor)))
PY

if [ "$AGREE" -gt 0 ]; then
  # Both at once on the same messages: the lethal cells of their local costmaps.
  load_params move_base_a A
  load_params move_base_b B
  start "$OUT/move_base_a.log" "$MOVE_BASE" __name:=move_base_a
  pa=$STARTED
  start "$OUT/move_base_b.log" "$MOVE_BASE" __name:=move_base_b
  pb=$STARTED
  t_ready=$(python3 -c "import time; print(time.time() + $WARMUP)")
  t_end=$(python3 -c "print($t_ready + $AGREE + 15)")
  start "$OUT/monitor_agree.log" python3 "$MONITOR" __name:=cpu_monitor _mode:=agree _a:=/move_base_a _b:=/move_base_b \
    _start:="$t_ready" _end:="$t_end"
  mon=$STARTED
  sleep_until "$(python3 -c "print($t_ready + $AGREE)")"
  rosparam set /cpu_world/paused true
  wait "$mon" || true
  rosparam set /cpu_world/paused false
  stop "$pa"
  stop "$pb"
  echo "moving world: from ${WARMUP} s after the start for ${AGREE} s; paused: 12 s after 3 s of settling"
  grep '^monitor:' "$OUT/monitor_agree.log" || echo "bench_move_base_cpu: the agreement monitor printed nothing"
fi
