// Speed-limit features as YAML: limits: [{area_id: 1, max_speed: 0.5}, ...]
#pragma once

#include <string>

#include "costmap_layers/core/grid_data.hpp"
#include "costmap_layers/core/param_value.hpp"

namespace costmap_layers::io
{
/// Reads the `limits` list of a parameter tree. Throws std::runtime_error naming `what`, the entry and
/// the field when the structure or a type is wrong. Values are not range-checked here (SpeedFilter
/// rejects bad entries one by one).
SpeedLimitsData speedLimitsFromParams(const ParamValue& root, const std::string& what);
/// speedLimitsFromParams() on a YAML file.
SpeedLimitsData loadFeaturesFile(const std::string& path);
}  // namespace costmap_layers::io
