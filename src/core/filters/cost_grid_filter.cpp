#include "costmap_layers/core/filters/cost_grid_filter.hpp"

#include <string>

#include "costmap_layers/core/costmap/layer_context.hpp"
#include "costmap_layers/core/grid/grid_sampler.hpp"
#include "costmap_layers/core/rules/cost_rules.hpp"

namespace costmap_layers
{
void CostGridFilter::process(Costmap2D& master_grid, const CellWindow&, const OccupancyGridData& mask,
                             const GridSampler& mapping, double, double, double)
{
  // The mask pointer changes only when a new mask was accepted: recompute its costs then, not per update.
  const std::shared_ptr<const OccupancyGridData>& current = activeMask();
  if (costs_for_ != current)
  {
    const std::size_t invalid = computeCosts(mask, costs_);
    costs_for_ = current;
    // Once per accepted mask (the node's log throttles by key): a later mask with other bad values is
    // named too, as the other filters do.
    if (invalid > 0)
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
}  // namespace costmap_layers
