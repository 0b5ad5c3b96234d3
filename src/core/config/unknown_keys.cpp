#include "costmap_layers/core/config/unknown_keys.hpp"

#include <algorithm>

#include "costmap_layers/core/config/plugin_types.hpp"

namespace costmap_layers
{
std::size_t editDistance(const std::string& a, const std::string& b)
{
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
  {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
    {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string nearestName(const std::string& key, const std::vector<std::string>& candidates)
{
  // Up to a third of the name's letters wrong (at least one, at most three): a typo, not another word.
  const std::size_t limit = std::max<std::size_t>(1, std::min<std::size_t>(3, key.size() / 3));
  std::string best;
  std::size_t best_d = limit + 1;
  for (const auto& c : candidates)
  {
    if (c == key) continue;
    const std::size_t d = editDistance(key, c);
    if (d < best_d)
    {
      best_d = d;
      best = c;
    }
  }
  return best;
}

namespace
{
struct IgnoredKey
{
  const char* scope;  ///< "costmap", "source", a plugin class, or "*"
  const char* key;
  const char* why;
};

const std::vector<IgnoredKey>& ignoredKeys()
{
  static const char* kNav2Static =
      "Nav2 reads it at the costmap level for its StaticLayer; costmap_layers reads it in the static layer's "
      "namespace (costmap_2d's place): move it there";
  // costmap_2d's copyParentParameters moves each of these from the costmap's namespace into a plugin
  // of one type only, written costmap_2d::... (e.g. max_obstacle_height into an ObstacleLayer, not a
  // VoxelLayer).
  static const char* kNeedsStatic =
      "a pre-Hydro costmap-level key: with a plugins list costmap_2d copies it only into a plugin of type "
      "costmap_2d::StaticLayer; set it in the static layer's namespace";
  static const char* kNeedsInflation =
      "a pre-Hydro costmap-level key: with a plugins list costmap_2d copies it only into a plugin of type "
      "costmap_2d::InflationLayer; set it in the inflation layer's namespace";
  static const char* kNeedsObstacle =
      "a pre-Hydro costmap-level key: with a plugins list costmap_2d copies it only into a plugin of type "
      "costmap_2d::ObstacleLayer (not a VoxelLayer); set it in the obstacle or voxel layer's namespace";
  static const char* kNeedsVoxel =
      "a pre-Hydro costmap-level key: with a plugins list costmap_2d copies it only into a plugin of type "
      "costmap_2d::VoxelLayer; set it in the voxel layer's namespace";
  // How sensor readings meet tf here, for the two stacks' tolerance keys of obstacle and voxel layers.
  static const char* kCostmap2dSensorTf =
      "costmap_2d's obstacle layer lets tf lag this much (default 0.2 s); here readings wait for tf in a bounded "
      "queue and the costmap's transform_tolerance applies to the robot pose";
  static const char* kNav2SensorTf =
      "Nav2's tf message filter tolerance; here readings wait for tf in a bounded queue and the costmap's "
      "transform_tolerance applies to the robot pose";
  static const std::vector<IgnoredKey> table = {
      {"costmap", "footprint_topic",
       "costmap_2d subscribes to it for footprint changes at run time; costmap_layers takes the footprint from "
       "parameters only"},
      {"costmap", "published_footprint_topic", "costmap_layers always publishes the footprint on ~footprint"},
      {"costmap", "use_sim_time", "a ROS 2 node parameter; in ROS 1 set the global /use_sim_time"},
      {"costmap", "clearable_layers", "Nav2's; here ~clear resets every obstacle, voxel and range layer"},
      {"costmap", "initial_transform_timeout", "Nav2's; costmap_node waits for the robot's transform, saying so"},
      {"costmap", "map_vis_z", "Nav2's; costmap_layers publishes no visualisation offset"},
      {"costmap", "lethal_cost_threshold", kNav2Static},
      {"costmap", "unknown_cost_value", kNav2Static},
      {"costmap", "trinary_costmap", kNav2Static},
      {"costmap", "use_maximum", kNav2Static},
      {"costmap", "map_topic", kNeedsStatic},
      {"costmap", "inflation_radius", kNeedsInflation},
      {"costmap", "cost_scaling_factor", kNeedsInflation},
      {"costmap", "max_obstacle_height", kNeedsObstacle},
      {"costmap", "observation_sources",
       "a pre-Hydro costmap-level key: with a plugins list costmap_2d reads it only in an obstacle or voxel "
       "layer's namespace; set it there"},
      {"costmap", "obstacle_range", "found by searchParam from an obstacle layer's sources; this costmap has none"},
      {"costmap", "raytrace_range", "found by searchParam from an obstacle layer's sources; this costmap has none"},
      {"costmap", "origin_z", kNeedsVoxel},
      {"costmap", "z_resolution", kNeedsVoxel},
      {"costmap", "z_voxels", kNeedsVoxel},
      {"costmap", "mark_threshold", kNeedsVoxel},
      {"costmap", "unknown_threshold", kNeedsVoxel},
      {"costmap", "publish_voxel_map", kNeedsVoxel},
      {"ObstacleLayer", "transform_tolerance", kCostmap2dSensorTf},
      {"VoxelLayer", "transform_tolerance", kCostmap2dSensorTf},
      {"StaticLayer", "map_subscribe_transient_local", "Nav2's QoS switch; ROS 1 map topics are latched"},
      {"costmap", "introspection_mode", "Nav2's ROS 2 service introspection; ROS 1 has none"},
      {"*", "allow_parameter_qos_overrides", "a ROS 2 QoS setting; ROS 1 topics have no QoS"},
      {"ObstacleLayer", "tf_filter_tolerance", kNav2SensorTf},
      {"VoxelLayer", "tf_filter_tolerance", kNav2SensorTf},
      {"source", "transport_type", "Nav2's point cloud transport (ROS 2); ROS 1 subscribes to the topic itself"},
      {"StaticLayer", "transform_tolerance", "Nav2's; the map is placed with the costmap's transform_tolerance"},
      {"RangeSensorLayer", "ns", "the ROS 1 plugin's topic prefix; write the full topic names in `topics`"},
      {"KeepoutFilter", "transform_tolerance", "Nav2's; the mask is placed with the costmap's transform_tolerance"},
      {"SpeedFilter", "transform_tolerance", "Nav2's; the mask is placed with the costmap's transform_tolerance"},
      {"BinaryFilter", "transform_tolerance", "Nav2's; the mask is placed with the costmap's transform_tolerance"},
  };
  return table;
}

const char* ignoredReason(const std::string& scope, const std::string& key)
{
  for (const auto& k : ignoredKeys())
    if (key == k.key && (scope == k.scope || std::string(k.scope) == "*")) return k.why;
  return nullptr;
}

void walk(const ParamValue& m, const ParamReadLog& log, const std::string& prefix, const std::string& scope,
          const std::vector<std::string>& known, const std::vector<std::string>& skip, std::vector<UnknownKey>& out)
{
  std::vector<std::string> candidates = log.askedKeys(&m);
  candidates.insert(candidates.end(), known.begin(), known.end());
  for (const auto& [key, value] : m.entries())
  {
    if (std::find(skip.begin(), skip.end(), key) != skip.end()) continue;
    const bool is_known = log.asked(&m, key) || std::find(known.begin(), known.end(), key) != known.end();
    if (is_known)
    {
      if (value.isMap() && log.readFrom(&value))
      {
        const bool sensor_layer = scope == "ObstacleLayer" || scope == "VoxelLayer";
        walk(value, log, prefix + key + "/", sensor_layer ? "source" : scope, {}, {}, out);
      }
      continue;
    }
    UnknownKey u;
    u.path = prefix + key;
    u.is_namespace = value.isMap();
    if (const char* why = ignoredReason(scope, key)) u.known_elsewhere = why;
    if (u.known_elsewhere.empty()) u.suggestion = nearestName(key, candidates);
    out.push_back(u);
  }
}
}  // namespace

std::vector<UnknownKey> unknownKeys(const ParamValue& ns, const ParamReadLog& log, const std::string& scope,
                                    const std::vector<std::string>& known, const std::vector<std::string>& skip)
{
  std::vector<UnknownKey> out;
  if (ns.isMap()) walk(ns, log, "", scope, known, skip, out);
  return out;
}

std::string describeUnknownKey(const UnknownKey& key, const std::string& ns_name,
                               const std::vector<std::string>& plugins, const std::string& layer_class)
{
  std::string text = "parameter '" + key.path + "' in " + ns_name;
  if (!key.known_elsewhere.empty()) return text + " is ignored: " + key.known_elsewhere;
  if (key.is_namespace && key.path.find('/') == std::string::npos && !layer_class.empty())
  {
    const bool sources = layer_class == "ObstacleLayer" || layer_class == "VoxelLayer";
    text = "namespace '" + key.path + "' in " + ns_name + " is not read by this " + layer_class +
           (sources ? " (no observation source of that name)" : "") + ": its parameters are not used";
    if (!key.suggestion.empty()) text += " (did you mean `" + key.suggestion + "`?)";
    return text;
  }
  if (key.is_namespace && key.path.find('/') == std::string::npos)
  {
    std::string names;
    for (const auto& p : plugins)
      names += (names.empty() ? "" : ", ") + p;
    text = "namespace '" + key.path + "' in " + ns_name +
           " names no plugin of this costmap (plugins: " + (names.empty() ? "none" : names) +
           "): its parameters are not used";
    if (!key.suggestion.empty()) text += " (did you mean `" + key.suggestion + "`?)";
    return text;
  }
  text += " is not a parameter of costmap_layers and is ignored";
  if (!key.suggestion.empty()) text += " (did you mean `" + key.suggestion + "`?)";
  return text;
}

std::vector<std::string> unusedParameterLines(const CompatResult& compat, const ParamReadLog& log,
                                              const std::vector<std::pair<PluginSpec, const ParamValue*>>& layers,
                                              const std::string& ns_name)
{
  std::vector<std::string> lines, names;
  for (const auto& layer : layers)
    names.push_back(layer.first.name);
  for (const auto& u : unknownKeys(compat.params, log, "costmap", compat.consumed, names))
    lines.push_back(describeUnknownKey(u, ns_name, names));
  const std::string prefix = ns_name.empty() || ns_name.back() != '/' ? ns_name + "/" : ns_name;
  for (const auto& [spec, params] : layers)
  {
    std::vector<std::string> known = {"plugin"};
    const auto consumed = compat.layer_consumed.find(spec.name);
    if (consumed != compat.layer_consumed.end())
      known.insert(known.end(), consumed->second.begin(), consumed->second.end());
    const std::string scope = pluginClassName(resolvePluginType(spec.type));
    // A container's plugins ("<container>/<plugin>") read their namespaces themselves: walked as theirs.
    std::vector<std::string> held;
    for (const auto& other : layers)
      if (other.first.name.size() > spec.name.size() + 1 &&
          other.first.name.compare(0, spec.name.size() + 1, spec.name + "/") == 0 &&
          other.first.name.find('/', spec.name.size() + 1) == std::string::npos)
        held.push_back(other.first.name.substr(spec.name.size() + 1));
    for (const auto& u : unknownKeys(*params, log, scope, known, held))
      lines.push_back(describeUnknownKey(u, prefix + spec.name, {}, scope));
  }
  return lines;
}
}  // namespace costmap_layers
