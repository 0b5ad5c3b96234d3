#include "costmap_layers/core/config/plugin_types.hpp"

namespace costmap_layers
{
const std::vector<PluginTypeAlias>& pluginTypeAliases()
{
  static const std::vector<PluginTypeAlias> table = {
      {"costmap_2d::StaticLayer", "costmap_layers/StaticLayer", TypeDialect::Costmap2D},
      {"costmap_2d::ObstacleLayer", "costmap_layers/ObstacleLayer", TypeDialect::Costmap2D},
      {"costmap_2d::VoxelLayer", "costmap_layers/VoxelLayer", TypeDialect::Costmap2D},
      {"costmap_2d::InflationLayer", "costmap_layers/InflationLayer", TypeDialect::Costmap2D},
      {"range_sensor_layer::RangeSensorLayer", "costmap_layers/RangeSensorLayer", TypeDialect::Costmap2D},
      {"nav2_costmap_2d::StaticLayer", "costmap_layers/StaticLayer", TypeDialect::Nav2},
      {"nav2_costmap_2d::ObstacleLayer", "costmap_layers/ObstacleLayer", TypeDialect::Nav2},
      {"nav2_costmap_2d::VoxelLayer", "costmap_layers/VoxelLayer", TypeDialect::Nav2},
      {"nav2_costmap_2d::InflationLayer", "costmap_layers/InflationLayer", TypeDialect::Nav2},
      // Nav2 (2025) keeps its earlier inflation under this name: the same costs and parameters.
      {"nav2_costmap_2d::LegacyInflationLayer", "costmap_layers/InflationLayer", TypeDialect::Nav2},
      {"nav2_costmap_2d::RangeSensorLayer", "costmap_layers/RangeSensorLayer", TypeDialect::Nav2},
      {"nav2_costmap_2d::KeepoutFilter", "costmap_layers/KeepoutFilter", TypeDialect::Nav2},
      {"nav2_costmap_2d::SpeedFilter", "costmap_layers/SpeedFilter", TypeDialect::Nav2},
      {"nav2_costmap_2d::ZoneParameterFilter", "costmap_layers/ZoneParameterFilter", TypeDialect::Nav2},
      {"nav2_costmap_2d::BinaryFilter", "costmap_layers/BinaryFilter", TypeDialect::Nav2},
      {"nav2_costmap_2d::DenoiseLayer", "costmap_layers/DenoiseLayer", TypeDialect::Nav2},
      {"nav2_costmap_2d::AsymmetricInflationLayer", "costmap_layers/AsymmetricInflationLayer", TypeDialect::Nav2},
      {"nav2_costmap_2d::PluginContainerLayer", "costmap_layers/PluginContainerLayer", TypeDialect::Nav2},
  };
  return table;
}

namespace
{
const PluginTypeAlias* findAlias(const std::string& written)
{
  for (const auto& a : pluginTypeAliases())
    if (written == a.written) return &a;
  return nullptr;
}
}  // namespace

std::string resolvePluginType(const std::string& written)
{
  const PluginTypeAlias* a = findAlias(written);
  return a != nullptr ? a->ours : written;
}

TypeDialect typeDialect(const std::string& written)
{
  const PluginTypeAlias* a = findAlias(written);
  return a != nullptr ? a->dialect : TypeDialect::Native;
}

std::string pluginClassName(const std::string& type)
{
  const auto colons = type.rfind("::");
  const auto slash = type.rfind('/');
  std::size_t start = 0;
  if (colons != std::string::npos) start = colons + 2;
  if (slash != std::string::npos && slash + 1 > start) start = slash + 1;
  return type.substr(start);
}
std::string costmap2dRole(const std::string& class_name)
{
  for (const auto& a : pluginTypeAliases())
    if (a.dialect == TypeDialect::Costmap2D && pluginClassName(a.ours) == class_name) return a.written;
  return "";
}
}  // namespace costmap_layers
