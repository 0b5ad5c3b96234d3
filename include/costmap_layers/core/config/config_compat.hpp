// Real move_base (costmap_2d) and Nav2 costmap configurations, read the way those stacks read them:
// their plugin type names, costmap_2d's pre-Hydro parameters (no `plugins:` list), its
// copyParentParameters and searchParam look-ups, and the defaults its plugins have where ours differ.
// Everything works on the ParamValue tree of one costmap namespace, before the costmap is built.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "costmap_layers/core/costmap/costmap_config.hpp"
#include "costmap_layers/core/config/param_value.hpp"

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

struct CompatResult
{
  ParamValue params;  ///< the costmap's namespace as the costmap is then built from
  bool converted_pre_hydro = false;
  std::string plugin_list_yaml;  ///< when converted: the equivalent plugin-list form, to adopt
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

/// The costmap_2d type whose place a layer of this package's class takes ("InflationLayer" ->
/// "costmap_2d::InflationLayer", "RangeSensorLayer" -> "range_sensor_layer::RangeSensorLayer"), "" when
/// costmap_2d has none (the filters, GradientLayer).
std::string costmap2dRole(const std::string& class_name);

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

/// roslaunch loads a move_base file that nests everything under `global_costmap:` into the costmap's
/// own namespace as <ns>/global_costmap/global_costmap. When ns holds a map under the costmap's own
/// name (and no plugin of that name), its keys are merged over ns (they win, as a file loaded after
/// the common one does) and the nested key removed. @return true when it lifted.
bool liftOwnNamespace(ParamValue& ns, const std::string& own_name);

/// One costmap namespace made ready to build from, the same way in costmap_node and costmap_tool:
/// liftOwnNamespace() (noted), then applyCostmap2dRules(); a costmap with no plugin and no filter is
/// warned about (it would stay as it starts).
/// @param own_name  the last component of the costmap's namespace ("" for none)
CompatResult prepareCostmapNamespace(ParamValue ns, const std::string& own_name,
                                     const std::vector<ParentNamespace>& parents = {});

/// The namespaces around the one at `path` ("a/b/c") in a parameter tree, nearest first ("/a/b", "/a",
/// "/"), each with the searchedKeys() it holds: what a host reads from the parameter server.
std::vector<ParentNamespace> parentsInTree(const ParamValue& root, const std::string& path);

/// One warning line per parameter no parse asked for while `log` recorded (the costmap and its layers
/// set up): in the costmap's namespace (compat.params; its consumed keys are known) and in each layer's
/// (`layers`: each plugin with the parameter map its layer read). ns_name names the costmap's namespace.
std::vector<std::string> unusedParameterLines(const CompatResult& compat, const ParamReadLog& log,
                                              const std::vector<std::pair<PluginSpec, const ParamValue*>>& layers,
                                              const std::string& ns_name);

/// A YAML rendering of a tree (maps in block style, lists and small maps inline).
std::string toYaml(const ParamValue& value, int indent = 0);

/// Levenshtein distance.
std::size_t editDistance(const std::string& a, const std::string& b);
/// The candidate nearest to key when it is near enough to be a likely typo, else "".
std::string nearestName(const std::string& key, const std::vector<std::string>& candidates);

/// A key nobody asked for.
struct UnknownKey
{
  std::string path;             ///< relative to the namespace walked, e.g. "obstacle_layer/scan/topicc"
  std::string suggestion;       ///< the nearest known name, or ""
  std::string known_elsewhere;  ///< when costmap_2d or Nav2 know the key: why it is ignored here
  bool is_namespace = false;    ///< its value is a map (e.g. a layer namespace no plugin uses)
};

/// Walks ns: every key never asked while `log` recorded is reported; sub-maps that were read from are
/// walked too. `known` are names to take as asked at the top level; `skip` are top-level keys not to
/// look at (e.g. plugin namespaces walked separately). `scope` picks the table of keys costmap_2d or
/// Nav2 know: "costmap", "source", or a plugin class name such as "ObstacleLayer".
std::vector<UnknownKey> unknownKeys(const ParamValue& ns, const ParamReadLog& log, const std::string& scope,
                                    const std::vector<std::string>& known = {},
                                    const std::vector<std::string>& skip = {});

/// One warning line for an unknown key (`plugins` lists the costmap's plugin names, for namespaces), e.g.
/// "parameter 'inflaton_radius' in /move_base/global_costmap/inflation_layer is not used (did you mean
/// `inflation_radius`?)".
/// In a layer's namespace (layer_class set, e.g. "ObstacleLayer") a namespace key is one the layer does
/// not read, e.g. a misspelt observation source.
std::string describeUnknownKey(const UnknownKey& key, const std::string& ns_name,
                               const std::vector<std::string>& plugins = {}, const std::string& layer_class = "");
}  // namespace costmap_layers
