#include "costmap_layers/core/config/config_compat.hpp"

#include <algorithm>
#include <charconv>
#include <map>
#include <set>
#include <sstream>

#include "costmap_layers/core/costmap/costmap_config.hpp"

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
  r.plugin_list_yaml = toYaml(shown);
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

/// Whether a footprint value is a polygon (not empty, not "[]"), i.e. one robot_radius yields to.
bool givesPolygon(const ParamValue& footprint)
{
  if (footprint.isList()) return !footprint.asList().empty();
  if (footprint.type() != ParamValue::Type::String) return false;
  std::string text;
  for (const char c : footprint.asString())
    if (c != ' ' && c != '\t') text += c;
  return !text.empty() && text != "[]";
}

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

std::string costmap2dRole(const std::string& class_name)
{
  for (const auto& a : pluginTypeAliases())
    if (a.dialect == TypeDialect::Costmap2D && pluginClassName(a.ours) == class_name) return a.written;
  return "";
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

namespace
{
void mergeInto(ParamValue& target, const ParamValue& source)
{
  for (const auto& [key, value] : source.entries())
  {
    ParamValue* existing = target.findMutable(key);
    if (existing != nullptr && existing->isMap() && value.isMap())
      mergeInto(*existing, value);
    else
      target.set(key, value);
  }
}

bool namesPlugin(const ParamValue& ns, const std::string& name)
{
  for (const char* key : {"plugins", "filters", "plugin_names", "filter_names"})
  {
    const ParamValue* list = ns.find(key);
    if (list == nullptr || !list->isList()) continue;
    for (const auto& item : list->asList())
    {
      if (item.type() == ParamValue::Type::String && item.asString() == name) return true;
      const ParamValue* n = item.find("name");
      if (n != nullptr && n->type() == ParamValue::Type::String && n->asString() == name) return true;
    }
  }
  return false;
}
}  // namespace

bool liftOwnNamespace(ParamValue& ns, const std::string& own_name)
{
  const ParamValue* nested = ns.find(own_name);
  if (nested == nullptr || !nested->isMap() || namesPlugin(ns, own_name)) return false;
  const ParamValue copy = *nested;
  ns.erase(own_name);
  mergeInto(ns, copy);
  return true;
}

namespace
{
std::string yamlScalar(const ParamValue& v)
{
  switch (v.type())
  {
    case ParamValue::Type::Null:
      return "null";
    case ParamValue::Type::Bool:
      return v.asBool() ? "true" : "false";
    case ParamValue::Type::Int:
      return std::to_string(v.asInt());
    case ParamValue::Type::Double:
    {
      char buf[64];
      const auto res = std::to_chars(buf, buf + sizeof(buf), v.asDouble());
      std::string s(buf, res.ptr);
      if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // stays a double when read back
      return s;
    }
    case ParamValue::Type::String:
    {
      std::string out = "\"";
      for (char c : v.asString())
      {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
      }
      return out + "\"";
    }
    default:
      return "";
  }
}

std::string yamlFlow(const ParamValue& v)
{
  if (v.isList())
  {
    std::string out = "[";
    for (std::size_t k = 0; k < v.asList().size(); ++k)
      out += (k ? ", " : "") + yamlFlow(v.asList()[k]);
    return out + "]";
  }
  if (v.isMap())
  {
    std::string out = "{";
    bool first = true;
    for (const auto& [key, value] : v.entries())
    {
      out += (first ? "" : ", ") + key + ": " + yamlFlow(value);
      first = false;
    }
    return out + "}";
  }
  return yamlScalar(v);
}
}  // namespace

std::string toYaml(const ParamValue& value, int indent)
{
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  std::string out;
  if (!value.isMap()) return pad + yamlFlow(value) + "\n";
  for (const auto& [key, v] : value.entries())
  {
    if (v.isMap() && !v.entries().empty())
    {
      out += pad + key + ":\n" + toYaml(v, indent + 2);
    }
    else if (v.isList() &&
             std::any_of(v.asList().begin(), v.asList().end(), [](const ParamValue& i) { return i.isMap(); }))
    {
      out += pad + key + ":\n";
      for (const auto& item : v.asList())
        out += pad + "  - " + yamlFlow(item) + "\n";
    }
    else
    {
      out += pad + key + ": " + yamlFlow(v) + "\n";
    }
  }
  return out;
}

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
namespace
{
/// The components of a namespace path ("a//b/" -> a, b).
std::vector<std::string> pathParts(const std::string& path)
{
  std::vector<std::string> parts;
  std::string part;
  for (const char c : path + "/")
  {
    if (c != '/')
    {
      part += c;
      continue;
    }
    if (!part.empty()) parts.push_back(part);
    part.clear();
  }
  return parts;
}

/// costmap_2d reads the plugin named "a/b" from the namespace a/b, which a parameter tree holds nested
/// (a: {b: {...}}): that map moves to the key "a/b", where everything here looks a plugin's parameters
/// up; maps left empty on the way go too.
void hoistNestedPluginNamespace(ParamValue& ns, const std::string& name)
{
  if (name.find('/') == std::string::npos || ns.find(name) != nullptr) return;
  const ParamValue* nested = ns.findPath(name);
  if (nested == nullptr || !nested->isMap()) return;
  const ParamValue copy = *nested;
  const std::vector<std::string> parts = pathParts(name);
  // Erase the leaf, then each ancestor it leaves empty.
  for (std::size_t depth = parts.size(); depth-- > 0;)
  {
    ParamValue* parent = &ns;
    for (std::size_t k = 0; k < depth && parent != nullptr; ++k)
      parent = parent->findMutable(parts[k]);
    if (parent == nullptr) break;
    const ParamValue* child = parent->find(parts[depth]);
    if (depth + 1 < parts.size() && (child == nullptr || !child->isMap() || !child->entries().empty())) break;
    parent->erase(parts[depth]);
  }
  ns.set(name, copy);
}
}  // namespace

namespace
{
/// A Nav2 file (ROS 2's ros__parameters level) reads Nav2's Costmap2DROS defaults where they differ from
/// costmap_2d's, which are this package's: each one taken is said.
void nav2CostmapDefaults(CompatResult& r)
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
}  // namespace

CompatResult prepareCostmapNamespace(ParamValue ns, const std::string& own_name,
                                     const std::vector<ParentNamespace>& parents)
{
  const bool lifted = !own_name.empty() && liftOwnNamespace(ns, own_name);
  // A Nav2 file keeps its parameters one level down, under ros__parameters (ROS 2's form); or the
  // namespace named is that level itself (costmap_tool --namespace local_costmap/local_costmap/ros__parameters).
  const bool named_level = own_name == "ros__parameters";
  const bool ros2 = liftOwnNamespace(ns, "ros__parameters") || named_level;
  {
    const PluginLists named = parsePluginLists(ns);
    for (const auto* list : {&named.plugins, &named.filters})
      for (const auto& spec : *list)
        hoistNestedPluginNamespace(ns, spec.name);
  }
  CompatResult r = applyCostmap2dRules(ns, parents);
  if (ros2) nav2CostmapDefaults(r);
  if (ros2 && !named_level)
  {
    r.warnings.insert(r.warnings.begin(),
                      "this namespace holds ROS 2's `ros__parameters:` level (a Nav2 file): its parameters apply "
                      "to this costmap; remove that level from the file for ROS 1");
  }
  if (lifted)
    r.notes.insert(r.notes.begin(), "this namespace holds a move_base file's `" + own_name +
                                        ":` section: its parameters apply to this costmap");
  const PluginLists lists = parsePluginLists(r.params);
  if (lists.plugins.empty() && lists.filters.empty())
    r.warnings.push_back("no plugins and no filters: the costmap has no layer and stays as it starts (all " +
                         std::string("free, or unknown with track_unknown_space)"));
  return r;
}

std::vector<ParentNamespace> parentsInTree(const ParamValue& root, const std::string& path)
{
  const std::vector<std::string> parts = pathParts(path);
  std::vector<ParentNamespace> parents;
  for (std::size_t depth = parts.size(); depth-- > 0;)
  {
    std::string name;
    for (std::size_t k = 0; k < depth; ++k)
      name += "/" + parts[k];
    const ParamValue* at = depth == 0 ? &root : root.findPath(name.substr(1));
    ParentNamespace parent{name.empty() ? "/" : name, ParamValue::makeMap()};
    if (at != nullptr && at->isMap())
      for (const auto& key : searchedKeys())
        if (const ParamValue* v = at->find(key)) parent.values.set(key, *v);
    parents.push_back(std::move(parent));
  }
  return parents;
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
    for (const auto& u : unknownKeys(*params, log, scope, known))
      lines.push_back(describeUnknownKey(u, prefix + spec.name, {}, scope));
  }
  return lines;
}
}  // namespace costmap_layers
