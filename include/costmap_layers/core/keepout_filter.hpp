// KeepoutFilter: keepout zones and costly areas from a mask. A mask value v in 1..100 costs
// round(v * 254 / 100) (100 is LETHAL, a virtual wall); 0 and -1 write nothing.
#pragma once

#include <array>
#include <atomic>

#include "costmap_layers/core/costmap_filter.hpp"

namespace costmap_layers
{
/// Cost of a keepout mask value: round(v * 254 / 100) for v in 1..100; 0 for 0, -1 and invalid values.
uint8_t keepoutCost(int8_t mask_value);

class KeepoutFilter : public CostmapFilter
{
protected:
  void onInitializeFilter(const ParamReader& params) override;
  /// A master cell takes the mask's cost when higher; an unknown master cell only takes a cost >= 253,
  /// so a keepout zone never turns unknown space into free space.
  void process(Costmap2D& master_grid, const CellWindow& window, const OccupancyGridData& mask,
               const MaskMapping& mapping, double robot_x, double robot_y, double robot_yaw) override;

private:
  std::array<uint8_t, 256> table_{};  ///< cost per mask byte
  std::atomic<bool> warned_invalid_{false};
};
}  // namespace costmap_layers
