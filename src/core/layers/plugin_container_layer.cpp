#include "costmap_layers/core/layers/plugin_container_layer.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/config/plugin_types.hpp"
#include "costmap_layers/core/costmap/costmap_config.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/rules/limits.hpp"

namespace costmap_layers
{
PluginContainerConfig parsePluginContainerConfig(const ParamReader& params)
{
  PluginContainerConfig cfg;
  const int method = params.getInt("combination_method", static_cast<int>(cfg.combination_method), 0, 2);
  cfg.combination_method = static_cast<ContainerCombination>(method);
  return cfg;
}

void PluginContainerLayer::setMaker(LayerMaker maker, int level)
{
  maker_ = std::move(maker);
  level_ = level;
}

void PluginContainerLayer::onInitialize()
{
  const ParamReader p(context_->params(), name_);
  config_ = parsePluginContainerConfig(p);
  if (level_ <= 0 || !maker_.layers || !maker_.contexts)
    throw std::invalid_argument(name_ + ": this host cannot make the plugins of a PluginContainerLayer");
  if (level_ > kMaxNesting)
    throw std::invalid_argument(name_ + ": containers nested " + std::to_string(level_) + " deep, at most " +
                                std::to_string(kMaxNesting));
  const std::vector<PluginSpec> specs = parsePluginList(context_->params(), name_);
  // Nav2 runs an empty container as a layer that draws nothing: here that is taken for a mistake (a
  // misspelt `plugins`, a list in the wrong namespace).
  if (specs.empty()) p.fail("plugins", "must list at least one plugin (a container of nothing draws nothing)");
  *maker_.listed += specs.size();
  if (*maker_.listed > limits::kMaxPlugins)
    p.fail("plugins", "makes " + std::to_string(*maker_.listed) +
                          " plugins in this costmap with the others, more than " + std::to_string(limits::kMaxPlugins));
  costmap_.setDefaultValue(NO_INFORMATION);
  for (const PluginSpec& spec : specs)
  {
    // A container named as one holding it ("group/group") can only be a copy-paste slip.
    if (pluginClassName(resolvePluginType(spec.type)) == "PluginContainerLayer")
    {
      std::size_t start = 0;
      while (start <= name_.size())
      {
        const std::size_t slash = std::min(name_.find('/', start), name_.size());
        if (name_.compare(start, slash - start, spec.name) == 0 && slash - start == spec.name.size())
          p.fail("plugins", "lists '" + shownText(spec.name) +
                                "', a container named as one holding it (a container "
                                "inside itself)");
        start = slash + 1;
      }
    }
    const PluginSpec held{name_ + "/" + spec.name, spec.type};
    if (const std::string problem = pluginNameProblem(held.name); !problem.empty())
      p.fail("plugins", "makes the plugin name " + problem);
    plugins_.push_back(makeLayer(*layered_costmap_, held, maker_, level_));
  }
  // The host's factories stay with the plugins they made; the container needs them no more.
  maker_.layers = nullptr;
  maker_.contexts = nullptr;
  // On the master's geometry now: a host that added the container before initialising it (the move_base
  // bridge) calls no matchSize until the master changes.
  matchSize();
}

void PluginContainerLayer::onReconfigure(const ParamValue& params)
{
  config_ = parsePluginContainerConfig(ParamReader(params, name_));
}

std::vector<ParamSpec> PluginContainerLayer::tunableLayerParameters(const ParamValue& params) const
{
  return recordParameters(params, name_, [](const ParamReader& r) { parsePluginContainerConfig(r); });
}

void PluginContainerLayer::updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y,
                                        double* max_x, double* max_y)
{
  followRollingMaster();
  useExtraBounds(min_x, min_y, max_x, max_y);
  bool redraw = false;
  for (const auto& layer : plugins_)
  {
    // As LayeredCostmap does for its plugins: a plugin switched on or off redraws everything once,
    // a disabled one is not asked, and one that shrinks the bounds is ignored for this cycle.
    if (layer->takeEnabledFlip() && layer->writesCosts()) redraw = true;
    if (!layer->enabled()) continue;
    const double px0 = *min_x, py0 = *min_y, px1 = *max_x, py1 = *max_y;
    layer->updateBounds(robot_x, robot_y, robot_yaw, min_x, min_y, max_x, max_y);
    *min_x = std::min(*min_x, px0);
    *min_y = std::min(*min_y, py0);
    *max_x = std::max(*max_x, px1);
    *max_y = std::max(*max_y, py1);
  }
  if (redraw)
  {
    touch(costmap_.getOriginX(), costmap_.getOriginY(), min_x, min_y, max_x, max_y);
    touch(costmap_.getOriginX() + costmap_.getSizeInMetersX(), costmap_.getOriginY() + costmap_.getSizeInMetersY(),
          min_x, min_y, max_x, max_y);
  }
}

