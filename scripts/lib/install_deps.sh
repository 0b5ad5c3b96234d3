#!/usr/bin/env bash
# Installs every Debian package the build, the demo and the tests need.
# Safe to re-run: apt-get skips what is already installed.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
PKGS=(
  build-essential cmake catkin ros-message-generation libroscpp-dev pluginlib-dev librostest-dev
  python3-rostest libgtest-dev libgmock-dev libstd-msgs-dev ros-std-msgs libgeometry-msgs-dev
  ros-geometry-msgs libnav-msgs-dev ros-nav-msgs python3-geometry-msgs python3-nav-msgs
  colcon python3-colcon-ros python3-colcon-test-result python3-colcon-output python3-colcon-bash
  python3-colcon-package-selection rosbash python3-rostopic python3-rosnode python3-roslaunch
  libeigen3-dev libtf2-ros-dev libmap-msgs-dev python3-map-msgs ros-map-msgs libyaml-cpp-dev
  libpng-dev libbenchmark-dev libstd-srvs-dev ros-std-srvs python3-std-srvs python3-rospy
  python3-tf2-ros libtf2-msgs-dev python3-tf2-msgs python3-yaml libsensor-msgs-dev ros-sensor-msgs python3-sensor-msgs
  libmessage-filters-dev libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  libdiagnostic-updater-dev libdiagnostic-msgs-dev ros-diagnostic-msgs python3-diagnostic-msgs
  libcli11-dev nlohmann-json3-dev libhwy-dev
  libinteractive-markers-dev python3-interactive-markers libvisualization-msgs-dev
  ros-visualization-msgs python3-visualization-msgs
  clang libclang-rt-14-dev
  # RViz, its Python bindings and a virtual X server: the demo's RViz view and its test (test/rostest/rviz)
  rviz python3-rviz xvfb
)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#PKGS[@]} packages present"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
