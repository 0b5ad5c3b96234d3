#!/usr/bin/env bash
# launch-prefix of move_base in move_base.test: runs the command with its standard error copied, as it
# is written, to <this run's log directory>/move_base-stderr.log (roslaunch-logs names the directory;
# the test finds it from /run_id), and still to the console. A subscriber to /rosout sees only the
# lines written after it connects, so a check of what move_base says at start-up reads this file.
# (LD_PRELOAD, set by scripts/dev/sanitize_package.sh for move_base, is kept away from the helpers.)
set -euo pipefail
dir=$(env -u LD_PRELOAD roslaunch-logs)
log="$dir/move_base-stderr.log"
: > "$log"
exec "$@" 2> >(env -u LD_PRELOAD tee -a "$log" >&2)
