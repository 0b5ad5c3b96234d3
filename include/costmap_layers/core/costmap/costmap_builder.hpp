// Builds a LayeredCostmap's layers from the plugin lists, the same way in the node and in the tool.
#pragma once

#include <cstddef>
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

/// The host's ways of making layers, shared by the costmap's lists and by the lists of layers that hold
/// layers (PluginContainerLayer), so that both follow one rule.
struct LayerMaker
{
  LayerFactory layers;
  ContextFactory contexts;
  /// Layers listed so far in this costmap, containers' plugins included: at most limits::kMaxPlugins.
  std::shared_ptr<std::size_t> listed = std::make_shared<std::size_t>(0);
};

/// Creates the layer `spec` names and initialises it in costmap, without adding it: loadPlugins' step
/// for one plugin. A PluginContainerLayer gets `maker` for its own plugins, one level deeper than
/// `depth` (0: the costmap's lists). Throws naming the plugin and its type.
std::shared_ptr<Layer> makeLayer(LayeredCostmap& costmap, const PluginSpec& spec, const LayerMaker& maker, int depth);

/// Creates, initializes and adds every plugin and filter in order. Throws (std::runtime_error or
/// std::invalid_argument) with the plugin's name and type on the first failure.
void loadPlugins(LayeredCostmap& costmap, const PluginLists& lists, const LayerFactory& factory,
                 const ContextFactory& contexts);
}  // namespace costmap_layers
