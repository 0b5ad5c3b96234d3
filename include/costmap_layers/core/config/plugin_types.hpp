// The plugin type names of move_base (costmap_2d) and Nav2 configurations, and this package's classes
// that take their place: the one table every host and tool resolves a written `type:` through.
#pragma once

#include <string>
#include <vector>

namespace costmap_layers
{
/// Whose plugin type name a configuration wrote.
enum class TypeDialect
{
  Native,     ///< costmap_layers/...
  Costmap2D,  ///< costmap_2d::... or range_sensor_layer::... (ROS 1)
  Nav2        ///< nav2_costmap_2d::...
};

struct PluginTypeAlias
{
  const char* written;  ///< as costmap_2d's or Nav2's configurations write it
  const char* ours;     ///< this package's pluginlib class
  TypeDialect dialect;
};

/// The one table of foreign type names this package loads.
const std::vector<PluginTypeAlias>& pluginTypeAliases();
/// This package's class for a written type: the alias' target, or the type itself when it is not an alias.
std::string resolvePluginType(const std::string& written);
/// Whose name `written` is.
TypeDialect typeDialect(const std::string& written);
/// The class name without its package: "costmap_2d::VoxelLayer" and "costmap_layers/VoxelLayer" -> "VoxelLayer".
std::string pluginClassName(const std::string& type);

/// The costmap_2d type whose place a layer of this package's class takes ("InflationLayer" ->
/// "costmap_2d::InflationLayer", "RangeSensorLayer" -> "range_sensor_layer::RangeSensorLayer"), "" when
/// costmap_2d has none (the filters, GradientLayer).
std::string costmap2dRole(const std::string& class_name);
}  // namespace costmap_layers
