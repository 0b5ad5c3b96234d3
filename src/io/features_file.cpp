#include "costmap_layers/io/features_file.hpp"

#include <stdexcept>

#include "costmap_layers/core/filters/speed_filter.hpp"
#include "costmap_layers/io/param_yaml.hpp"

namespace costmap_layers::io
{
SpeedLimitsData speedLimitsFromParams(const ParamValue& root, const std::string& what)
{
  const ParamValue* limits = root.find("limits");
  if (limits == nullptr || !limits->isList())
    throw std::runtime_error(what + ": expected a list under 'limits' (e.g. limits: [{area_id: 1, max_speed: 0.5}])");
  SpeedLimitsData data;
  std::size_t k = 0;
  for (const auto& entry : limits->asList())
  {
    const std::string where = what + ": limits[" + std::to_string(k++) + "]";
    const ParamValue* id = entry.find("area_id");
    const ParamValue* speed = entry.find("max_speed");
    if (id == nullptr || id->type() != ParamValue::Type::Int || id->asInt() < 0 || id->asInt() > 0xFFFFFFFFll)
      throw std::runtime_error(where + ": area_id must be a non-negative integer (got " +
                               (id ? id->toString() : std::string("nothing")) + ")");
    if (speed == nullptr || !speed->isNumber())
      throw std::runtime_error(where + ": max_speed must be a number (got " +
                               (speed ? speed->toString() : std::string("nothing")) + ")");
    data.limits.push_back({static_cast<uint32_t>(id->asInt()), speed->asDouble()});
  }
  return data;
}

SpeedLimitsData loadFeaturesFile(const std::string& path)
{
  return speedLimitsFromParams(loadOwnFormatYamlFile(path, kMaxFeaturesYamlBytes), path);
}

std::vector<std::string> featuresFileProblems(const SpeedLimitsData& limits)
{
  std::vector<SpeedLimitIssue> issues;
  buildSpeedLimitTable(limits, SpeedFilterConfig{}, &issues);
  std::vector<std::string> lines;
  for (const auto& i : issues)
    lines.push_back(std::string(i.error ? "error: " : "warning: ") + i.message);
  return lines;
}
}  // namespace costmap_layers::io
