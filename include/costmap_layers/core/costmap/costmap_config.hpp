// The costmap's own parameters (costmap_2d's names, meanings and defaults) and its plugin lists.
#pragma once

#include <string>
#include <vector>

#include "costmap_layers/core/grid/footprint.hpp"
#include "costmap_layers/core/config/param_value.hpp"

namespace costmap_layers
{
struct CostmapConfig
{
  std::string global_frame = "map";
  std::string robot_base_frame = "base_link";
  // Ranges: see limits.hpp (frequencies, kMaxDuration, kMinResolution..kMaxResolution,
  // kMaxCoordinate, kMaxDistance, kMaxGridCells for width x height).
  double transform_tolerance = 0.3;  ///< [s]
  double update_frequency = 5.0;     ///< [Hz], > 0
  double publish_frequency = 0.0;    ///< [Hz], 0 = never publish (costmap_2d's default)
  double width = 10.0;               ///< [m]
  double height = 10.0;              ///< [m]
  double resolution = 0.05;          ///< [m/cell]
  double origin_x = 0.0;             ///< [m]
  double origin_y = 0.0;             ///< [m]
  bool rolling_window = false;
  bool track_unknown_space = false;
  bool always_send_full_costmap = false;
  double reset_distance = 3.0;  ///< [m] side of the square ~clear_around_robot keeps
  FootprintConfig footprint;

  unsigned int sizeInCellsX() const;
  unsigned int sizeInCellsY() const;
};

/// Reads and validates the costmap's namespace. Throws std::invalid_argument naming the parameter.
CostmapConfig parseCostmapConfig(const ParamValue& ns);

struct PluginSpec
{
  std::string name;  ///< instance name, also its parameter namespace
  std::string type;  ///< pluginlib class name, e.g. costmap_layers/GradientLayer
};

struct PluginLists
{
  std::vector<PluginSpec> plugins;
  std::vector<PluginSpec> filters;
};

/// Reads the plugin lists in every form users have:
///  - ROS 1: plugins: [{name: a, type: costmap_layers/GradientLayer}, ...]
///  - Nav2 (Foxy): plugin_names: [a, ...] with plugin_types: [costmap_layers/GradientLayer, ...]
///  - Nav2 (Galactic on): plugins: [a, ...] with a: {plugin: costmap_layers/GradientLayer}
/// and the same for an optional `filters` list. Throws std::invalid_argument on a malformed list,
/// a missing type or a name used twice.
PluginLists parsePluginLists(const ParamValue& ns);

/// The `plugins` list of a layer that holds layers (PluginContainerLayer), in any of the forms above,
/// under the same rules (names, count, a name used twice); errors start with `owner`.
std::vector<PluginSpec> parsePluginList(const ParamValue& ns, const std::string& owner);
/// The parameters of plugin `name` in the costmap's namespace ns: the key `name`, or for a container's
/// plugin ("<container>/<plugin>") the nested map; nullptr when there is none.
const ParamValue* pluginParams(const ParamValue& ns, const std::string& name);
}  // namespace costmap_layers
