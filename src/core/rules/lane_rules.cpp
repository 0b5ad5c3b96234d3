#include "costmap_layers/core/rules/lane_rules.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "costmap_layers/core/grid/cost_values.hpp"

namespace costmap_layers
{
uint8_t lanesForbiddenCost(const LanesFilterConfig& c, double d, double r)
{
  const double w = c.lane_border_width;
  if (!(d < w)) return LETHAL_OBSTACLE;  // also +infinity and NaN
  const double span = w - r;
  double s = 0.0;
  if (span > 0.0 && d > r)
  {
    if (c.cost_profile == LaneCostProfile::Linear)
      s = (d - r) / span;
    else
      // (e^{k(d-r)} - 1) / (e^{k(W-r)} - 1), written so that it neither overflows nor loses precision.
      s = std::exp(c.decay * (d - w)) * std::expm1(-c.decay * (d - r)) / std::expm1(-c.decay * span);
  }
  s = std::clamp(s, 0.0, 1.0);
  const double cost = c.border_cost + (INSCRIBED_INFLATED_OBSTACLE - c.border_cost) * s;
  return static_cast<uint8_t>(std::min<long>(std::lround(cost), INSCRIBED_INFLATED_OBSTACLE));
}

uint64_t lanesLethalSquaredDistance(const LanesFilterConfig& c, double r)
{
  auto lethal = [&](uint64_t q) { return std::sqrt(static_cast<double>(q)) * r >= c.lane_border_width; };
  const double ratio = c.lane_border_width / r;
  // Beyond any grid's reach (the validator caps masks at 4e8 cells): never lethal by distance.
  if (!(ratio < 1e9)) return std::numeric_limits<uint64_t>::max();
  uint64_t q = static_cast<uint64_t>(std::floor(ratio * ratio));
  while (q > 0 && lethal(q - 1))
    --q;
  while (!lethal(q))
    ++q;
  return q;
}
}  // namespace costmap_layers
