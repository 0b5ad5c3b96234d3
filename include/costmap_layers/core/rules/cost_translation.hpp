// Costs (0..255) to nav_msgs/OccupancyGrid values (0..100, -1), as costmap_2d's publisher does it.
#pragma once

#include <array>
#include <cstdint>

namespace costmap_layers
{
/// 0 -> 0, 1..252 -> 1 + 97 * (c - 1) / 251, 253 -> 99, 254 -> 100, 255 -> -1.
const std::array<int8_t, 256>& costTranslationTable();
}  // namespace costmap_layers
