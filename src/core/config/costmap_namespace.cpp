#include "costmap_layers/core/config/costmap_namespace.hpp"

#include "costmap_layers/core/config/nav2_defaults.hpp"
#include "costmap_layers/core/costmap/costmap_config.hpp"

namespace costmap_layers
{
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
  if (ros2) applyNav2CostmapDefaults(r);
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
}  // namespace costmap_layers
