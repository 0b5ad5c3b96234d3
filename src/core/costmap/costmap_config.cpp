#include "costmap_layers/core/costmap/costmap_config.hpp"

#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/rules/limits.hpp"

namespace costmap_layers
{
namespace
{
constexpr double kMaxCellsPerSide = 100000.0;

/// A loop frequency [Hz] that may be off: 0 or in [kMinFrequency, kMaxFrequency], so that
/// 1 / frequency is a period ros::Duration and the loop can hold.
double getFrequency(const ParamReader& p, const std::string& name, double def)
{
  const double f = p.getDouble(name, def, 0.0, limits::kMaxFrequency);
  if (f != 0.0 && f < limits::kMinFrequency)
  {
    std::ostringstream what;
    what << "must be 0 (off) or in [" << limits::kMinFrequency << ", " << limits::kMaxFrequency << "] Hz";
    p.fail(name, what.str());
  }
  return f;
}
}  // namespace

unsigned int CostmapConfig::sizeInCellsX() const
{
  return static_cast<unsigned int>(std::max(1.0, std::round(width / resolution)));
}

unsigned int CostmapConfig::sizeInCellsY() const
{
  return static_cast<unsigned int>(std::max(1.0, std::round(height / resolution)));
}

CostmapConfig parseCostmapConfig(const ParamValue& ns)
{
  const ParamReader p(ns, "costmap");
  CostmapConfig c;
  c.global_frame = p.getFrameId("global_frame", c.global_frame);
  c.robot_base_frame = p.getFrameId("robot_base_frame", c.robot_base_frame);
  c.transform_tolerance = p.getDouble("transform_tolerance", c.transform_tolerance, 0.0, limits::kMaxDuration);
  // The update loop always runs (the node refuses 0): at least kMinFrequency.
  c.update_frequency =
      p.getDouble("update_frequency", c.update_frequency, limits::kMinFrequency, limits::kMaxFrequency);
  c.publish_frequency = getFrequency(p, "publish_frequency", c.publish_frequency);
  c.resolution = p.getDouble("resolution", c.resolution, limits::kMinResolution, limits::kMaxResolution);
  c.width = p.getDouble("width", c.width, c.resolution, kMaxCellsPerSide * c.resolution);
  c.height = p.getDouble("height", c.height, c.resolution, kMaxCellsPerSide * c.resolution);
  if (static_cast<uint64_t>(c.sizeInCellsX()) * c.sizeInCellsY() > limits::kMaxGridCells)
  {
    std::ostringstream what;
    what << "makes " << c.sizeInCellsX() << " x " << c.sizeInCellsY() << " cells with 'width' " << c.width
         << " m at 'resolution' " << c.resolution << " m/cell, more than the limit of " << limits::kMaxGridCells;
    p.fail("height", what.str());
  }
  c.origin_x = p.getDouble("origin_x", c.origin_x, -limits::kMaxCoordinate, limits::kMaxCoordinate);
  c.origin_y = p.getDouble("origin_y", c.origin_y, -limits::kMaxCoordinate, limits::kMaxCoordinate);
  c.rolling_window = p.getBool("rolling_window", c.rolling_window);
  c.track_unknown_space = p.getBool("track_unknown_space", c.track_unknown_space);
  c.always_send_full_costmap = p.getBool("always_send_full_costmap", c.always_send_full_costmap);
  c.reset_distance = p.getDouble("reset_distance", c.reset_distance, 0.0, limits::kMaxDistance);
  c.footprint = parseFootprintConfig(p);
  return c;
}

namespace
{
std::string typeOfNamed(const ParamValue& ns, const std::string& list_key, const std::string& name,
                        const std::string& owner)
{
  const ParamValue* sub = ns.find(name);
  const ParamValue* type = sub != nullptr ? sub->find("plugin") : nullptr;
  if (type == nullptr && sub != nullptr) type = sub->find("type");
  if (type == nullptr || type->type() != ParamValue::Type::String)
    throw std::invalid_argument(owner + ": " + list_key + " names '" + shownText(name) + "' but '" + shownText(name) +
                                "/plugin' (its type) is not set");
  return type->asString();
}

void checkPluginCount(const std::string& key, std::size_t count, const std::string& owner = "costmap")
{
  if (count > limits::kMaxPlugins)
    throw std::invalid_argument(owner + ": '" + key + "' lists " + std::to_string(count) + " plugins, more than " +
                                std::to_string(limits::kMaxPlugins) +
                                ": a costmap has a handful (a repeated YAML alias or a generated list?)");
}

std::vector<PluginSpec> parseOneList(const ParamValue& ns, const std::string& key, const std::string& owner = "costmap")
{
  std::vector<PluginSpec> specs;
  const ParamValue* list = ns.find(key);
  const std::string names_key = key == "plugins" ? "plugin_names" : "filter_names";
  const std::string types_key = key == "plugins" ? "plugin_types" : "filter_types";
  const ParamValue* names = ns.find(names_key);
  const ParamValue* types = ns.find(types_key);
  if (list != nullptr && !list->isNull())
  {
    if (!list->isList())
      throw std::invalid_argument(owner + ": parameter '" + key + "' must be a list (got " +
                                  shownText(list->toString(), 200) + ")");
    checkPluginCount(key, list->asList().size(), owner);
    for (const auto& item : list->asList())
    {
      if (item.isMap())
      {
        const ParamValue* name = item.find("name");
        const ParamValue* type = item.find("type");
        if (type == nullptr) type = item.find("plugin");
        if (name == nullptr || name->type() != ParamValue::Type::String || type == nullptr ||
            type->type() != ParamValue::Type::String)
          throw std::invalid_argument(owner + ": each entry of '" + key + "' needs string fields name and type (got " +
                                      item.toString() + ")");
        specs.push_back({name->asString(), type->asString()});
      }
      else if (item.type() == ParamValue::Type::String)
      {
        specs.push_back({item.asString(), typeOfNamed(ns, key, item.asString(), owner)});
      }
      else
      {
        throw std::invalid_argument(owner + ": entries of '" + key + "' must be {name, type} maps or names (got " +
                                    shownText(item.toString(), 200) + ")");
      }
    }
  }
  else if (names != nullptr || types != nullptr)
  {
    if (names == nullptr || types == nullptr || !names->isList() || !types->isList())
      throw std::invalid_argument(owner + ": '" + names_key + "' and '" + types_key + "' must both be lists");
    checkPluginCount(names_key, names->asList().size(), owner);
    if (names->asList().size() != types->asList().size())
      throw std::invalid_argument(owner + ": '" + names_key + "' has " + std::to_string(names->asList().size()) +
                                  " entries but '" + types_key + "' has " + std::to_string(types->asList().size()));
    for (std::size_t k = 0; k < names->asList().size(); ++k)
    {
      const ParamValue& n = names->asList()[k];
      const ParamValue& t = types->asList()[k];
      if (n.type() != ParamValue::Type::String || t.type() != ParamValue::Type::String)
        throw std::invalid_argument(owner + ": '" + names_key + "' and '" + types_key + "' must hold strings");
      specs.push_back({n.asString(), t.asString()});
    }
  }
  for (const auto& s : specs)
  {
    // The rule costmap_node's NodeHandles and costmap_2d apply to a plugin's namespace, here where
    // costmap_tool reads the same list: a name one of them refuses is refused by both.
    if (const std::string problem = pluginNameProblem(s.name); !problem.empty())
      throw std::invalid_argument(owner + ": a plugin in '" + key + "' has a bad name: " + problem);
    if (s.type.empty()) throw std::invalid_argument(owner + ": plugin '" + s.name + "' has an empty type");
  }
  return specs;
}
}  // namespace

PluginLists parsePluginLists(const ParamValue& ns)
{
  PluginLists lists;
  const ParamReader p(ns, "costmap");
  p.declare("plugins", "[{name: <name>, type: <type>}, ...] (or Nav2's forms), at most 64 with filters",
            "none");
  p.declare("filters", "the same, applied after the plugins", "none");
  lists.plugins = parseOneList(ns, "plugins");
  lists.filters = parseOneList(ns, "filters");
  checkPluginCount("plugins' and 'filters", lists.plugins.size() + lists.filters.size());
  std::set<std::string> seen;
  for (const auto* l : {&lists.plugins, &lists.filters})
  {
    for (const auto& s : *l)
    {
      if (!seen.insert(s.name).second)
        throw std::invalid_argument("costmap: plugin name '" + shownText(s.name) +
                                    "' is used twice; each instance needs its "
                                    "own name (and parameter namespace)");
    }
  }
  return lists;
}

std::vector<PluginSpec> parsePluginList(const ParamValue& ns, const std::string& owner)
{
  const ParamReader p(ns, owner);
  p.declare("plugins", "[names] with <name>: {plugin: <type>} (or the other forms of the costmap's list)", "none");
  std::vector<PluginSpec> specs = parseOneList(ns, "plugins", owner);
  std::set<std::string> seen;
  for (const auto& s : specs)
    if (!seen.insert(s.name).second)
      throw std::invalid_argument(owner + ": plugin name '" + shownText(s.name) + "' is used twice in 'plugins'");
  return specs;
}

const ParamValue* pluginParams(const ParamValue& ns, const std::string& name)
{
  const ParamValue* own = ns.find(name);
  return own != nullptr ? own : ns.findPath(name);
}
}  // namespace costmap_layers
