#include "costmap_layers/core/config/nav2_defaults.hpp"

#include <sstream>
#include <utility>

#include "costmap_layers/core/costmap/costmap_config.hpp"

namespace costmap_layers
{
// A Nav2 file (ROS 2's ros__parameters level) reads Nav2's Costmap2DROS defaults where they differ from
// costmap_2d's, which are this package's: each one taken is said.
void applyNav2CostmapDefaults(CompatResult& r)
{
  const CostmapConfig ours;  // costmap_2d's defaults
  const std::pair<const char*, std::pair<double, double>> defaults[] = {
      {"publish_frequency", {1.0, ours.publish_frequency}},
      {"width", {5.0, ours.width}},
      {"height", {5.0, ours.height}},
      {"resolution", {0.1, ours.resolution}}};
  ParamValue& ns = r.params;
  auto take = [&](const char* key, double nav2, double costmap_2d)
  {
    ns.set(key, ParamValue::makeDouble(nav2));
    std::ostringstream text;
    text << key << " not set: " << nav2 << ", Nav2's default (costmap_2d's is " << costmap_2d
         << (costmap_2d == 0.0 ? ": never" : "") << ")";
    r.notes.push_back(text.str());
  };
  for (const auto& [key, values] : defaults)
    if (ns.find(key) == nullptr) take(key, values.first, values.second);
  const ParamValue* footprint = ns.find("footprint");
  if (ns.find("robot_radius") == nullptr && (footprint == nullptr || !givesPolygon(*footprint)))
    take("robot_radius", 0.1, ours.footprint.robot_radius);
}
}  // namespace costmap_layers
