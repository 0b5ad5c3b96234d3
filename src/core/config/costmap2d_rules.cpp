#include "costmap_layers/core/config/costmap2d_rules.hpp"

#include <algorithm>
#include <sstream>
#include <utility>

#include "costmap_layers/core/config/plugin_types.hpp"
#include "costmap_layers/core/costmap/costmap_config.hpp"

namespace costmap_layers
{
const std::vector<std::string>& searchedKeys()
{
  static const std::vector<std::string> keys = {"footprint", "robot_radius", "obstacle_range", "raytrace_range"};
  return keys;
}

const ParamValue* searchParam(const std::vector<const ParamValue*>& chain, const std::string& key, std::size_t* where)
{
  for (std::size_t k = 0; k < chain.size(); ++k)
  {
    if (chain[k] == nullptr) continue;
    if (const ParamValue* v = chain[k]->find(key))
    {
      if (where != nullptr) *where = k;
      return v;
    }
  }
  return nullptr;
}

namespace
{
std::vector<std::string> splitWords(const std::string& text)
{
  std::vector<std::string> words;
  std::istringstream in(text);
  std::string w;
  while (in >> w)
    words.push_back(w);
  return words;
}

/// The names in observation_sources: a space-separated string (costmap_2d) or a list of names.
std::vector<std::string> sourceNamesOf(const ParamValue* v)
{
  std::vector<std::string> names;
  if (v == nullptr) return names;
  if (v->type() == ParamValue::Type::String) return splitWords(v->asString());
  if (v->isList())
    for (const auto& item : v->asList())
      if (item.type() == ParamValue::Type::String) names.push_back(item.asString());
  return names;
}

ParamValue& subMap(ParamValue& ns, const std::string& name)
{
  ParamValue* sub = ns.findMutable(name);
  if (sub == nullptr || !sub->isMap()) return ns.set(name, ParamValue::makeMap());
  return *sub;
}

/// costmap_2d's move_parameter: the value of `key` in ns, when set, into ns/<layer>/<key>
/// (replacing what was there); with erase the costmap-level key goes away.
void moveParameter(ParamValue& ns, const std::string& layer, const std::string& key, bool erase, CompatResult& r,
                   const std::string& type = "")
{
  const ParamValue* v = ns.find(key);
  if (v == nullptr) return;
  const ParamValue value = *v;
  ParamValue& target = subMap(ns, layer);
  if (const ParamValue* old = target.find(key))
  {
    if (old->toString() != value.toString())
      r.warnings.push_back("'" + key + "' " + value.toString() + " of the costmap's namespace replaces '" + layer +
                           "/" + key + "' " + old->toString() + ", as costmap_2d copies it into " +
                           (type.empty() ? std::string("a layer of this type") : "a " + type) +
                           " (remove one of them)");
  }
  target.set(key, value);
  if (erase) ns.erase(key);
  if (std::find(r.consumed.begin(), r.consumed.end(), key) == r.consumed.end()) r.consumed.push_back(key);
}

ParamValue pluginEntry(const std::string& name, const std::string& type)
{
  ParamValue e = ParamValue::makeMap();
  e.set("name", ParamValue::makeString(name));
  e.set("type", ParamValue::makeString(type));
  return e;
}

void consume(CompatResult& r, const std::string& key)
{
  if (std::find(r.consumed.begin(), r.consumed.end(), key) == r.consumed.end()) r.consumed.push_back(key);
}

void loadOldParameters(CompatResult& r)
{
  ParamValue& ns = r.params;
  r.converted_pre_hydro = true;
  r.warnings.push_back(
      "parameter \"plugins\" not provided: loading the pre-Hydro parameters as costmap_2d does "
      "(static_map, map_type, observation_sources, ... become a static, an obstacle and an inflation layer)");
  ParamValue plugins = ParamValue::makeList();
  std::vector<std::string> layers;
  const ParamValue* static_map = ns.find("static_map");
  if (static_map != nullptr) consume(r, "static_map");
  if (static_map != nullptr && static_map->type() != ParamValue::Type::Bool)
    r.warnings.push_back("pre-Hydro parameter \"static_map\" is " + static_map->toString() +
                         ", not true or false: no static layer (costmap_2d reads it as a bool only, and skips it "
                         "as well)");
  if (static_map != nullptr && static_map->type() == ParamValue::Type::Bool && static_map->asBool())
  {
    plugins.push(pluginEntry("static_layer", "costmap_2d::StaticLayer"));
    layers.push_back("static_layer");
    subMap(ns, "static_layer");
    for (const char* key : {"map_topic", "unknown_cost_value", "lethal_cost_threshold"})
      moveParameter(ns, "static_layer", key, true, r);
    moveParameter(ns, "static_layer", "track_unknown_space", false, r);
  }
  const ParamValue* map_type = ns.find("map_type");
  if (map_type != nullptr) consume(r, "map_type");
  const bool voxel =
      map_type != nullptr && map_type->type() == ParamValue::Type::String && map_type->asString() == "voxel";
  if (map_type != nullptr && !voxel &&
      !(map_type->type() == ParamValue::Type::String && map_type->asString() == "costmap"))
    r.warnings.push_back("pre-Hydro parameter \"map_type\" is " + map_type->toString() +
                         ", neither \"voxel\" nor \"costmap\": an ObstacleLayer, as costmap_2d makes for any value "
                         "but \"voxel\"");
  plugins.push(pluginEntry("obstacle_layer", voxel ? "costmap_2d::VoxelLayer" : "costmap_2d::ObstacleLayer"));
  layers.push_back("obstacle_layer");
  subMap(ns, "obstacle_layer");
  if (voxel)
    for (const char* key :
         {"origin_z", "z_resolution", "z_voxels", "mark_threshold", "unknown_threshold", "publish_voxel_map"})
      moveParameter(ns, "obstacle_layer", key, true, r);
  for (const char* key : {"max_obstacle_height", "raytrace_range", "obstacle_range"})
    moveParameter(ns, "obstacle_layer", key, true, r);
  // costmap_2d moves it away, but its costmap has read its own track_unknown_space before: keep it.
  moveParameter(ns, "obstacle_layer", "track_unknown_space", false, r);
  for (const auto& source : sourceNamesOf(ns.find("observation_sources")))
    moveParameter(ns, "obstacle_layer", source, true, r);
  moveParameter(ns, "obstacle_layer", "observation_sources", true, r);
  subMap(ns, "inflation_layer");
  for (const char* key : {"cost_scaling_factor", "inflation_radius"})
    moveParameter(ns, "inflation_layer", key, true, r);
  plugins.push(pluginEntry("inflation_layer", "costmap_2d::InflationLayer"));
  layers.push_back("inflation_layer");
  ns.set("plugins", plugins);

  ParamValue shown = ParamValue::makeMap();
  shown.set("plugins", plugins);
  for (const auto& l : layers)
  {
    const ParamValue* sub = ns.find(l);
    if (sub != nullptr && !sub->entries().empty()) shown.set(l, *sub);
  }
  r.plugin_list = std::move(shown);
}

struct CopyRule
{
  const char* type;
  std::vector<const char*> keys;
};

/// A frame id written with tf's leading '/': stripped, with a warning naming `shown`.
void stripLeadingSlash(ParamValue& map, const std::string& key, const std::string& shown, CompatResult& r)
{
  ParamValue* v = map.findMutable(key);
  if (v == nullptr || v->type() != ParamValue::Type::String) return;
  const std::string written = v->asString();
  const std::size_t first = written.find_first_not_of('/');
  if (first == 0 || first == std::string::npos) return;  // no slash, or nothing but slashes (refused later)
  *v = ParamValue::makeString(written.substr(first));
  r.warnings.push_back(shown + " '" + written +
                       "': tf2 frame ids cannot start with '/' (tf stripped it; tf2, and "
                       "costmap_2d on it, find no such frame): using '" +
                       written.substr(first) + "'");
}

/// The sensor_frame of each observation source of the layer `name` in ns, without tf's leading '/'.
void stripSensorFrameSlashes(ParamValue& ns, const std::string& name, CompatResult& r)
{
  ParamValue* layer = ns.findMutable(name);
  if (layer == nullptr || !layer->isMap()) return;
  for (const auto& source : sourceNamesOf(layer->find("observation_sources")))
    if (ParamValue* src = layer->findMutable(source); src != nullptr && src->isMap())
      stripLeadingSlash(*src, "sensor_frame", name + "/" + source + "/sensor_frame", r);
}
}  // namespace

bool givesPolygon(const ParamValue& footprint)
{
  if (footprint.isList()) return !footprint.asList().empty();
  if (footprint.type() != ParamValue::Type::String) return false;
  std::string text;
  for (const char c : footprint.asString())
    if (c != ' ' && c != '\t') text += c;
  return !text.empty() && text != "[]";
}

namespace
{
/// The namespace of an obstacle or voxel layer typed in costmap_2d's or Nav2's names, or nullptr.
ParamValue* foreignObstacleLayer(ParamValue& ns, const PluginSpec& spec)
{
  const std::string cls = pluginClassName(resolvePluginType(spec.type));
  if (typeDialect(spec.type) == TypeDialect::Native || (cls != "ObstacleLayer" && cls != "VoxelLayer")) return nullptr;
  ParamValue* layer = ns.findMutable(spec.name);
  return layer != nullptr && layer->isMap() ? layer : nullptr;
}

/// Where costmap_2d's or Nav2's obstacle layers read a value differently from this package's: the
/// translation into this package's terms, said.
///  - combination_method: costmap_2d's layers write nothing for any value but 0 and 1 (its documented
///    99, "Do nothing"); Nav2's use 1 for any value but 0, 1 and 2 (with a warning).
///  - min_obstacle_height (the layer's): Nav2's default 0.0 for nav2_costmap_2d:: types, where it is not
///    set (costmap_2d has no such limit).
///  (An observation source without data_type: defaultSourceDataType().)
void translateObstacleDefaults(ParamValue& ns, const PluginSpec& spec, CompatResult& r)
{
  ParamValue* layer = foreignObstacleLayer(ns, spec);
  if (layer == nullptr) return;
  const TypeDialect dialect = typeDialect(spec.type);
  const std::string cls = pluginClassName(resolvePluginType(spec.type));
  if (ParamValue* cm = layer->findMutable("combination_method"); cm != nullptr && cm->type() == ParamValue::Type::Int)
  {
    const int64_t v = cm->asInt();
    if (dialect == TypeDialect::Costmap2D && v != 0 && v != 1 && v != 99)
    {
      r.warnings.push_back(spec.name + "/combination_method " + std::to_string(v) + ": " + spec.type +
                           " writes nothing into the costmap for any value but 0 and 1 (costmap_2d's 99, \"Do "
                           "nothing\"): taken as 99. (2 is Nav2's maximum that keeps unknown cells unknown: write "
                           "the type as costmap_layers/" +
                           cls + " or nav2_costmap_2d::" + cls + " for that)");
      *cm = ParamValue::makeInt(99);
    }
    else if (dialect == TypeDialect::Nav2 && (v < 0 || v > 2))
    {
      r.warnings.push_back(spec.name + "/combination_method " + std::to_string(v) + ": " + spec.type +
                           " takes 0, 1 or 2, and uses 1 (maximum) for any other value, as Nav2 does");
      *cm = ParamValue::makeInt(1);
    }
  }
  if (dialect != TypeDialect::Nav2) return;
  // Nav2's layers drop hits below their own min_obstacle_height, 0.0 unless set (costmap_2d's have no
  // such limit, nor has this package's own type unless it is set).
  if (layer->find("min_obstacle_height") == nullptr)
  {
    layer->set("min_obstacle_height", ParamValue::makeDouble(0.0));
    r.notes.push_back(spec.name + ": min_obstacle_height not set: 0.0 m, Nav2's default (hits below are not marked)");
  }
  for (const auto& source : sourceNamesOf(layer->find("observation_sources")))
  {
    ParamValue& src = subMap(*layer, source);
    if (src.find("max_obstacle_height") == nullptr)
      r.notes.push_back(spec.name + "/" + source +
                        ": max_obstacle_height not set: 2.0 m, costmap_2d's default (Nav2's is 0.0, which keeps no "
                        "point above the ground: set it to be sure)");
  }
}

/// An observation source without data_type reads what the stack the type name comes from reads:
/// costmap_2d's PointCloud (sensor_msgs/PointCloud), Nav2's LaserScan (this package's own default is
/// PointCloud2).
void defaultSourceDataType(ParamValue& ns, const PluginSpec& spec, CompatResult& r)
{
  ParamValue* layer = foreignObstacleLayer(ns, spec);
  if (layer == nullptr) return;
  const TypeDialect dialect = typeDialect(spec.type);
  const char* type = dialect == TypeDialect::Nav2 ? "LaserScan" : "PointCloud";
  for (const auto& source : sourceNamesOf(layer->find("observation_sources")))
  {
    ParamValue& src = subMap(*layer, source);
    if (src.find("data_type") != nullptr) continue;
    src.set("data_type", ParamValue::makeString(type));
    r.notes.push_back(spec.name + "/" + source + ": data_type not set: " + type + ", " +
                      (dialect == TypeDialect::Nav2 ? "Nav2's" : "costmap_2d's") + " default");
  }
}

/// costmap_2d's copyParentParameters, by the type name exactly as written.
const std::vector<CopyRule>& copyRules()
{
  static const std::vector<CopyRule> rules = {
      {"costmap_2d::StaticLayer", {"map_topic", "unknown_cost_value", "lethal_cost_threshold", "track_unknown_space"}},
      {"costmap_2d::VoxelLayer",
       {"origin_z", "z_resolution", "z_voxels", "mark_threshold", "unknown_threshold", "publish_voxel_map"}},
      {"costmap_2d::ObstacleLayer", {"max_obstacle_height", "raytrace_range", "obstacle_range", "track_unknown_space"}},
      {"costmap_2d::InflationLayer", {"cost_scaling_factor", "inflation_radius"}},
  };
  return rules;
}

/// costmap_2d's copyParentParameters for one plugin, by its type name exactly as written, and the
/// default costmap_2d's StaticLayer has where this package's differs (track_unknown_space true).
void copyParentParameters(ParamValue& ns, const PluginSpec& spec, CompatResult& r)
{
  for (const auto& rule : copyRules())
    if (spec.type == rule.type)
      for (const char* key : rule.keys)
        moveParameter(ns, spec.name, key, false, r, spec.type);
  if (spec.type == "costmap_2d::StaticLayer")
  {
    ParamValue& layer = subMap(ns, spec.name);
    if (layer.find("track_unknown_space") == nullptr)
    {
      layer.set("track_unknown_space", ParamValue::makeBool(true));
      r.notes.push_back(spec.name + ": track_unknown_space not set: true, costmap_2d's StaticLayer default");
    }
  }
}

/// costmap_2d's ObstacleLayer looks up obstacle_range and raytrace_range with searchParam from each
/// observation source's namespace: the source, the layer, the costmap, then its parents.
void searchSourceRanges(ParamValue& ns, const PluginSpec& spec, const std::vector<ParentNamespace>& parents,
                        CompatResult& r)
{
  const std::string cls = pluginClassName(resolvePluginType(spec.type));
  if ((cls != "ObstacleLayer" && cls != "VoxelLayer") || typeDialect(spec.type) == TypeDialect::Nav2) return;
  const ParamValue* layer_ro = ns.find(spec.name);
  if (layer_ro == nullptr) return;
  std::vector<const ParamValue*> parent_chain;
  for (const auto& p : parents)
    parent_chain.push_back(&p.values);
  const std::vector<std::string> sources = sourceNamesOf(layer_ro->find("observation_sources"));
  for (const char* key : {"obstacle_range", "raytrace_range"})
    if (layer_ro->find(key) != nullptr) r.layer_consumed[spec.name].push_back(key);
  for (const auto& source : sources)
  {
    for (const auto& [key, nav2_name] : {std::pair<std::string, std::string>{"obstacle_range", "obstacle_max_range"},
                                         {"raytrace_range", "raytrace_max_range"}})
    {
      const ParamValue* layer = ns.find(spec.name);
      const ParamValue* src = layer->find(source);
      if (src != nullptr && (src->find(key) != nullptr || src->find(nav2_name) != nullptr)) continue;
      std::vector<const ParamValue*> chain = {layer, &ns};
      chain.insert(chain.end(), parent_chain.begin(), parent_chain.end());
      std::size_t at = 0;
      const ParamValue* v = searchParam(chain, key, &at);
      if (v == nullptr) continue;
      const ParamValue value = *v;
      if (at == 1) consume(r, key);
      ParamValue& src_map = subMap(subMap(ns, spec.name), source);
      src_map.set(key, value);
      const std::string found_in = at == 0 ? spec.name : at == 1 ? "the costmap's namespace" : parents[at - 2].name;
      r.notes.push_back(spec.name + "/" + source + ": " + key + " " + value.toString() + " found in " + found_in +
                        " (costmap_2d looks it up with searchParam)");
    }
  }
}
}  // namespace

CompatResult applyCostmap2dRules(const ParamValue& ns_in, const std::vector<ParentNamespace>& parents)
{
  CompatResult r;
  r.params = ns_in.isMap() ? ns_in : ParamValue::makeMap();
  ParamValue& ns = r.params;

  // 1. Pre-Hydro parameters.
  if (ns.find("plugins") == nullptr && ns.find("plugin_names") == nullptr)
  {
    loadOldParameters(r);
  }
  else
  {
    for (const char* key : {"static_map", "map_type"})
    {
      if (ns.find(key) == nullptr) continue;
      r.warnings.push_back(std::string("pre-Hydro parameter \"") + key +
                           "\" unused since \"plugins\" is provided (as in costmap_2d)");
      consume(r, key);
    }
  }
  const PluginLists lists = parsePluginLists(ns);

  // tf took "/map"; tf2 refuses frame ids with a leading '/', so that costmap_2d on tf2 waits forever
  // for such a frame: the name without it, said once.
  for (const char* key : {"global_frame", "robot_base_frame"})
    stripLeadingSlash(ns, key, key, r);
  for (const auto& spec : lists.plugins)
    stripSensorFrameSlashes(ns, spec.name, r);

  // 2. copyParentParameters, 3. costmap_2d's own defaults.
  for (const auto& spec : lists.plugins)
  {
    translateObstacleDefaults(ns, spec, r);
    defaultSourceDataType(ns, spec, r);
    copyParentParameters(ns, spec, r);
    // Nav2's StaticLayer reads these at the costmap level only (node->get_parameter), not in its own
    // namespace: the costmap's value is the one it uses.
    if (spec.type == "nav2_costmap_2d::StaticLayer")
    {
      for (const char* key :
           {"lethal_cost_threshold", "unknown_cost_value", "trinary_costmap", "use_maximum", "track_unknown_space"})
      {
        const ParamValue* v = ns.find(key);
        if (v == nullptr) continue;
        const ParamValue value = *v;
        ParamValue& layer = subMap(ns, spec.name);
        const ParamValue* own = layer.find(key);
        if (own != nullptr && own->toString() != value.toString())
          r.warnings.push_back("'" + spec.name + "/" + key + "' " + own->toString() + " is replaced by the costmap's " +
                               value.toString() + ": Nav2's StaticLayer reads " + key +
                               " at the costmap level only (remove one of them)");
        else if (own == nullptr && std::string(key) != "track_unknown_space")
          r.notes.push_back(spec.name + ": " + key + " " + value.toString() +
                            " taken from the costmap's namespace, where Nav2's StaticLayer reads it");
        layer.set(key, value);
        consume(r, key);
      }
    }
  }

  // 4. searchParam.
  std::vector<const ParamValue*> parent_chain;
  for (const auto& p : parents)
    parent_chain.push_back(&p.values);
  for (const char* key : {"footprint", "robot_radius"})
  {
    if (ns.find(key) != nullptr) continue;
    std::size_t at = 0;
    if (const ParamValue* v = searchParam(parent_chain, key, &at))
    {
      const ParamValue value = *v;
      ns.set(key, value);
      r.notes.push_back(std::string(key) + " " + value.toString() + " found in " + parents[at].name +
                        " (costmap_2d looks it up with searchParam)");
    }
  }
  for (const auto& spec : lists.plugins)
    searchSourceRanges(ns, spec, parents, r);
  // costmap_2d's makeFootprintFromParams takes a footprint given as a polygon over robot_radius.
  const ParamValue* footprint = ns.find("footprint");
  const ParamValue* radius = ns.find("robot_radius");
  if (footprint != nullptr && radius != nullptr && givesPolygon(*footprint))
    r.notes.push_back("robot_radius " + radius->toString() +
                      " is not used: footprint is set too, and the footprint wins (as in costmap_2d)");
  // costmap_2d refuses every pose not stamped exactly now with 0 (a costmap that never updates); here 0
  // leaves the age unchecked. Either way not what a user means by 0.
  const ParamValue* tolerance = ns.find("transform_tolerance");
  if (tolerance != nullptr && tolerance->isNumber() && tolerance->asDouble() == 0.0)
    r.warnings.push_back(
        "transform_tolerance 0: the robot's transform is used however old it is (costmap_2d "
        "would refuse every transform not stamped exactly now); set the age you accept, e.g. 0.3");
  return r;
}

CompatResult applyCostmap2dRulesAsRole(const ParamValue& ns_in, const std::string& name, const std::string& role_type,
                                       const std::vector<ParentNamespace>& parents)
{
  CompatResult r;
  r.params = ns_in.isMap() ? ns_in : ParamValue::makeMap();
  const PluginSpec spec{name, role_type};
  stripSensorFrameSlashes(r.params, name, r);
  defaultSourceDataType(r.params, spec, r);
  copyParentParameters(r.params, spec, r);
  searchSourceRanges(r.params, spec, parents, r);
  return r;
}
}  // namespace costmap_layers
