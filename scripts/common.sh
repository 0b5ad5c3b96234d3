# Sourced by the scripts: puts Debian's python first (a pyenv python breaks catkin), names the
# workspace folders, and builds the package when asked.
export PATH=/usr/bin:/bin:$PATH
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export ROOT
BUILD_TYPE="${BUILD_TYPE:-Release}"

build_package() {
  bash "$ROOT/scripts/install_deps.sh"
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
