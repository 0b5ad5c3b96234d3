// The base of filters that act through their outputs only (SpeedFilter, BinaryFilter,
// ZoneParameterFilter): they read the mask at the robot's cell and write no costs.
#pragma once

#include "costmap_layers/core/filters/costmap_filter.hpp"

namespace costmap_layers
{
/// A filter that acts through its outputs only (the robot's cell of the mask, in processPose()) and
/// writes no costs: a new mask, a switch or a rolling window asks for no redraw of the costmap.
class OutputFilter : public CostmapFilter
{
protected:
  bool drawsCosts() const final { return false; }
  void process(Costmap2D&, const CellWindow&, const OccupancyGridData&, const GridSampler&, double, double,
               double) final
  {
  }
};
}  // namespace costmap_layers
