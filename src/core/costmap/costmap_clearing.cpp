#include "costmap_layers/core/costmap/costmap_clearing.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

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

namespace
{
/// The cells of the grid that meet the square [x - half, x + half]^2 (upper edges excluded), as
/// [kx0, kx1] x [ky0, ky1]; false when the square misses the grid. Worked out in double: the centre may be
/// off the grid by any distance (worldToMapEnforceBounds would pull a square lying off the grid onto its
/// edge cells); only the values cut to the grid are converted to integers.
bool squareCells(const Costmap2D& grid, double x, double y, double half, unsigned& kx0, unsigned& kx1, unsigned& ky0,
                 unsigned& ky1)
{
  const double res = grid.getResolution();
  auto cells = [res](double lo_m, double hi_m, double origin, unsigned size, unsigned& lo, unsigned& hi)
  {
    const double lo_c = std::floor((lo_m - origin) / res), hi_c = std::floor((hi_m - origin) / res);
    if (!(lo_c <= hi_c) || hi_c < 0.0 || lo_c >= static_cast<double>(size)) return false;  // off the grid
    lo = static_cast<unsigned>(std::max(lo_c, 0.0));
    hi = static_cast<unsigned>(std::min(hi_c, static_cast<double>(size) - 1.0));
    return true;
  };
  return cells(x - half, x + half, grid.getOriginX(), grid.getSizeInCellsX(), kx0, kx1) &&
         cells(y - half, y + half, grid.getOriginY(), grid.getSizeInCellsY(), ky0, ky1);
}

void clearSquareOf(Layer& layer, double x, double y, double half, SquareClear mode)
{
  auto* grid_layer = dynamic_cast<CostmapLayer*>(&layer);
  if (grid_layer == nullptr)
  {
    layer.reset();
    return;
  }
  const Costmap2D& grid = grid_layer->costmap();
  unsigned kx0, kx1, ky0, ky1;
  const bool meets = squareCells(grid, x, y, half, kx0, kx1, ky0, ky1);
  if (mode == SquareClear::ClearSquare)
  {
    if (meets) grid_layer->clearCells(kx0, ky0, kx1 + 1, ky1 + 1, kCleared);
  }
  else if (meets)
  {
    clearOutside(*grid_layer, kx0, kx1, ky0, ky1);
  }
  else
  {
    grid_layer->clearCells(0, 0, grid.getSizeInCellsX(), grid.getSizeInCellsY(), kCleared);  // keeps nothing here
  }
  redrawAll(*grid_layer);
}

/// The plugins a clear acts on: the named ones, or every clearable one for an empty list.
std::vector<Layer*> clearTargets(const LayeredCostmap& costmap, const std::vector<std::string>& plugins)
{
  std::vector<Layer*> targets;
  for (const auto& layer : costmap.getPlugins())
  {
    const bool named = std::find(plugins.begin(), plugins.end(), layer->getName()) != plugins.end();
    if (plugins.empty() ? layer->isClearable() : named) targets.push_back(layer.get());
  }
  return targets;
}
}  // namespace

std::string clearPluginsProblem(const LayeredCostmap& costmap, const std::vector<std::string>& plugins)
{
  constexpr std::size_t kNamed = 5;  // names quoted in the message; the count says the rest
  std::string listed;
  std::size_t bad = 0;
  for (const auto& name : plugins)
  {
    const auto it = std::find_if(costmap.getPlugins().begin(), costmap.getPlugins().end(),
                                 [&name](const auto& l) { return l->getName() == name; });
    const char* why = it == costmap.getPlugins().end() ? "not found"
                      : !(*it)->isClearable()          ? "not clearable"
                                                       : nullptr;
    if (why == nullptr) continue;
    if (bad++ < kNamed)
      listed += (listed.empty() ? "" : ", ") + ("'" + name.substr(0, 64) + (name.size() > 64 ? "...'" : "'")) + " (" +
                why + ")";
  }
  if (bad == 0) return "";
  return "plugins: " + std::to_string(bad) + " of the " + std::to_string(plugins.size()) +
         " name(s) are not clearable plugins of this costmap: " + listed + (bad > kNamed ? ", ..." : "");
}

int clearSquare(LayeredCostmap& costmap, double x, double y, double size, SquareClear mode,
                const std::vector<std::string>& plugins, std::string& error)
{
  if (!std::isfinite(x) || !std::isfinite(y))
  {
    error = "the square's centre (" + std::to_string(x) + ", " + std::to_string(y) + ") is not finite";
    return -1;
  }
  if (!(size >= 0.0))
  {
    error = "reset_distance " + std::to_string(size) + " is not a distance >= 0";
    return -1;
  }
  error = clearPluginsProblem(costmap, plugins);
  if (!error.empty()) return -1;
  const auto targets = clearTargets(costmap, plugins);
  for (Layer* layer : targets)
    clearSquareOf(*layer, x, y, size / 2.0, mode);
  return static_cast<int>(targets.size());
}

int clearEntirely(LayeredCostmap& costmap, const std::vector<std::string>& plugins, std::string& error)
{
  error = clearPluginsProblem(costmap, plugins);
  if (!error.empty()) return -1;
  int n = 0;
  if (plugins.empty())
  {
    for (const auto* list : {&costmap.getPlugins(), &costmap.getFilters()})
      for (const auto& layer : *list)
      {
        layer->reset();
        if (auto* grid_layer = dynamic_cast<CostmapLayer*>(layer.get())) redrawAll(*grid_layer);
        ++n;
      }
  }
  else
  {
    for (Layer* layer : clearTargets(costmap, plugins))
    {
      if (!resetLayerCells(*layer)) layer->reset();
      ++n;
    }
  }
  costmap.requestFullUpdate();
  return n;
}

int clearClearableLayersAround(LayeredCostmap& costmap, double x, double y, double keep_size)
{
  std::string error;
  return clearSquare(costmap, x, y, keep_size, SquareClear::KeepSquare, {}, error);
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
