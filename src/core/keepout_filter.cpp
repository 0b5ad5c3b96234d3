#include "costmap_layers/core/keepout_filter.hpp"

#include <array>
#include <cmath>

#include "costmap_layers/core/cost_values.hpp"

namespace costmap_layers
{
void CostGridFilter::process(Costmap2D& master_grid, const CellWindow&, const OccupancyGridData& mask,
                             const MaskMapping& mapping, double, double, double)
{
  // The mask pointer changes only when a new mask was accepted: recompute its costs then, not per update.
  const std::shared_ptr<const OccupancyGridData>& current = activeMask();
  if (costs_for_ != current)
  {
    const std::size_t invalid = computeCosts(mask, costs_);
    costs_for_ = current;
    if (invalid > 0 && !warned_invalid_.exchange(true))
      context_->report(Severity::Warn, "invalid_values",
                       name_ + ": the mask holds " + std::to_string(invalid) +
                           " values outside -1..100 (invalid in an OccupancyGrid); they are skipped");
  }
  mapping.forEachRow(master_grid, costs_.data(), mask.width, mask.height, uint8_t{0}, scratch_,
                     [](uint8_t* cells, const uint8_t* costs, std::size_t n)
                     {
                       for (std::size_t k = 0; k < n; ++k)
                         cells[k] = mergeFilterCost(cells[k], costs[k]);
                     });
}

std::size_t KeepoutFilter::computeCosts(const OccupancyGridData& mask, std::vector<uint8_t>& costs)
{
  std::array<uint8_t, 256> table{};
  for (int b = 0; b < 256; ++b)
    table[static_cast<std::size_t>(b)] = maskValueCost(static_cast<int8_t>(b));
  costs.resize(mask.data.size());
  std::size_t invalid = 0;
  for (std::size_t k = 0; k < mask.data.size(); ++k)
  {
    const int8_t v = mask.data[k];
    invalid += (v < -1 || v > 100) ? 1 : 0;
    costs[k] = table[static_cast<uint8_t>(v)];
  }
  return invalid;
}
}  // namespace costmap_layers
