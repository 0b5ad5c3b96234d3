// RangeSensorLayer's sensor model (Nav2's formulas): how a sonar / IR reading turns into a
// probability of occupancy per cell of its cone, and how probabilities are kept as costs.
#pragma once

#include <cstdint>

#include "costmap_layers/core/grid/cost_values.hpp"

namespace costmap_layers
{
namespace range_model
{
/// Angular weight: 1 - (theta / max_angle)^2 inside the cone, 0 outside.
double gamma(double theta, double max_angle);
/// Distance weight: 1 - (1 + tanh(2 (phi - phi_v))) / 2.
double delta(double phi, double phi_v);
/// Probability of occupancy of a cell at distance phi and angle theta for a reading r [m], with the
/// cell size `resolution` [m] setting the width of the obstacle band (resolution * r).
double sensorModel(double r, double phi, double theta, double max_angle, double phi_v, double resolution);
/// Cost <-> probability: p = cost / 254, cost = (uint8) (p * 254). NO_INFORMATION (a cleared cell:
/// costmap_2d's clearArea leaves it) is unknown, p = 0.5, as a cell never seen (as 255 / 254 > 1 it
/// made the next reading, free or not, an obstacle).
inline double toProbability(uint8_t cost)
{
  return cost == NO_INFORMATION ? 0.5 : static_cast<double>(cost) / 254.0;
}
inline uint8_t toCost(double p)
{
  return static_cast<uint8_t>(p * 254.0);
}
}  // namespace range_model
}  // namespace costmap_layers
