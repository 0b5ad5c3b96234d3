# Sourced by the scripts: where the navigation underlay (costmap_2d, move_base, ...) lives, and how to
# put it into the environment. scripts/build_navigation.sh builds it there.

navigation_underlay_dir() {
  echo "${NAV_UNDERLAY:-${XDG_CACHE_HOME:-$HOME/.cache}/costmap_layers/navigation-underlay}"
}

# Sources the underlay when it is built; returns 1 when there is none.
source_navigation_underlay() {
  local dir
  dir="$(navigation_underlay_dir)"
  [ -f "$dir/install/setup.bash" ] || return 1
  set +u
  # shellcheck disable=SC1091
  source "$dir/install/setup.bash"
  set -u
}

# Prints the install prefix holding ROS package $1 (e.g. costmap_2d), or nothing (status 1) when this
# environment has none.
ros_package_prefix() {
  local p
  for p in ${CMAKE_PREFIX_PATH//:/ }; do
    if [ -f "$p/share/$1/package.xml" ]; then
      echo "$p"
      return 0
    fi
  done
  return 1
}
