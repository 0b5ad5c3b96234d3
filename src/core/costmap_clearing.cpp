#include "costmap_layers/core/costmap_clearing.hpp"

#include <algorithm>
#include <cmath>

#include "costmap_layers/core/costmap_layer.hpp"
#include "costmap_layers/core/layered_costmap.hpp"

namespace costmap_layers
{
namespace
{
/// The master keeps what a layer drew until an update window covers it: ask for the whole grid.
void redrawAll(CostmapLayer& layer)
{
  const Costmap2D& grid = layer.costmap();
  layer.addExtraBounds(grid.getOriginX(), grid.getOriginY(), grid.getOriginX() + grid.getSizeInMetersX(),
                       grid.getOriginY() + grid.getSizeInMetersY());
}
}  // namespace

int resetClearableLayers(LayeredCostmap& costmap)
{
  int n = 0;
  for (const auto& layer : costmap.getPlugins())
  {
    if (!layer->isClearable()) continue;
    layer->reset();
    if (auto* grid_layer = dynamic_cast<CostmapLayer*>(layer.get())) redrawAll(*grid_layer);
    ++n;
  }
  return n;
}

int clearClearableLayersAround(LayeredCostmap& costmap, double x, double y, double keep_size)
{
  int n = 0;
  const double half = std::max(0.0, keep_size) / 2.0;
  for (const auto& layer : costmap.getPlugins())
  {
    if (!layer->isClearable()) continue;
    ++n;
    auto* grid_layer = dynamic_cast<CostmapLayer*>(layer.get());
    if (grid_layer == nullptr)
    {
      layer->reset();
      continue;
    }
    Costmap2D& grid = grid_layer->costmap();
    int kx0, ky0, kx1, ky1;
    grid.worldToMapEnforceBounds(x - half, y - half, kx0, ky0);
    grid.worldToMapEnforceBounds(x + half, y + half, kx1, ky1);
    const unsigned sx = grid.getSizeInCellsX(), sy = grid.getSizeInCellsY();
    // Everything but the kept square [kx0, kx1] x [ky0, ky1]: the bands below, above, left and right.
    grid.resetMap(0, 0, sx, static_cast<unsigned>(ky0));
    grid.resetMap(0, static_cast<unsigned>(ky1) + 1, sx, sy);
    grid.resetMap(0, static_cast<unsigned>(ky0), static_cast<unsigned>(kx0), static_cast<unsigned>(ky1) + 1);
    grid.resetMap(static_cast<unsigned>(kx1) + 1, static_cast<unsigned>(ky0), sx, static_cast<unsigned>(ky1) + 1);
    redrawAll(*grid_layer);
  }
  return n;
}
}  // namespace costmap_layers
