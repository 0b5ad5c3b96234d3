// The ranges every number from outside (map files, parameters, messages, command lines) must fall in,
// one constant per quantity, so that every quantity derived from them stays representable: cell
// counts and indices in int, world extents and 1 / resolution finite, durations within ros::Duration
// and within uint64 nanoseconds, and float32 casts for messages finite and > 0. Each value is checked
// where it is read, with an error naming the field and the value; nothing is clamped silently.
#pragma once

#include <cstddef>
#include <cstdint>

namespace costmap_layers
{
namespace limits
{
/// Cells of any one grid: a map or mask file's image, an incoming OccupancyGrid, the costmap itself.
/// 400 million cells (20000 x 20000) is 400 MB of int8 occupancy and 400 MB of costs; it keeps every
/// cell index below INT_MAX, so row * width + column never overflows an int.
constexpr uint64_t kMaxGridCells = 400'000'000ull;

/// [m/cell] Resolution of maps, masks and the costmap. 0.1 mm to 1 km per cell: finer is no sensor's
/// scale and makes distances of a few km exceed int cell counts (1e7 m / 1e-4 = 1e11); coarser
/// is no robot's scale. Both ends are normal float32 numbers (nav_msgs/MapMetaData::resolution), so
/// the cast for a message gives neither 0 nor inf.
constexpr double kMinResolution = 1e-4;
constexpr double kMaxResolution = 1e3;

/// [m] |x| and |y| of any origin or pose read from outside: 10000 km, more than any map needs. With a
/// grid of at most kMaxGridCells cells of at most kMaxResolution, every world coordinate involved
/// stays far below 1e300, so sums, differences and squares stay finite.
constexpr double kMaxCoordinate = 1e7;

/// [rad] |yaw| of an origin or pose. Any angle is one of [-pi, pi] plus turns; a thousand radians
/// allows any sloppy sum of turns while sin/cos of it still keep 13 significant digits.
constexpr double kMaxYaw = 1e3;

/// [m] Lengths of the robot and its surroundings: robot_radius, footprint vertices and padding,
/// inflation_radius, sensor ranges, reset_distance. At kMinResolution this is 1e8 cells, below
/// INT_MAX, and its square (1e16) fits int64 and double exactly enough.
constexpr double kMaxDistance = 1e4;

/// [s] Durations: tolerances, timeouts, persistence. One hour; 3.6e12 ns fits uint64 and
/// ros::Duration (int32 seconds) with room to spare.
constexpr double kMaxDuration = 3600.0;

/// [Hz] Frequencies of loops: 0 means "off" where a parameter allows it; otherwise at least
/// kMinFrequency (a period of 1000 s, within kMaxDuration's ros::Duration range) and at most
/// kMaxFrequency (a period of 1 ms).
constexpr double kMinFrequency = 1e-3;
constexpr double kMaxFrequency = 1e3;

/// Zones drawn as shapes (zone_server): at most this many shapes in one layout and vertices in one
/// polygon, well above what a person draws by hand (a few shapes of a few dozen vertices).
constexpr std::size_t kMaxZoneShapes = 1000;
constexpr std::size_t kMaxZoneVertices = 1000;
/// The self-intersection check is quadratic in a polygon's vertices (n^2 / 2 segment pairs, 7 ns each
/// here): the sum of n^2 over a layout's polygons is bounded, so that checking a whole layout (a load,
/// a reload) takes at most about 0.1 s. An edit checks only the shape it changes. 2e7 is 20 polygons
/// of 1000 vertices, or 1000 of 141.
constexpr double kMaxZoneVertexPairs = 2e7;
/// Zones: the most cell visits drawing one layout may take, summed over its shapes: each shape's
/// bounding box in cells, plus its rows times its vertices for a polygon (a row's crossings are
/// sought among all its edges). kMaxGridCells alone does not bound it: 1000 circles each covering a
/// 4e8-cell grid, or one 1000-vertex polygon over a grid of 1e8 rows, would take minutes and hold
/// zone_server's only thread. 1e9 visits take one to a few seconds.
constexpr double kMaxZoneRasterWork = 1e9;
/// zone_server: the most handles (interactive markers) it offers in RViz, whole shapes in file order.
/// Each costs about a kilobyte in the marker server and its latched update_full; kMaxZoneShapes shapes
/// of kMaxZoneVertices vertices would be a million handles (gigabytes), rebuilt on every edit.
constexpr std::size_t kMaxZoneHandles = 10000;
/// Poses of one path: 200 000 poses is a 5 km plan at navfn's 2.5 cm spacing. Bigger paths are
/// refused (each cycle may walk the whole path to find the robot on it).
constexpr std::size_t kMaxPathPoses = 200'000;
/// [m/s] |speed| an odometry message may report: no ground robot is faster; beyond it the braking
/// distance v^2 / (2 a) loses meaning.
constexpr double kMaxSpeed = 100.0;
/// Plugins in one costmap (layers and filters together). Real configurations have 2 to 10; a list of
/// hundreds is a mistake (a YAML alias repeated, a generated file), and each layer may own a grid the
/// size of the map: such a list is refused before any plugin is made.
constexpr std::size_t kMaxPlugins = 64;
}  // namespace limits
}  // namespace costmap_layers
