// What costmap_2d (move_base) does to a costmap's namespace before its layers read it, done here on the
// ParamValue tree of one costmap namespace: its pre-Hydro parameters (no `plugins:` list,
// loadOldParameters), copyParentParameters, its searchParam look-ups, and the defaults its plugins (and
// Nav2's, for their type names) have where this package's differ.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "costmap_layers/core/config/param_value.hpp"

namespace costmap_layers
{
/// The keys costmap_2d looks up with searchParam (the namespace first, then each parent namespace
/// up to the root): `footprint` and `robot_radius` from the costmap's namespace, `obstacle_range`
/// and `raytrace_range` from each observation source's namespace. A host fetches these from the
/// parents of the costmap's namespace and hands them to applyCostmap2dRules().
const std::vector<std::string>& searchedKeys();

/// The searched keys set in one parent namespace of the costmap's.
struct ParentNamespace
{
  std::string name;   ///< e.g. "/move_base" (for messages)
  ParamValue values;  ///< a map holding (some of) searchedKeys()
};

/// costmap_2d's searchParam over a chain of namespaces, nearest first: the first that holds key.
/// @param where  set to the index in chain of the namespace that held it
const ParamValue* searchParam(const std::vector<const ParamValue*>& chain, const std::string& key,
                              std::size_t* where = nullptr);

/// Whether a footprint value is a polygon (a non-empty list, or a string other than "[]"), i.e. one
/// that robot_radius yields to in costmap_2d's makeFootprintFromParams.
bool givesPolygon(const ParamValue& footprint);

struct CompatResult
{
  ParamValue params;  ///< the costmap's namespace as the costmap is then built from
  bool converted_pre_hydro = false;
  /// When converted: the equivalent plugin-list form (a map of `plugins` and each layer's namespace that
  /// holds keys), for the user to adopt; a host prints it with io::paramToYaml(). Null otherwise.
  ParamValue plugin_list;
  /// Keys of the costmap's own namespace this step used up (known: not to be reported as unknown).
  std::vector<std::string> consumed;
  /// The same for each plugin's namespace (by plugin name): keys costmap_2d reads there through
  /// searchParam from the sources (obstacle_range, raytrace_range).
  std::map<std::string, std::vector<std::string>> layer_consumed;
  std::vector<std::string> warnings;  ///< what costmap_2d would have warned about, and more
  std::vector<std::string> notes;     ///< what was done on the user's behalf (info)
};

/// Applies costmap_2d's rules to one costmap namespace `ns` (the parents nearest first):
///  1. no `plugins` (nor Nav2's `plugin_names`): loadOldParameters, i.e. static_map -> static_layer
///     (map_topic, unknown_cost_value, lethal_cost_threshold, track_unknown_space), map_type voxel or
///     costmap -> obstacle_layer (VoxelLayer: origin_z, z_resolution, z_voxels, mark_threshold,
///     unknown_threshold, publish_voxel_map; both: max_obstacle_height, raytrace_range,
///     obstacle_range, track_unknown_space, observation_sources and each source's namespace), and
///     always inflation_layer (cost_scaling_factor, inflation_radius); moved keys leave the costmap's
///     namespace, except track_unknown_space, which the costmap itself reads first.
///     With a plugin list, static_map and map_type are reported as unused.
///  2. copyParentParameters for each costmap_2d:: type: the costmap-level value of the layer's keys
///     replaces the layer's own (costmap_2d's behaviour, reported when they differ).
///  3. costmap_2d's defaults where this package's differ, for costmap_2d:: types only:
///     StaticLayer track_unknown_space true; an observation source without data_type reads PointCloud
///     (sensor_msgs/PointCloud; Nav2's types: LaserScan).
///  4. searchParam: footprint and robot_radius from the parents when the costmap's namespace lacks
///     them; obstacle_range and raytrace_range for each source of an obstacle or voxel layer from the
///     layer's namespace, the costmap's, then the parents.
/// Throws std::invalid_argument on a malformed plugin list.
CompatResult applyCostmap2dRules(const ParamValue& ns, const std::vector<ParentNamespace>& parents = {});

/// For a layer that costmap_2d hosts (move_base) in the place of its own `role_type` (from
/// costmap2dRole(); "" for none): what costmap_2d does for that type of its own, which it does not do
/// for a type it does not know. On the costmap's namespace ns (its plugin list is not read):
/// copyParentParameters (the costmap-level value replaces the layer's own, reported when they differ),
/// StaticLayer's track_unknown_space default true, data_type PointCloud for an observation source that
/// sets none, the searchParam of obstacle_range and raytrace_range for each observation source, and a
/// sensor_frame's leading '/' stripped. The layer's namespace is then
/// params.find(name); warnings and notes concern that layer only.
CompatResult applyCostmap2dRulesAsRole(const ParamValue& ns, const std::string& name, const std::string& role_type,
                                       const std::vector<ParentNamespace>& parents = {});
}  // namespace costmap_layers