void PluginContainerLayer::updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j)
{
  min_i = std::max(min_i, 0);
  min_j = std::max(min_j, 0);
  max_i = std::min(max_i, static_cast<int>(costmap_.getSizeInCellsX()));
  max_j = std::min(max_j, static_cast<int>(costmap_.getSizeInCellsY()));
  bool current = true;
  if (min_i < max_i && min_j < max_j)
  {
    // The plugins draw on a clean window each cycle, as on the master: Nav2 keeps the container's grid
    // from the last cycle, so that a cost a plugin drew with its maximum stays after the plugin dropped it.
    costmap_.resetMap(static_cast<unsigned>(min_i), static_cast<unsigned>(min_j), static_cast<unsigned>(max_i),
                      static_cast<unsigned>(max_j));
    for (const auto& layer : plugins_)
    {
      if (!layer->enabled()) continue;
      layer->updateCosts(costmap_, min_i, min_j, max_i, max_j);
      current = current && layer->isCurrent();
    }
    switch (config_.combination_method)
    {
      case ContainerCombination::Overwrite:
        updateWithOverwrite(master_grid, min_i, min_j, max_i, max_j);
        break;
      case ContainerCombination::MaxWithoutUnknownOverwrite:
        updateWithMaxWithoutUnknownOverwrite(master_grid, min_i, min_j, max_i, max_j);
        break;
      case ContainerCombination::Max:
        updateWithMax(master_grid, min_i, min_j, max_i, max_j);
        break;
    }
  }
  else
  {
    for (const auto& layer : plugins_)
      current = current && (!layer->enabled() || layer->isCurrent());
  }
  // Nav2 says current after every update; here only when its plugins are, so that a stalled sensor in
  // a container shows in the costmap's "not current" as it would outside one.
  current_ = current;
}

void PluginContainerLayer::matchSize()
{
  CostmapLayer::matchSize();
  for (const auto& layer : plugins_)
    layer->matchSize();
}

void PluginContainerLayer::onFootprintChanged()
{
  for (const auto& layer : plugins_)
    layer->onFootprintChanged();
}

void PluginContainerLayer::reset()
{
  for (const auto& layer : plugins_)
    layer->reset();
  costmap_.resetMaps();
  current_ = false;
}

void PluginContainerLayer::activate()
{
  for (const auto& layer : plugins_)
    layer->activate();
}

void PluginContainerLayer::deactivate()
{
  for (const auto& layer : plugins_)
    layer->deactivate();
}

bool PluginContainerLayer::isClearable()
{
  return std::any_of(plugins_.begin(), plugins_.end(), [](const auto& layer) { return layer->isClearable(); });
}

void PluginContainerLayer::clearCells(unsigned int x0, unsigned int y0, unsigned int xn, unsigned int yn, uint8_t value)
{
  CostmapLayer::clearCells(x0, y0, xn, yn, value);
  for (const auto& layer : plugins_)
  {
    if (!layer->isClearable()) continue;
    if (auto* grid_layer = dynamic_cast<CostmapLayer*>(layer.get())) grid_layer->clearCells(x0, y0, xn, yn, value);
  }
}
}  // namespace costmap_layers
