// LanesFilter's cost rule (the formula is in filters/lanes_filter.hpp's file comment): what a forbidden
// mask cell costs at a distance from the nearest lane cell, and from which distance it is lethal.
#pragma once

#include <cstdint>

namespace costmap_layers
{
enum class LaneCostProfile
{
  Linear,
  Exponential
};

struct LanesFilterConfig
{
  double lane_border_width = 0.5;  ///< [m]
  int border_cost = 1;
  LaneCostProfile cost_profile = LaneCostProfile::Linear;
  double decay = 10.0;  ///< [1/m]
};

/// The cost of a forbidden cell whose nearest lane cell is d [m] away, on a mask of the given
/// resolution [m] (formula in filters/lanes_filter.hpp). d = +infinity (no lane at all) gives 254.
uint8_t lanesForbiddenCost(const LanesFilterConfig& config, double d, double resolution);

/// The smallest squared distance [cells^2] at which a forbidden cell is lethal on a mask of the given
/// resolution: the least integer q with sqrt(q) * resolution >= lane_border_width.
uint64_t lanesLethalSquaredDistance(const LanesFilterConfig& config, double resolution);
}  // namespace costmap_layers
