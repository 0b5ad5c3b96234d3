#include "costmap_layers/core/costmap/costmap_builder.hpp"

#include <stdexcept>

#include "costmap_layers/core/layers/plugin_container_layer.hpp"

namespace costmap_layers
{
std::shared_ptr<Layer> makeLayer(LayeredCostmap& costmap, const PluginSpec& spec, const LayerMaker& maker, int depth)
{
  std::shared_ptr<Layer> layer;
  try
  {
    layer = maker.layers(spec.type);
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error("plugin '" + spec.name + "': " + e.what());
  }
  if (!layer) throw std::runtime_error("plugin '" + spec.name + "' of type " + spec.type + " could not be created");
  // A container makes its plugins as the costmap makes its own: the same factories, one level deeper.
  if (auto* container = dynamic_cast<PluginContainerLayer*>(layer.get())) container->setMaker(maker, depth + 1);
  try
  {
    layer->initialize(&costmap, spec.name, maker.contexts(spec));
  }
  catch (const std::exception& e)
  {
    throw std::invalid_argument("plugin '" + spec.name + "' (" + spec.type + "): " + e.what());
  }
  return layer;
}

void loadPlugins(LayeredCostmap& costmap, const PluginLists& lists, const LayerFactory& factory,
                 const ContextFactory& contexts)
{
  LayerMaker maker{factory, contexts};
  *maker.listed = lists.plugins.size() + lists.filters.size();
  auto load = [&](const PluginSpec& spec, bool is_filter)
  {
    std::shared_ptr<Layer> layer = makeLayer(costmap, spec, maker, 0);
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
