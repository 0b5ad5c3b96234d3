// The cost values every layer and filter agrees on (costmap_2d's meanings).
#pragma once

#include <cstdint>

namespace costmap_layers
{
constexpr uint8_t NO_INFORMATION = 255;
constexpr uint8_t LETHAL_OBSTACLE = 254;
constexpr uint8_t INSCRIBED_INFLATED_OBSTACLE = 253;
constexpr uint8_t MAX_NON_OBSTACLE = 252;
constexpr uint8_t FREE_SPACE = 0;
}  // namespace costmap_layers
