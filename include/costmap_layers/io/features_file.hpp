// Speed-limit features as YAML: limits: [{area_id: 1, max_speed: 0.5}, ...]
#pragma once

#include <string>
#include <vector>

#include "costmap_layers/core/data/grid_data.hpp"
#include "costmap_layers/core/config/param_value.hpp"

namespace costmap_layers::io
{
/// Reads the `limits` list of a parameter tree. Throws std::runtime_error naming `what`, the entry and
/// the field when the structure or a type is wrong. Values are not range-checked here (SpeedFilter
/// rejects bad entries one by one).
SpeedLimitsData speedLimitsFromParams(const ParamValue& root, const std::string& what);
/// speedLimitsFromParams() on a YAML file.
SpeedLimitsData loadFeaturesFile(const std::string& path);
/// What every SpeedFilter will say about these limits whatever its mode (buildSpeedLimitTable's rules
/// in m/s: area ids 1..100, finite speeds >= 0, repeated ids): one line per entry, "error: ..." for
/// an entry a filter drops, "warning: ..." for one it takes with a remark. Empty when all is well.
std::vector<std::string> featuresFileProblems(const SpeedLimitsData& limits);
}  // namespace costmap_layers::io
