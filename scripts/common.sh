# Sourced by the scripts: puts Debian's python first (a pyenv python breaks catkin), names the
# workspace folders, and builds the package when asked.
export PATH=/usr/bin:/bin:$PATH
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export ROOT
BUILD_TYPE="${BUILD_TYPE:-Release}"

# shellcheck source=scripts/navigation_underlay.sh
source "$ROOT/scripts/navigation_underlay.sh"

build_package() {
  bash "$ROOT/scripts/install_deps.sh"
  # costmap_2d and move_base for the move_base plugins and their tests: from the ROS distribution, or
  # from the navigation underlay scripts/build_navigation.sh builds (sourced when it is there).
  if source_navigation_underlay; then
    echo "build: with the navigation underlay in $(navigation_underlay_dir)"
  fi
  cd "$ROOT"
  colcon --log-base "$ROOT/log" build --base-paths "$ROOT" --build-base "$ROOT/build" --install-base "$ROOT/install" \
    --event-handlers console_cohesion+ \
    --cmake-args -DCMAKE_BUILD_TYPE="$BUILD_TYPE" "$@"
}

source_install() {
  # setup.bash reads unset variables: relax -u while sourcing it.
  set +u
  # shellcheck disable=SC1091
  source "$ROOT/install/setup.bash"
  set -u
}
