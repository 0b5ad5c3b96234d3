// What a loaded map or mask holds, in one line, and whether its values look like an image drawn for
// the other pixel rule (map_file.hpp describes both rules). mask_server logs both when it loads a file.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "costmap_layers/core/data/grid_data.hpp"
#include "costmap_layers/io/map_file.hpp"

namespace costmap_layers
{
namespace io
{
/// How many cells hold each value; index = value + 128 (so -1 is index 127).
std::array<uint64_t, 256> countValues(const OccupancyGridData& grid);

/// "value x count" for each value present, ascending ("-1 x 12, 0 x 3400, 100 x 56"), when at most
/// `max_listed` distinct values are present; otherwise a histogram: -1, 0, 1-10, 11-20, ..., 91-99,
/// 100 and "other" (values outside -1..100), each with its count and the number of distinct values
/// in it, empty bins left out.
std::string describeValues(const std::array<uint64_t, 256>& counts, std::size_t max_listed = 16);

/// The rule `mode` converts pixels with: "ros1 (map_server: 1 + 98 * ratio, truncated; strict
/// thresholds)" or "nav2 (map_io: round(100 * ratio); inclusive thresholds)" for the scale modes,
/// and the ROS 1 rule's short name for trinary and raw.
std::string pixelRuleDescription(MapMode mode);

/// A warning when the values look like an image drawn for the other pixel rule, else empty. Checked:
/// read with ROS 1's scale rule, the grid has 1 and/or 99 but neither 0 nor 100 (known values only):
/// what a Nav2 mask with thresholds 1.0 / 0.0 gives under that rule, where 0 and 100 were meant.
/// (The opposite direction cannot be told from the values: the two rules differ by at most one.)
std::string pixelRuleWarning(const std::array<uint64_t, 256>& counts, MapMode mode);
}  // namespace io
}  // namespace costmap_layers
