// Plain data types the core receives from outside: an occupancy grid (map or filter mask), speed
// limits, and a costmap filter info. The ROS adapter converts messages into them; costmap_tool fills them from files.
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

/// What Nav2's CostmapFilterInfo message says (costmap_layers/CostmapFilterInfo carries the same
/// fields): which mask a filter reads and how its values map to the filter's quantity,
/// value = base + multiplier * mask value.
struct FilterInfoData
{
  std::string frame_id;
  uint64_t stamp_ns = 0;
  /// 0 keepout / lanes, 1 speed limit in percent, 2 speed limit in m/s, 3 binary (filter_info.hpp)
  uint8_t type = 0;
  std::string filter_mask_topic;
  double base = 0.0;        ///< float32 in the message
  double multiplier = 1.0;  ///< float32 in the message
};
}  // namespace costmap_layers
