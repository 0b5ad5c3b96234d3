#include "costmap_layers/core/costmap/costmap_clearing.hpp"

#include <algorithm>
#include <cmath>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/costmap/costmap_layer.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"

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

/// What a cleared cell holds: NO_INFORMATION, as costmap_2d's CostmapLayer::clearArea (and Nav2's)
/// writes whatever the layer's default value: the layer forgets the cell, and until it sees the cell
/// again the master keeps what the layers below give there (a static map's unknown stays unknown).
constexpr uint8_t kCleared = NO_INFORMATION;

/// Clears every cell of the layer's grid but those of [kx0, kx1] x [ky0, ky1] (inside the grid).
void clearOutside(CostmapLayer& layer, unsigned kx0, unsigned kx1, unsigned ky0, unsigned ky1)
{
  const Costmap2D& grid = layer.costmap();
  const unsigned sx = grid.getSizeInCellsX(), sy = grid.getSizeInCellsY();
  // The bands below, above, left and right of the kept rectangle.
  layer.clearCells(0, 0, sx, ky0, kCleared);
  layer.clearCells(0, ky1 + 1, sx, sy, kCleared);
  layer.clearCells(0, ky0, kx0, ky1 + 1, kCleared);
  layer.clearCells(kx1 + 1, ky0, sx, ky1 + 1, kCleared);
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
  if (!std::isfinite(x) || !std::isfinite(y) || !(keep_size >= 0.0)) return -1;
  const double half = keep_size / 2.0;
  int n = 0;
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
    const Costmap2D& grid = grid_layer->costmap();
    const unsigned sx = grid.getSizeInCellsX(), sy = grid.getSizeInCellsY();
    // The kept square in cell coordinates, in double: the robot may be off the grid by any distance
    // (worldToMapEnforceBounds would pull a square lying off the grid onto its edge cells). Then cut to
    // the grid; only the clamped values are converted to integers.
    const double res = grid.getResolution();
    auto cells = [res](double lo_m, double hi_m, double origin, unsigned size, unsigned& lo, unsigned& hi)
    {
      const double lo_c = std::floor((lo_m - origin) / res), hi_c = std::floor((hi_m - origin) / res);
      if (!(lo_c <= hi_c) || hi_c < 0.0 || lo_c >= static_cast<double>(size)) return false;  // off the grid
      lo = static_cast<unsigned>(std::max(lo_c, 0.0));
      hi = static_cast<unsigned>(std::min(hi_c, static_cast<double>(size) - 1.0));
      return true;
    };
    unsigned kx0, kx1, ky0, ky1;
    if (!cells(x - half, x + half, grid.getOriginX(), sx, kx0, kx1) ||
        !cells(y - half, y + half, grid.getOriginY(), sy, ky0, ky1))
    {
      grid_layer->clearCells(0, 0, sx, sy, kCleared);  // the square keeps nothing of this grid
      redrawAll(*grid_layer);
      continue;
    }
    clearOutside(*grid_layer, kx0, kx1, ky0, ky1);
    redrawAll(*grid_layer);
  }
  return n;
}

bool clearLayerArea(Layer& layer, int x0, int y0, int x1, int y1, bool invert)
{
  if (!layer.isClearable()) return false;
  auto* grid_layer = dynamic_cast<CostmapLayer*>(&layer);
  if (grid_layer == nullptr)
  {
    layer.reset();
    return true;
  }
  const Costmap2D& grid = grid_layer->costmap();
  const long long sx = grid.getSizeInCellsX(), sy = grid.getSizeInCellsY();
  // The cells strictly between, cut to the grid (in 64 bits: x0 + 1 may not fit an int).
  const long long ix0 = std::max<long long>(x0 + 1LL, 0), ix1 = std::min<long long>(x1 - 1LL, sx - 1);
  const long long iy0 = std::max<long long>(y0 + 1LL, 0), iy1 = std::min<long long>(y1 - 1LL, sy - 1);
  const bool between = ix0 <= ix1 && iy0 <= iy1;
  if (invert)
  {
    if (between)
      grid_layer->clearCells(static_cast<unsigned>(ix0), static_cast<unsigned>(iy0), static_cast<unsigned>(ix1 + 1),
                             static_cast<unsigned>(iy1 + 1), kCleared);
  }
  else if (!between)
  {
    grid_layer->clearCells(0, 0, static_cast<unsigned>(sx), static_cast<unsigned>(sy), kCleared);
  }
  else
  {
    clearOutside(*grid_layer, static_cast<unsigned>(ix0), static_cast<unsigned>(ix1), static_cast<unsigned>(iy0),
                 static_cast<unsigned>(iy1));
  }
  redrawAll(*grid_layer);
  return true;
}

bool resetLayerCells(Layer& layer)
{
  auto* grid_layer = dynamic_cast<CostmapLayer*>(&layer);
  if (grid_layer == nullptr) return false;
  const Costmap2D& grid = grid_layer->costmap();
  grid_layer->clearCells(0, 0, grid.getSizeInCellsX(), grid.getSizeInCellsY(), grid.getDefaultValue());
  redrawAll(*grid_layer);
  return true;
}
}  // namespace costmap_layers
