#include "costmap_layers/core/keepout_filter.hpp"

#include <cmath>

#include "costmap_layers/core/cost_values.hpp"

namespace costmap_layers
{
uint8_t keepoutCost(int8_t mask_value)
{
  if (mask_value < 1 || mask_value > 100) return FREE_SPACE;
  return static_cast<uint8_t>(std::lround(mask_value * 254.0 / 100.0));
}

void KeepoutFilter::onInitializeFilter(const ParamReader&)
{
  for (int b = 0; b < 256; ++b) table_[static_cast<std::size_t>(b)] = keepoutCost(static_cast<int8_t>(b));
}

void KeepoutFilter::process(Costmap2D& master_grid, const CellWindow&, const OccupancyGridData& mask,
                            const MaskMapping& mapping, double, double, double)
{
  bool invalid = false;
  const uint8_t* table = table_.data();
  mapping.forEach(master_grid, mask, [table, &invalid](uint8_t& cell, int8_t value) {
    const uint8_t cost = table[static_cast<uint8_t>(value)];
    invalid |= value > 100 || value < -1;
    const uint8_t old = cell;
    const bool take = old == NO_INFORMATION ? cost >= INSCRIBED_INFLATED_OBSTACLE : cost > old;
    cell = take ? cost : old;
  });
  if (invalid && !warned_invalid_.exchange(true))
    context_->report(Severity::Warn, "invalid_values",
                     name_ + ": the mask holds values outside -1..100 (invalid in an OccupancyGrid); they are "
                             "skipped");
}
}  // namespace costmap_layers
