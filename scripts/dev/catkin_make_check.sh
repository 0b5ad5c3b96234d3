#!/usr/bin/env bash
# The package built as a ROS 1 user builds it: cloned into the src folder of a fresh catkin workspace
# and built with catkin_make (the README's "Build it in your catkin workspace"), then a smoke test from
# that workspace's devel space: pluginlib finds every plugin (costmap_tool --describe-params creates
# each one).
# Tests are not built here (scripts/test.sh builds and runs them with colcon).
# Usage: scripts/dev/catkin_make_check.sh [WORKSPACE]   (default: a temporary folder, removed after)
set -euo pipefail
# A user's shell: none of the caller's ROS environment (scripts/test.sh has its colcon install and maybe
# the navigation underlay sourced), so that the workspace builds against Debian's ROS alone.
if [ -z "${CATKIN_MAKE_CHECK_CLEAN:-}" ]; then
  exec env -i CATKIN_MAKE_CHECK_CLEAN=1 HOME="$HOME" PATH=/usr/bin:/bin LANG=C.UTF-8 bash "$0" "$@"
fi
root="$(cd "$(dirname "$0")/../.." && pwd)"
ws="${1:-}"
cleanup=""
if [ -z "$ws" ]; then
  ws="$(mktemp -d)"
  cleanup="$ws"
fi
trap '[ -z "$cleanup" ] || rm -rf "$cleanup"' EXIT
mkdir -p "$ws/src"
# The committed files and the working tree's changes to them, as a clone would hold them.
(cd "$root" && git ls-files -z --cached --others --exclude-standard) |
  (cd "$root" && xargs -0 tar -cf - --no-recursion 2>/dev/null) | (mkdir -p "$ws/src/costmap_layers" && cd "$ws/src/costmap_layers" && tar -xf -)
start=$(date +%s)
cd "$ws"
set +u
# shellcheck disable=SC1091
source /usr/share/catkin/../../setup.bash 2>/dev/null || true
set -u
catkin_make -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=OFF -j2 > "$ws/catkin_make.log" 2>&1 || {
  echo "catkin_make_check: catkin_make failed, the last lines of its log:"
  tail -n 40 "$ws/catkin_make.log"
  exit 1
}
echo "catkin_make_check: catkin_make built the package in $(( $(date +%s) - start )) s"
set +u
# shellcheck disable=SC1091
source "$ws/devel/setup.bash"
set -u
found="$(rospack find costmap_layers)"
[ "$found" = "$ws/src/costmap_layers" ] || { echo "catkin_make_check: rospack finds costmap_layers in $found, not in the workspace"; exit 1; }
ref="$(rosrun costmap_layers costmap_tool --describe-params)"
for t in GradientLayer KeepoutFilter SpeedFilter LanesFilter StaticLayer InflationLayer ObstacleLayer VoxelLayer \
  RangeSensorLayer ZoneParameterFilter BinaryFilter; do
  grep -q "^costmap_layers/$t:" <<<"$ref" || { echo "catkin_make_check: pluginlib did not find costmap_layers/$t"; exit 1; }
done
echo "catkin_make_check: every plugin loads from the catkin_make devel space"
