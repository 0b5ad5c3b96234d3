#!/usr/bin/env bash
# Rewrites docs/parameters.md from the code: every parameter, topic and service each plugin declares
# (costmap_tool --describe-params --markdown). Run it after changing a parse function; test_ros
# (ParamReference.TheCommittedReferenceIsWhatTheCodeDeclares) fails until it is run.
# Usage: scripts/dev/make_reference.sh [BUILD_DIR]   (default: the one scripts/test.sh builds)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="${1:-}"
if [ -z "$build" ]; then
  # scripts/test.sh's colcon build keeps its devel space here.
  build="$(ls -d "$root"/build/costmap_layers 2>/dev/null || true)"
fi
if [ -z "$build" ] || [ ! -f "$build/devel/setup.bash" ]; then
  echo "make_reference: no build found; give the catkin build folder (the one with devel/setup.bash)" >&2
  exit 1
fi
set +u
# shellcheck disable=SC1091
source "$build/devel/setup.bash"
set -u
tool="$build/devel/lib/costmap_layers/costmap_tool"
"$tool" --describe-params --markdown > "$root/docs/parameters.md.new"
mv "$root/docs/parameters.md.new" "$root/docs/parameters.md"
echo "make_reference: wrote docs/parameters.md"
