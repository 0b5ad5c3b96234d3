#include "costmap_layers/core/costmap/costmap_builder.hpp"

#include <stdexcept>

namespace costmap_layers
{
void loadPlugins(LayeredCostmap& costmap, const PluginLists& lists, const LayerFactory& factory,
                 const ContextFactory& contexts)
{
  auto load = [&](const PluginSpec& spec, bool is_filter)
  {
    std::shared_ptr<Layer> layer;
    try
    {
      layer = factory(spec.type);
    }
    catch (const std::exception& e)
    {
      throw std::runtime_error("plugin '" + spec.name + "': " + e.what());
    }
    if (!layer) throw std::runtime_error("plugin '" + spec.name + "' of type " + spec.type + " could not be created");
    try
    {
      layer->initialize(&costmap, spec.name, contexts(spec));
    }
    catch (const std::exception& e)
    {
      throw std::invalid_argument("plugin '" + spec.name + "' (" + spec.type + "): " + e.what());
    }
    if (is_filter)
      costmap.addFilter(layer);
    else
      costmap.addPlugin(layer);
    layer->matchSize();
  };
  for (const auto& spec : lists.plugins)
    load(spec, false);
  for (const auto& spec : lists.filters)
    load(spec, true);
}
}  // namespace costmap_layers
