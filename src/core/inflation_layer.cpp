#include "costmap_layers/core/inflation_layer.hpp"

// The hot loops are written for the vectoriser; GCC enables it at -O2 only for trivially
// profitable loops, so this file asks for the full vectoriser (Clang vectorises at -O2 anyway).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("tree-vectorize", "vect-cost-model=dynamic")
#endif

#include <algorithm>
#include <cmath>
#include <limits>

#include "costmap_layers/core/cost_values.hpp"
#include "costmap_layers/core/costmap_2d.hpp"
#include "costmap_layers/core/layered_costmap.hpp"
#include "costmap_layers/core/limits.hpp"
#include "costmap_layers/core/param_reader.hpp"

namespace costmap_layers
{
namespace
{
/// Radii up to this many cells use the 16-bit banded engine; larger ones the exact transform.
constexpr int kBanded16Limit = 40;
/// Past this many squared distances the cost is computed per cell instead of from a table.
constexpr uint64_t kMaxTableSize = uint64_t{1} << 22;
}  // namespace

InflationConfig parseInflationConfig(const ParamReader& params)
{
  InflationConfig cfg;
  cfg.inflation_radius = params.getDouble("inflation_radius", cfg.inflation_radius, 0.0, limits::kMaxDistance);
  cfg.cost_scaling_factor = params.getDouble("cost_scaling_factor", cfg.cost_scaling_factor, 0.0);
  cfg.inflate_unknown = params.getBool("inflate_unknown", cfg.inflate_unknown);
  cfg.inflate_around_unknown = params.getBool("inflate_around_unknown", cfg.inflate_around_unknown);
  return cfg;
}

void InflationLayer::onInitialize()
{
  config_ = parseInflationConfig(ParamReader(context_->params(), name_));
  inscribed_radius_ = layered_costmap_->getInscribedRadius();
  resolution_ = layered_costmap_->getCostmap().getResolution();
  rebuildTable();
  need_reinflation_ = true;
}

void InflationLayer::setConfig(const InflationConfig& config)
{
  config_ = config;
  rebuildTable();
  need_reinflation_ = true;
}

void InflationLayer::matchSize()
{
  resolution_ = layered_costmap_->getCostmap().getResolution();
  rebuildTable();
  need_reinflation_ = true;
}

void InflationLayer::onFootprintChanged()
{
  inscribed_radius_ = layered_costmap_->getInscribedRadius();
  rebuildTable();
  need_reinflation_ = true;
}

void InflationLayer::reset()
{
  need_reinflation_ = true;
}

void InflationLayer::onReconfigure(const ParamValue& params)
{
  setConfig(parseInflationConfig(ParamReader(params, name_)));
}

std::vector<ParamSpec> InflationLayer::tunableLayerParameters(const ParamValue& params) const
{
  return recordParameters(params, name_, [](const ParamReader& r) { parseInflationConfig(r); });
}

void InflationLayer::rebuildTable()
{
  cell_inflation_radius_ = 0;
  cost_table_.clear();
  table_limit_ = 0;
  table_non_increasing_ = false;
  if (!(resolution_ > 0.0)) return;
  const double cells = std::ceil(config_.inflation_radius / resolution_);
  cell_inflation_radius_ = static_cast<int>(std::min(cells, 1e6));
  const uint64_t cap_sq = static_cast<uint64_t>(cell_inflation_radius_) * cell_inflation_radius_;
  table_limit_ = static_cast<uint32_t>(std::min<uint64_t>(cap_sq, std::numeric_limits<uint32_t>::max() - 1));
  // The banded engines report up to 2 * cap^2 + 1; the table covers that so lookups need no test.
  uint64_t size = cap_sq + 1;
  if (cell_inflation_radius_ <= kBanded16Limit) size = std::max<uint64_t>(2 * cap_sq + 2, 256);
  if (size > kMaxTableSize) return;  // computed per cell
  cost_table_.assign(static_cast<std::size_t>(size), 0);
  for (uint64_t d2 = 0; d2 <= cap_sq; ++d2)
    cost_table_[static_cast<std::size_t>(d2)] =
        inflationCost(std::sqrt(static_cast<double>(d2)), resolution_, inscribed_radius_, config_.cost_scaling_factor);
  table_non_increasing_ = true;
  for (uint64_t d2 = 1; d2 <= cap_sq; ++d2)
    if (cost_table_[static_cast<std::size_t>(d2)] > cost_table_[static_cast<std::size_t>(d2 - 1)])
      table_non_increasing_ = false;
}

uint8_t InflationLayer::costAtSquaredDistance(uint32_t d2) const
{
  if (d2 > table_limit_) return 0;
  if (d2 < cost_table_.size()) return cost_table_[d2];
  return inflationCost(std::sqrt(static_cast<double>(d2)), resolution_, inscribed_radius_, config_.cost_scaling_factor);
}

void InflationLayer::updateBounds(double, double, double, double* min_x, double* min_y, double* max_x, double* max_y)
{
  if (need_reinflation_)
  {
    // The whole map once: float limits stay representable through the cell conversions.
    *min_x = -std::numeric_limits<float>::max();
    *min_y = -std::numeric_limits<float>::max();
    *max_x = std::numeric_limits<float>::max();
    *max_y = std::numeric_limits<float>::max();
    need_reinflation_ = false;
    return;
  }
  if (!(*min_x <= *max_x) || !(*min_y <= *max_y)) return;  // nothing changed below
  // Every cell within cell_inflation_radius_ cells of a changed cell may change. That is
  // ceil(radius / resolution) cells, at least the radius itself.
  const double grow = cell_inflation_radius_ * resolution_;
  *min_x -= grow;
  *min_y -= grow;
  *max_x += grow;
  *max_y += grow;
}

template <class T>
void InflationLayer::writeRow(uint8_t* master_row, const T* sq_dist, int n)
{
  uint8_t* costs = row_costs_.data();
  if constexpr (sizeof(T) < sizeof(uint32_t))
  {
    // The table covers every value the banded engines report.
    const uint8_t* table = cost_table_.data();
    for (int k = 0; k < n; ++k)
      costs[k] = table[sq_dist[k]];
  }
  else if (!cost_table_.empty())
  {
    const uint8_t* table = cost_table_.data();
    const uint32_t limit = table_limit_;
    for (int k = 0; k < n; ++k)
      costs[k] = sq_dist[k] <= limit ? table[sq_dist[k]] : uint8_t{0};
  }
  else
  {
    for (int k = 0; k < n; ++k)
      costs[k] = costAtSquaredDistance(sq_dist[k]);
  }
  // An unknown cell takes the cost only from the threshold on; any other cell takes the maximum.
  const uint8_t unknown_threshold = config_.inflate_unknown ? uint8_t{1} : INSCRIBED_INFLATED_OBSTACLE;
  for (int k = 0; k < n; ++k)
  {
    const uint8_t old_cost = master_row[k], cost = costs[k];
    const uint8_t for_unknown = cost >= unknown_threshold ? cost : NO_INFORMATION;
    const uint8_t for_known = old_cost > cost ? old_cost : cost;
    master_row[k] = old_cost == NO_INFORMATION ? for_unknown : for_known;
  }
}

void InflationLayer::updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j)
{
  if (!enabled_) return;
  if (master_grid.getResolution() != resolution_)
  {
    resolution_ = master_grid.getResolution();
    rebuildTable();
  }
  const int cap = cell_inflation_radius_;
  if (cap <= 0) return;
  const int width = static_cast<int>(master_grid.getSizeInCellsX());
  const int height = static_cast<int>(master_grid.getSizeInCellsY());
  DistanceWindow win;
  win.x0 = std::max(min_i, 0);
  win.y0 = std::max(min_j, 0);
  win.x1 = std::min(max_i, width);
  win.y1 = std::min(max_j, height);
  if (win.x0 >= win.x1 || win.y0 >= win.y1) return;

  const int n = win.x1 - win.x0;
  if (row_costs_.size() < static_cast<std::size_t>(n)) row_costs_.resize(static_cast<std::size_t>(n));
  const SourceRange sources = config_.inflate_around_unknown ? SourceRange{LETHAL_OBSTACLE, NO_INFORMATION}
                                                             : SourceRange{LETHAL_OBSTACLE, LETHAL_OBSTACLE};
  uint8_t* data = master_grid.data();
  const std::ptrdiff_t stride = width;
  // The engines read the sources of a row (and the rows after it) before the sink writes that row;
  // writing never adds or removes a source (a source's cost is 254 and stays so).
  if (cap <= kMaxBandedCap8 && table_non_increasing_)
  {
    // The transform in the cost domain, merged into the master in place.
    CostMergeRule rule;
    rule.special = NO_INFORMATION;
    rule.special_threshold = config_.inflate_unknown ? uint8_t{1} : INSCRIBED_INFLATED_OBSTACLE;
    cappedCostMerge8(data, width, height, stride, sources, cap, win, cost_table_.data(), rule, scratch_);
  }
  else if (cap <= kMaxBandedCap8)
  {
    cappedSquaredDistanceRows8(data, width, height, stride, sources, cap, win, scratch_,
                               [&](int y, const uint8_t* d) { writeRow(data + y * stride + win.x0, d, n); });
  }
  else if (cap <= kBanded16Limit)
  {
    cappedSquaredDistanceRows16(data, width, height, stride, sources, cap, win, scratch_,
                                [&](int y, const uint16_t* d) { writeRow(data + y * stride + win.x0, d, n); });
  }
  else
  {
    // The exact transform over the window padded by the radius (clipped to the grid).
    const int px0 = std::max(0, win.x0 - cap), py0 = std::max(0, win.y0 - cap);
    const int px1 = std::min(width, win.x1 + cap), py1 = std::min(height, win.y1 + cap);
    const int pw = px1 - px0, ph = py1 - py0;
    const std::size_t cells = static_cast<std::size_t>(pw) * static_cast<std::size_t>(ph);
    if (exact_.size() < cells) exact_.resize(cells);
    squaredDistanceTransform(data + py0 * stride + px0, pw, ph, stride, sources, exact_.data(), pw, table_limit_,
                             scratch_);
    for (int y = win.y0; y < win.y1; ++y)
      writeRow(data + y * stride + win.x0, exact_.data() + static_cast<std::size_t>(y - py0) * pw + (win.x0 - px0), n);
  }
}
}  // namespace costmap_layers
