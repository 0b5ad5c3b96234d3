// Filters that turn their mask into a grid of costs once per mask, then merge it into the master
// grid row by row (KeepoutFilter, LanesFilter), and KeepoutFilter itself: a mask value v in 1..100
// costs round(v * 254 / 100) (100 is LETHAL, a virtual wall); 0 and -1 write nothing.
#pragma once

#include <atomic>
#include <memory>
#include <vector>

#include "costmap_layers/core/costmap_filter.hpp"

namespace costmap_layers
{
/// Cost of a keepout mask value: round(v * 254 / 100) for v in 1..100; 0 for 0, -1 and invalid values.
uint8_t keepoutCost(int8_t mask_value);

/// Merges a cost into a master cell: the master takes the cost when higher; an unknown master cell
/// only takes a cost >= 253, so a filter never turns unknown space into known free space.
inline uint8_t mergeFilterCost(uint8_t master, uint8_t cost)
{
  const bool unknown = master == 255;
  const uint8_t higher = cost > master ? cost : master;
  return unknown ? (cost >= 253 ? cost : master) : higher;
}

/// A filter whose mask means a cost per mask cell (0 = no effect), computed once per mask.
class CostGridFilter : public CostmapFilter
{
protected:
  /// Fills costs (one per mask cell, row-major) for a new mask.
  /// @return the number of mask cells with values outside -1..100 (invalid in an OccupancyGrid).
  virtual std::size_t computeCosts(const OccupancyGridData& mask, std::vector<uint8_t>& costs) = 0;

  void process(Costmap2D& master_grid, const CellWindow& window, const OccupancyGridData& mask,
               const MaskMapping& mapping, double robot_x, double robot_y, double robot_yaw) final;
  /// Recompute the costs at the next update (after a parameter change). Update thread only.
  void invalidateCosts() { costs_for_.reset(); }

private:
  std::shared_ptr<const OccupancyGridData> costs_for_;  ///< the mask the costs were computed from
  std::vector<uint8_t> costs_;
  std::vector<uint8_t> scratch_;
  std::atomic<bool> warned_invalid_{false};
};

class KeepoutFilter : public CostGridFilter
{
protected:
  std::size_t computeCosts(const OccupancyGridData& mask, std::vector<uint8_t>& costs) override;
};
}  // namespace costmap_layers
