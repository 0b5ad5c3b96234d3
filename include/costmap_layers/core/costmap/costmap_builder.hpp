// Builds a LayeredCostmap's layers from the plugin lists, the same way in the node and in the tool.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "costmap_layers/core/costmap/costmap_config.hpp"
#include "costmap_layers/core/costmap/layer.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"

namespace costmap_layers
{
/// Creates a layer of a pluginlib type; throws std::runtime_error for an unknown type.
using LayerFactory = std::function<std::shared_ptr<Layer>(const std::string& type)>;
/// Makes the context (parameters, inputs, outputs) of one plugin instance.
using ContextFactory = std::function<std::shared_ptr<LayerContext>(const PluginSpec& spec)>;

/// Creates, initializes and adds every plugin and filter in order. Throws (std::runtime_error or
/// std::invalid_argument) with the plugin's name and type on the first failure.
void loadPlugins(LayeredCostmap& costmap, const PluginLists& lists, const LayerFactory& factory,
                 const ContextFactory& contexts);
}  // namespace costmap_layers
