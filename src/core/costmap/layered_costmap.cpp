#include "costmap_layers/core/costmap/layered_costmap.hpp"

#include <algorithm>
#include <limits>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/costmap/layer.hpp"

namespace costmap_layers
{
LayeredCostmap::LayeredCostmap(std::string global_frame, bool rolling_window, bool track_unknown)
    : global_frame_(std::move(global_frame)), rolling_window_(rolling_window), track_unknown_(track_unknown)
{
  const uint8_t def = track_unknown ? NO_INFORMATION : FREE_SPACE;
  primary_.setDefaultValue(def);
  combined_.setDefaultValue(def);
}

LayeredCostmap::~LayeredCostmap()
{
  // Layers hold a plain pointer back to this object: drop them first, in reverse order of creation.
  while (!filters_.empty())
    filters_.pop_back();
  while (!plugins_.empty())
    plugins_.pop_back();
}

void LayeredCostmap::addPlugin(std::shared_ptr<Layer> plugin)
{
  plugins_.push_back(std::move(plugin));
}

void LayeredCostmap::addFilter(std::shared_ptr<Layer> filter)
{
  if (filters_.empty()) combined_ = primary_;
  filters_.push_back(std::move(filter));
}

std::shared_ptr<Layer> LayeredCostmap::findLayer(const std::string& name) const
{
  for (const auto* list : {&plugins_, &filters_})
  {
    for (const auto& layer : *list)
    {
      if (layer->getName() == name) return layer;
    }
  }
  for (const auto& layer : nestedLayers())
    if (layer->getName() == name) return layer;
  return nullptr;
}

std::vector<std::shared_ptr<Layer>> LayeredCostmap::nestedLayers() const
{
  std::vector<std::shared_ptr<Layer>> out;
  // Depth first: each holder's layers right after it. The nesting is bounded by the holders themselves.
  const std::function<void(const Layer&)> walk = [&](const Layer& holder)
  {
    for (const auto& held : holder.heldLayers())
    {
      out.push_back(held);
      walk(*held);
    }
  };
  for (const auto* list : {&plugins_, &filters_})
    for (const auto& layer : *list)
      walk(*layer);
  return out;
}

void LayeredCostmap::resizeMap(unsigned int size_x, unsigned int size_y, double resolution, double origin_x,
                               double origin_y, bool size_locked)
{
  size_locked_ = size_locked;
  if (resize_handler_)
  {
    resize_handler_(size_x, size_y, resolution, origin_x, origin_y, size_locked);
    return;
  }
  primary_.resizeMap(size_x, size_y, resolution, origin_x, origin_y);
  if (!filters_.empty()) combined_.resizeMap(size_x, size_y, resolution, origin_x, origin_y);
  for (const auto* list : {&plugins_, &filters_})
  {
    for (const auto& layer : *list)
      layer->matchSize();
  }
}

void LayeredCostmap::viewMaster(uint8_t* cells, unsigned int size_x, unsigned int size_y, double resolution,
                                double origin_x, double origin_y)
{
  const bool changed = size_x != primary_.getSizeInCellsX() || size_y != primary_.getSizeInCellsY() ||
                       resolution != primary_.getResolution() ||
                       (!rolling_window_ && (origin_x != primary_.getOriginX() || origin_y != primary_.getOriginY()));
  primary_.viewMemory(cells, size_x, size_y, resolution, origin_x, origin_y);
  if (!changed) return;
  for (const auto* list : {&plugins_, &filters_})
  {
    for (const auto& layer : *list)
      layer->matchSize();
  }
}

void LayeredCostmap::updateMap(double robot_x, double robot_y, double robot_yaw)
{
  if (rolling_window_)
  {
    const double new_origin_x = robot_x - primary_.getSizeInMetersX() / 2;
    const double new_origin_y = robot_y - primary_.getSizeInMetersY() / 2;
    primary_.updateOrigin(new_origin_x, new_origin_y);
    if (!filters_.empty()) combined_.updateOrigin(new_origin_x, new_origin_y);
  }
  updated_ = CellWindow{};
  if (plugins_.empty() && filters_.empty()) return;

  double min_x = std::numeric_limits<double>::max(), min_y = std::numeric_limits<double>::max();
  double max_x = std::numeric_limits<double>::lowest(), max_y = std::numeric_limits<double>::lowest();
  for (const auto* list : {&plugins_, &filters_})
  {
    for (const auto& layer : *list)
    {
      // A layer switched on or off since the last cycle: its cells appear or go everywhere at once.
      if (layer->takeEnabledFlip() && layer->writesCosts()) full_update_ = true;
      if (!layer->enabled()) continue;
      // A layer may only grow the bounds; one that shrinks them is ignored for this cycle.
      const double px0 = min_x, py0 = min_y, px1 = max_x, py1 = max_y;
      layer->updateBounds(robot_x, robot_y, robot_yaw, &min_x, &min_y, &max_x, &max_y);
      if (min_x > px0 || min_y > py0 || max_x < px1 || max_y < py1)
      {
        min_x = std::min(min_x, px0);
        min_y = std::min(min_y, py0);
        max_x = std::max(max_x, px1);
        max_y = std::max(max_y, py1);
      }
    }
  }
  if (full_update_)
  {
    full_update_ = false;
    min_x = primary_.getOriginX();
    min_y = primary_.getOriginY();
    max_x = primary_.getOriginX() + primary_.getSizeInMetersX();
    max_y = primary_.getOriginY() + primary_.getSizeInMetersY();
  }
  if (!(min_x <= max_x) || !(min_y <= max_y)) return;  // nobody asked for anything

  int x0, y0, xn, yn;
  primary_.worldToMapEnforceBounds(min_x, min_y, x0, y0);
  primary_.worldToMapEnforceBounds(max_x, max_y, xn, yn);
  x0 = std::max(0, x0);
  y0 = std::max(0, y0);
  xn = std::min(static_cast<int>(primary_.getSizeInCellsX()), xn + 1);
  yn = std::min(static_cast<int>(primary_.getSizeInCellsY()), yn + 1);
  if (xn <= x0 || yn <= y0) return;

  // The window starts from the default value, unless the first layer writes all of it anyway.
  const auto first = std::find_if(plugins_.begin(), plugins_.end(), [](const auto& l) { return l->enabled(); });
  if (first == plugins_.end() || !(*first)->overwritesWindow(primary_, x0, y0, xn, yn))
    primary_.resetMap(static_cast<unsigned>(x0), static_cast<unsigned>(y0), static_cast<unsigned>(xn),
                      static_cast<unsigned>(yn));
  for (const auto& layer : plugins_)
  {
    if (layer->enabled()) layer->updateCosts(primary_, x0, y0, xn, yn);
  }
  if (!filters_.empty())
  {
    combined_.copyWindow(primary_, static_cast<unsigned>(x0), static_cast<unsigned>(y0), static_cast<unsigned>(xn),
                         static_cast<unsigned>(yn), static_cast<unsigned>(x0), static_cast<unsigned>(y0));
    for (const auto& filter : filters_)
    {
      if (filter->enabled()) filter->updateCosts(combined_, x0, y0, xn, yn);
    }
  }
  updated_ = CellWindow{x0, y0, xn, yn};
  initialized_ = true;
}

bool LayeredCostmap::isCurrent() const
{
  for (const auto* list : {&plugins_, &filters_})
  {
    for (const auto& layer : *list)
    {
      if (layer->enabled() && !layer->isCurrent()) return false;
    }
  }
  return true;
}

void LayeredCostmap::setFootprint(const Footprint& footprint)
{
  footprint_ = footprint;
  calculateMinAndMaxDistances(footprint_, inscribed_radius_, circumscribed_radius_);
  for (const auto* list : {&plugins_, &filters_})
  {
    for (const auto& layer : *list)
      layer->onFootprintChanged();
  }
}
}  // namespace costmap_layers
