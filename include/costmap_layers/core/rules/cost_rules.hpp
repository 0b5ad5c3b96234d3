// The cost rules shared by several layers and filters: what a distance from an obstacle costs, what a
// mask value costs, and how a filter's cost merges into a master cell. Every rule of the package lives
// in this folder (rules/), one file per subject: map_value_rule (a map's occupancy), lane_rules,
// gradient_rule, range_model, speed_rules, cost_translation (costs to OccupancyGrid values), limits
// (the ranges of every number) and stamp_order (time). Layers, filters, tests and benchmarks call
// these; none writes its own copy.
#pragma once

#include <cmath>
#include <cstdint>

#include "costmap_layers/core/grid/cost_values.hpp"

namespace costmap_layers
{
/// costmap_2d's cost at dist_cells cells from the nearest source: 254 at 0, 253 while
/// dist_cells * resolution <= inscribed_radius, else (uchar)(252 * exp(-factor * (d [m] - inscribed))).
inline uint8_t inflationCost(double dist_cells, double resolution, double inscribed_radius, double cost_scaling_factor)
{
  if (dist_cells == 0.0) return LETHAL_OBSTACLE;
  const double dist = dist_cells * resolution;
  if (dist <= inscribed_radius) return INSCRIBED_INFLATED_OBSTACLE;
  const double factor = std::exp(-cost_scaling_factor * (dist - inscribed_radius));
  return static_cast<uint8_t>(MAX_NON_OBSTACLE * factor);
}

/// The cost of a mask value (Nav2's keepout rule): round(v * 254 / 100) for v in 1..100, so 100 is
/// LETHAL (a virtual wall); 0, -1 and invalid values cost nothing. Integer arithmetic that loops
/// vectorise: for v >= 1, round-half-up of 2.54 v is (254 v + 50) / 100 (at most 25450, within 16 bits).
inline uint8_t maskValueCost(int8_t v)
{
  const auto u = static_cast<uint8_t>(v);
  const auto c = static_cast<uint8_t>(static_cast<uint16_t>(u * 254u + 50u) / 100u);
  return static_cast<uint8_t>(u - 1u) < 100u ? c : FREE_SPACE;
}

/// KeepoutFilter's escape ramp: the cost of a lethal keepout cell whose centre lies depth [m] inside the
/// zone (from the nearest cell outside it) while the robot escapes: ceil(top * depth / ramp_length),
/// at least 1, and top from ramp_length on (and for a ramp_length that is not > 0).
inline uint8_t escapeRampCost(double depth, double ramp_length, uint8_t top)
{
  if (!(ramp_length > 0.0) || !(depth < ramp_length)) return top;
  const double c = std::ceil(top * depth / ramp_length);
  return c < 1.0 ? uint8_t{1} : (c > top ? top : static_cast<uint8_t>(c));
}

/// Merges a filter's cost into a master cell: the master takes the cost when higher; an unknown master
/// cell only takes a cost >= 253, so a filter never turns unknown space into known free space.
inline uint8_t mergeFilterCost(uint8_t master, uint8_t cost)
{
  const bool unknown = master == NO_INFORMATION;
  const uint8_t higher = cost > master ? cost : master;
  return unknown ? (cost >= INSCRIBED_INFLATED_OBSTACLE ? cost : master) : higher;
}
}  // namespace costmap_layers
