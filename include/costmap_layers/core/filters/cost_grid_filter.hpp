// The base of filters that turn their mask into a grid of costs once per mask, then merge it into the
// master grid row by row with mergeFilterCost (rules/cost_rules.hpp): KeepoutFilter and LanesFilter.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "costmap_layers/core/filters/costmap_filter.hpp"

namespace costmap_layers
{
/// A filter whose mask means a cost per mask cell (0 = no effect), computed once per mask.
class CostGridFilter : public CostmapFilter
{
protected:
  /// Fills costs (one per mask cell, row-major) for a new mask.
  /// @return the number of mask cells with values outside -1..100 (invalid in an OccupancyGrid).
  virtual std::size_t computeCosts(const OccupancyGridData& mask, std::vector<uint8_t>& costs) = 0;

  void process(Costmap2D& master_grid, const CellWindow& window, const OccupancyGridData& mask,
               const GridSampler& mapping, double robot_x, double robot_y, double robot_yaw) final;
  /// Recompute the costs at the next update (after a parameter change). Update thread only.
  void invalidateCosts() { costs_for_.reset(); }

private:
  std::shared_ptr<const OccupancyGridData> costs_for_;  ///< the mask the costs were computed from
  std::vector<uint8_t> costs_;
  std::vector<uint8_t> scratch_;
};

}  // namespace costmap_layers
