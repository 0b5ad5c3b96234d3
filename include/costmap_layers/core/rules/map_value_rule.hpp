// What an occupancy value of a map costs: costmap_2d's StaticLayer::interpretValue, the one rule
// the static layer (and its SIMD conversion of trinary maps) follows.
#pragma once

#include <cstdint>

namespace costmap_layers
{
/// The static layer's parameters that the rule reads (costmap_2d's names).
struct MapValueRule
{
  int unknown_cost_value = -1;      ///< the occupancy value meaning "unknown" (compared as a byte)
  int lethal_cost_threshold = 100;  ///< occupancy at or above this is lethal, in [0, 100]
  bool trinary_costmap = true;      ///< below the threshold: free, else scaled
  bool track_unknown_space = true;  ///< unknown stays NO_INFORMATION, else FREE_SPACE
};

/// The cost of one occupancy value, value and unknown_cost_value both read as bytes (so -1 is 255):
/// unknown (with tracking) -> NO_INFORMATION, unknown (without) -> FREE_SPACE, >= threshold ->
/// LETHAL_OBSTACLE, trinary -> FREE_SPACE, otherwise value / threshold * LETHAL_OBSTACLE truncated.
uint8_t mapValueCost(int8_t value, const MapValueRule& rule);
}  // namespace costmap_layers
