#!/usr/bin/env bash
# Builds the ROS 1 navigation stack (costmap_2d, move_base, navfn, DWA, ...) into an underlay workspace
# outside this package's own build, for the move_base integration (the costmap_2d plugins of this
# package and their tests). Debian 12 packages none of it; on Ubuntu with ROS Noetic install
# ros-noetic-move-base etc. instead and skip this script.
#
#   scripts/build_navigation.sh SOURCE_TARBALL_OR_DIR [UNDERLAY_DIR]
#
# SOURCE: the navigation stack's sources, as a folder or a .tar.gz: a clone of ros-planning/navigation
# (git clone -b noetic-devel https://github.com/ros-planning/navigation.git), its release tarball, or
# a trimmed copy holding only the packages below. Only what move_base and this package's plugins and
# tests need is built (NEEDED); the others of a whole checkout (amcl,
# map_server, fake_localization, ...) are skipped, and said, since nothing here uses them and they
# need Debian packages of their own. UNDERLAY_DIR defaults to $NAV_UNDERLAY, else
# ${XDG_CACHE_HOME:-~/.cache}/costmap_layers/navigation-underlay, which scripts/test.sh and
# scripts/demo.sh also look in. A second run with the same sources does nothing. The sources are only
# read: nothing is copied into this repository.
set -euo pipefail
export PATH=/usr/bin:/bin:$PATH
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# shellcheck source=scripts/lib/navigation_underlay.sh
source "$ROOT/scripts/lib/navigation_underlay.sh"

if [ $# -lt 1 ] || [ $# -gt 2 ]; then
  echo "usage: $0 SOURCE_TARBALL_OR_DIR [UNDERLAY_DIR]" >&2
  exit 2
fi
src="$1"
dest="${2:-$(navigation_underlay_dir)}"
if [ ! -e "$src" ]; then
  echo "build_navigation: no such file or folder: $src" >&2
  exit 2
fi

# The Debian packages the navigation stack needs beyond this package's own set.
NAV_PKGS=(
  ros-cmake-modules libangles-dev libtf2-geometry-msgs-dev libtf2-sensor-msgs-dev
  libvisualization-msgs-dev ros-visualization-msgs libactionlib-dev python3-actionlib
  libmove-base-msgs-dev ros-move-base-msgs python3-move-base-msgs liblaser-geometry-dev librosbag-dev
  libmap-msgs-dev ros-map-msgs python3-map-msgs
)
bash "$ROOT/scripts/lib/install_deps.sh"
missing=()
for p in "${NAV_PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# One stamp per source: the tarball's checksum, or the folder's listing with sizes and times.
if [ -f "$src" ]; then
  stamp="$(sha256sum "$src" | cut -d' ' -f1)"
else
  stamp="$(find "$src" -type f -printf '%P %s %T@\n' | sort | sha256sum | cut -d' ' -f1)"
fi
if [ -f "$dest/install/setup.bash" ] && [ "$(cat "$dest/source.sha256" 2>/dev/null)" = "$stamp" ]; then
  echo "build_navigation: $dest is up to date with $src"
  exit 0
fi

rm -rf "$dest"
mkdir -p "$dest/src"
if [ -f "$src" ]; then
  tar -xzf "$src" -C "$dest/src"
else
  cp -a "$src/." "$dest/src/"
fi
# What the bridge, its tests and a move_base with navfn / DWA / global_planner and the recoveries need:
# these packages exactly (their other dependencies are Debian packages). Selected by name, since a
# selection "up to move_base" also takes the test dependencies (costmap_2d's on map_server, which needs
# Bullet, and amcl's chain).
NEEDED=(costmap_2d voxel_grid nav_core navfn global_planner base_local_planner dwa_local_planner
  clear_costmap_recovery rotate_recovery move_base)
for p in "${NEEDED[@]}"; do
  if [ -z "$(find "$dest/src" -name package.xml -path "*/$p/package.xml" -print -quit)" ]; then
    echo "build_navigation: $src has no $p package" >&2
    exit 1
  fi
done
# The other packages of a whole checkout are hidden from colcon in this copy of the sources (a
# selection by name is not enough: colcon still wants costmap_2d's test dependency map_server built).
skipped=()
while IFS= read -r xml; do
  name="$(sed -n 's:.*<name>\(.*\)</name>.*:\1:p' "$xml" | head -n 1)"
  case " ${NEEDED[*]} " in
    *" $name "*) ;;
    *) touch "$(dirname "$xml")/COLCON_IGNORE"; skipped+=("$name") ;;
  esac
done < <(find "$dest/src" -name package.xml | sort)
if [ ${#skipped[@]} -gt 0 ]; then
  echo "build_navigation: skipped ${skipped[*]} (not needed by move_base or this package's plugins and" \
    "tests; map_server would need Bullet)"
fi
start=$(date +%s)
(
  cd "$dest"
  colcon --log-base "$dest/log" build --base-paths "$dest/src" --build-base "$dest/build" \
    --install-base "$dest/install" --event-handlers console_cohesion- \
    --cmake-args -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=OFF
)
echo "$stamp" > "$dest/source.sha256"
echo "build_navigation: built $(find "$dest/install" -name package.xml -path '*/share/*' | wc -l)" \
  "packages into $dest in $(($(date +%s) - start)) s"
