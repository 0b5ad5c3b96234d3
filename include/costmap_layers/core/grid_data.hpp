// Plain data types the core receives from outside: an occupancy grid (map or filter mask) and
// speed limits. The ROS adapter converts messages into them; costmap_tool fills them from files.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace costmap_layers
{
/// An occupancy grid as nav_msgs/OccupancyGrid carries it.
struct OccupancyGridData
{
  std::string frame_id;
  uint64_t stamp_ns = 0;
  uint32_t width = 0;       ///< [cells]
  uint32_t height = 0;      ///< [cells]
  double resolution = 0.0;  ///< [m/cell]
  double origin_x = 0.0;    ///< [m] lower-left corner of cell (0,0)
  double origin_y = 0.0;    ///< [m]
  double origin_yaw = 0.0;  ///< [rad]
  /// Row-major, row 0 = lowest y. -1 unknown, 0..100 occupancy (other values are invalid).
  std::vector<int8_t> data;
};

/// A partial update of an occupancy grid, as map_msgs/OccupancyGridUpdate carries it.
struct OccupancyGridUpdateData
{
  std::string frame_id;
  uint64_t stamp_ns = 0;
  int32_t x = 0;  ///< [cells] column of the window's first cell
  int32_t y = 0;  ///< [cells] row of the window's first cell
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<int8_t> data;  ///< row-major, width * height values
};

struct SpeedLimitEntry
{
  uint32_t area_id = 0;
  double max_speed = 0.0;  ///< [m/s], or [%] of the default in percent mode
};

struct SpeedLimitsData
{
  std::string frame_id;
  uint64_t stamp_ns = 0;
  std::vector<SpeedLimitEntry> limits;
};
}  // namespace costmap_layers
