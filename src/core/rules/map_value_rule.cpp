#include "costmap_layers/core/rules/map_value_rule.hpp"

#include "costmap_layers/core/grid/cost_values.hpp"

namespace costmap_layers
{
uint8_t mapValueCost(int8_t value, const MapValueRule& rule)
{
  // As costmap_2d: the message value and the unknown value both as unsigned bytes.
  const uint8_t v = static_cast<uint8_t>(value);
  const uint8_t unknown = static_cast<uint8_t>(rule.unknown_cost_value);
  const int threshold = rule.lethal_cost_threshold;
  if (v == unknown) return rule.track_unknown_space ? NO_INFORMATION : FREE_SPACE;
  if (v >= threshold) return LETHAL_OBSTACLE;
  if (rule.trinary_costmap) return FREE_SPACE;
  const double scale = static_cast<double>(v) / threshold;  // threshold > v >= 0 here
  return static_cast<uint8_t>(scale * LETHAL_OBSTACLE);
}
}  // namespace costmap_layers
