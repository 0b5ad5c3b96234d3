// GradientLayer's cost rule (the ramp of Nav2's "Writing a New Costmap2D Plugin" tutorial).
#pragma once

#include <cstdint>

#include "costmap_layers/core/grid/cost_values.hpp"

namespace costmap_layers
{
/// Cost of the k-th cell of a ramp: (LETHAL_OBSTACLE - k * factor) % 255, as the tutorial computes it
/// in int and stores it in an unsigned char.
inline uint8_t gradientCost(int k, int gradient_factor)
{
  return static_cast<uint8_t>((static_cast<int>(LETHAL_OBSTACLE) - k * gradient_factor) % 255);
}
}  // namespace costmap_layers
