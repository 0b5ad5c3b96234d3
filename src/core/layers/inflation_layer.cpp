#include "costmap_layers/core/layers/inflation_layer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <thread>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/grid/costmap_2d.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/core/config/param_reader.hpp"

namespace costmap_layers
{
InflationConfig parseInflationConfig(const ParamReader& params)
{
  InflationConfig cfg;
  cfg.inflation_radius = params.getDouble("inflation_radius", cfg.inflation_radius, 0.0, limits::kMaxDistance);
  cfg.cost_scaling_factor = params.getDouble("cost_scaling_factor", cfg.cost_scaling_factor, 0.0);
  cfg.inflate_unknown = params.getBool("inflate_unknown", cfg.inflate_unknown);
  cfg.inflate_around_unknown = params.getBool("inflate_around_unknown", cfg.inflate_around_unknown);
  // Nav2's: >= 0 replaces the footprint's inscribed radius, any negative number means "not set" (Nav2
  // tests >= 0 only, so -2 works there too).
  cfg.custom_inscribed_radius = params.getDouble("custom_inscribed_radius", cfg.custom_inscribed_radius,
                                                 -limits::kMaxDistance, limits::kMaxDistance);
  cfg.num_threads = parseInflationThreads(params, cfg.num_threads);
  return cfg;
}

int parseInflationThreads(const ParamReader& params, int def)
{
  // Nav2's InflationLayer takes 0 or less (its default, -1) as "half the cores, at least one".
  const int n = params.getInt("num_threads", def, -1, 64);
  if (n > 0) return n;
  return std::max(1, static_cast<int>(std::min(128u, std::thread::hardware_concurrency())) / 2);
}

void InflationLayer::onInitialize()
{
  initializeWith(parseInflationConfig(ParamReader(context_->params(), name_)));
}

void InflationLayer::initializeWith(const InflationConfig& config)
{
  config_ = config;
  updateInscribedRadius();
  resolution_ = layered_costmap_->getCostmap().getResolution();
  rebuildTable();
  need_reinflation_ = true;
}

void InflationLayer::updateInscribedRadius()
{
  const double footprint = layered_costmap_->getInscribedRadius();
  if (config_.custom_inscribed_radius < 0.0)
  {
    inscribed_radius_ = footprint;
    return;
  }
  inscribed_radius_ = config_.custom_inscribed_radius;
  // As Nav2 does: costs then no longer say where the footprint touches an obstacle.
  std::ostringstream what;
  what << name_ << ": custom_inscribed_radius " << config_.custom_inscribed_radius
       << " m replaces the footprint's inscribed radius " << footprint
       << " m: cells within it cost 253 (inscribed) and beyond it less, whatever the footprint; "
          "planners reading 253 as 'the robot touches' may take a robot into collision";
  if (context_) context_->report(Severity::Warn, "custom_inscribed_radius", what.str());
}

void InflationLayer::setConfig(const InflationConfig& config)
{
  const bool custom_changed = config.custom_inscribed_radius != config_.custom_inscribed_radius;
  config_ = config;
  if (custom_changed) updateInscribedRadius();
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
  updateInscribedRadius();
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
  if (!(resolution_ > 0.0))
  {
    costs_ = DistanceCosts();
    table_key_ = TableKey{};
    return;
  }
  const double cells = std::ceil(config_.inflation_radius / resolution_);
  cell_inflation_radius_ = static_cast<int>(std::min(cells, 1e8));
  const TableKey key{cell_inflation_radius_, config_.cost_scaling_factor, resolution_, inscribed_radius_};
  if (key == table_key_) return;  // e.g. the same footprint handed over again
  const uint64_t cap_sq = static_cast<uint64_t>(cell_inflation_radius_) * static_cast<uint64_t>(cell_inflation_radius_);
  const double res = resolution_, inscribed = inscribed_radius_, factor = config_.cost_scaling_factor;
  // costmap_2d's rule (cost_rules.hpp) at the exact distance; 0 past the radius. It does not increase
  // with the distance (factor >= 0), and the engine stops where it reaches 0.
  costs_ = DistanceCosts(
      cell_inflation_radius_,
      [&](uint64_t d2) -> uint8_t
      { return d2 > cap_sq ? 0 : inflationCost(std::sqrt(static_cast<double>(d2)), res, inscribed, factor); });
  table_key_ = key;
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
  // Every cell within the cost's reach of a changed cell may change (at most ceil(radius / resolution)
  // cells, at least the radius itself when the cost does not round to 0 before it).
  const double grow = static_cast<double>(costs_.reach()) * resolution_;
  *min_x -= grow;
  *min_y -= grow;
  *max_x += grow;
  *max_y += grow;
}

void InflationLayer::updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j)
{
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

  // The engine reads the sources of a row (and of the rows after it) before it writes that row; writing
  // never adds or removes a source (a source's cost is 254 and stays so).
  distanceCostMerge(master_grid.data(), width, height, width, sourceRange(), costs_, win, mergeRule(), scratch_,
                    config_.num_threads);
}

SourceRange InflationLayer::sourceRange() const
{
  return config_.inflate_around_unknown ? SourceRange{LETHAL_OBSTACLE, NO_INFORMATION}
                                        : SourceRange{LETHAL_OBSTACLE, LETHAL_OBSTACLE};
}

CostMergeRule InflationLayer::mergeRule() const
{
  CostMergeRule rule;
  rule.special = NO_INFORMATION;
  rule.special_threshold = config_.inflate_unknown ? uint8_t{1} : INSCRIBED_INFLATED_OBSTACLE;
  return rule;
}
}  // namespace costmap_layers
