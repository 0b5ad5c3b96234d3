#include "costmap_layers/core/rules/gradient_rule.hpp"

#include "costmap_layers/core/grid/cost_values.hpp"

namespace costmap_layers
{
uint8_t gradientCost(int k, int gradient_factor)
{
  return static_cast<uint8_t>((static_cast<int>(LETHAL_OBSTACLE) - k * gradient_factor) % 255);
}
}  // namespace costmap_layers
