// GradientLayer's cost rule (the ramp of Nav2's "Writing a New Costmap2D Plugin" tutorial).
#pragma once

#include <cstdint>

namespace costmap_layers
{
/// Cost of the k-th cell of a ramp: (LETHAL_OBSTACLE - k * factor) % 255, as the tutorial computes it
/// in int and stores it in an unsigned char.
uint8_t gradientCost(int k, int gradient_factor);
}  // namespace costmap_layers
