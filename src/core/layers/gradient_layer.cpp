#include "costmap_layers/core/layers/gradient_layer.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/grid/costmap_2d.hpp"
#include "costmap_layers/core/config/param_reader.hpp"

namespace costmap_layers
{
GradientConfig parseGradientConfig(const ParamReader& params)
{
  GradientConfig cfg;
  cfg.gradient_size = params.getInt("gradient_size", cfg.gradient_size, 0, 1000000);
  cfg.gradient_factor = params.getInt("gradient_factor", cfg.gradient_factor, 0, 254);
  return cfg;
}

void GradientLayer::onInitialize()
{
  config_ = parseGradientConfig(ParamReader(context_->params(), name_));
  need_recalculation_ = true;
}

void GradientLayer::onReconfigure(const ParamValue& params)
{
  config_ = parseGradientConfig(ParamReader(params, name_));  // throws before anything changes
  need_recalculation_ = true;
}

std::vector<ParamSpec> GradientLayer::tunableLayerParameters(const ParamValue& params) const
{
  return recordParameters(params, name_, [](const ParamReader& r) { parseGradientConfig(r); });
}

void GradientLayer::updateBounds(double, double, double, double* min_x, double* min_y, double* max_x, double* max_y)
{
  if (need_recalculation_)
  {
    last_min_x_ = *min_x;
    last_min_y_ = *min_y;
    last_max_x_ = *max_x;
    last_max_y_ = *max_y;
    // The whole map: float limits stay representable through the cell conversions.
    *min_x = -std::numeric_limits<float>::max();
    *min_y = -std::numeric_limits<float>::max();
    *max_x = std::numeric_limits<float>::max();
    *max_y = std::numeric_limits<float>::max();
    need_recalculation_ = false;
    return;
  }
  // Later cycles repeat the window that was asked for last time, together with this one.
  const double tmp_min_x = last_min_x_, tmp_min_y = last_min_y_, tmp_max_x = last_max_x_, tmp_max_y = last_max_y_;
  last_min_x_ = *min_x;
  last_min_y_ = *min_y;
  last_max_x_ = *max_x;
  last_max_y_ = *max_y;
  *min_x = std::min(tmp_min_x, *min_x);
  *min_y = std::min(tmp_min_y, *min_y);
  *max_x = std::max(tmp_max_x, *max_x);
  *max_y = std::max(tmp_max_y, *max_y);
}

void GradientLayer::updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j)
{
  min_i = std::max(min_i, 0);
  min_j = std::max(min_j, 0);
  max_i = std::min(max_i, static_cast<int>(master_grid.getSizeInCellsX()));
  max_j = std::min(max_j, static_cast<int>(master_grid.getSizeInCellsY()));
  if (min_i >= max_i || min_j >= max_j) return;

  // Every row of the window starts the ramp at its first column, so one row serves them all.
  const std::size_t width = static_cast<std::size_t>(max_i - min_i);
  row_.resize(width);
  int k = 0;
  for (std::size_t i = 0; i < width; ++i)
  {
    row_[i] = gradientCost(k, config_.gradient_factor);
    k = k <= config_.gradient_size ? k + 1 : 0;
  }
  for (int j = min_j; j < max_j; ++j)
  {
    std::memcpy(master_grid.data() + master_grid.getIndex(static_cast<unsigned>(min_i), static_cast<unsigned>(j)),
                row_.data(), width);
  }
}
}  // namespace costmap_layers
