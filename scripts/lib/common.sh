# Sourced by the scripts: puts Debian's python first (a pyenv python breaks catkin), names the
# workspace folders, and builds the package when asked.
export PATH=/usr/bin:/bin:$PATH
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
export ROOT
BUILD_TYPE="${BUILD_TYPE:-Release}"

# shellcheck source=scripts/lib/navigation_underlay.sh
source "$ROOT/scripts/lib/navigation_underlay.sh"

# catkin snapshots the environment (CMAKE_PREFIX_PATH, ROS_PACKAGE_PATH: which workspaces its setup
# files and test runs chain to) and CMake caches where it found costmap_2d and move_base, both at
# configure time, and colcon re-configures only when CMakeLists.txt changes. So when the navigation
# underlay appears or disappears between two builds of one build folder, the old snapshot stays: the
# move_base tests are then registered without move_base in the test environment ("cannot launch node
# of type [move_base/move_base]"), or left out although the underlay is there. A stamp in the build
# folder holds the underlay the folder was configured with ("none" without one); these two functions
# make colcon configure afresh (a new CMake cache) only when it changed.
#   navigation_underlay_configure_args BUILD_BASE   prints the colcon arguments for this build
#   navigation_underlay_stamp BUILD_BASE            records the underlay after a successful build
navigation_underlay_now() {
  if [ -f "$(navigation_underlay_dir)/install/setup.bash" ]; then navigation_underlay_dir; else echo none; fi
}

navigation_underlay_configure_args() {
  local build="$1/costmap_layers" now before
  now="$(navigation_underlay_now)"
  [ -f "$build/CMakeCache.txt" ] || return 0  # the first configure sees the environment as it is
  before="$(cat "$build/.navigation_underlay" 2>/dev/null || echo unknown)"
  # A configure outside these scripts (a plain `cmake .` or `colcon build` in another shell) rewrites
  # the snapshot without the stamp: trust what the devel space chains to as well.
  if [ -f "$build/devel/_setup_util.py" ]; then
    if grep -qF "$(navigation_underlay_dir)/" "$build/devel/_setup_util.py"; then
      [ "$now" != none ] || before="$(navigation_underlay_dir) (the devel space chains to it)"
    else
      [ "$now" = none ] || before="none (the devel space does not chain to it)"
    fi
  fi
  if [ "$before" != "$now" ]; then
    echo "build: the navigation underlay changed since $build was configured (was: $before, now: $now):" \
      "configuring afresh" >&2
    echo "--cmake-clean-cache"
  fi
}

navigation_underlay_stamp() {
  navigation_underlay_now > "$1/costmap_layers/.navigation_underlay"
}

build_package() {
  bash "$ROOT/scripts/lib/install_deps.sh"
  # costmap_2d and move_base for the move_base plugins and their tests: from the ROS distribution, or
  # from the navigation underlay scripts/build_navigation.sh builds (sourced when it is there).
  if source_navigation_underlay; then
    echo "build: with the navigation underlay in $(navigation_underlay_dir)"
  fi
  cd "$ROOT"
  local fresh
  fresh="$(navigation_underlay_configure_args "$ROOT/build")"
  # shellcheck disable=SC2086 # fresh is empty or one word
  colcon --log-base "$ROOT/log" build --base-paths "$ROOT" --build-base "$ROOT/build" --install-base "$ROOT/install" \
    --event-handlers console_cohesion+ $fresh \
    --cmake-args -DCMAKE_BUILD_TYPE="$BUILD_TYPE" "$@"
  navigation_underlay_stamp "$ROOT/build"
}

source_install() {
  # setup.bash reads unset variables: relax -u while sourcing it.
  set +u
  # shellcheck disable=SC1091
  source "$ROOT/install/setup.bash"
  set -u
}
