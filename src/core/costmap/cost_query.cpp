#include "costmap_layers/core/costmap/cost_query.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "costmap_layers/core/grid/cost_values.hpp"

namespace costmap_layers
{
CostAnswer pointCost(const Costmap2D& grid, double x, double y)
{
  if (!std::isfinite(x) || !std::isfinite(y)) return {static_cast<double>(NO_INFORMATION), false};
  unsigned mx = 0, my = 0;
  if (!grid.worldToMap(x, y, mx, my)) return {static_cast<double>(LETHAL_OBSTACLE), false};
  return {static_cast<double>(grid.getCost(mx, my)), true};
}

CostAnswer footprintCostAtPose(const Costmap2D& grid, double x, double y, double yaw, const Footprint& footprint)
{
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(yaw))
    return {static_cast<double>(NO_INFORMATION), false};
  if (footprint.empty()) return pointCost(grid, x, y);
  const Footprint placed = transformFootprint(x, y, yaw, footprint);
  std::vector<std::pair<unsigned, unsigned>> cells;
  cells.reserve(placed.size());
  for (const auto& p : placed)
  {
    unsigned mx = 0, my = 0;
    if (!grid.worldToMap(p.x(), p.y(), mx, my)) return {static_cast<double>(LETHAL_OBSTACLE), true};
    cells.emplace_back(mx, my);
  }
  // One edge: LETHAL_OBSTACLE as soon as a lethal cell is met, else the edge's highest cost.
  auto edgeCost = [&grid](std::pair<unsigned, unsigned> a, std::pair<unsigned, unsigned> b)
  {
    double best = 0;
    bool lethal = false;
    grid.walkLine(
        [&](int cx, int cy)
        {
          const uint8_t c = grid.getCost(static_cast<unsigned>(cx), static_cast<unsigned>(cy));
          if (c == LETHAL_OBSTACLE) lethal = true;
          best = std::max(best, static_cast<double>(c));
        },
        static_cast<int>(a.first), static_cast<int>(a.second), static_cast<int>(b.first), static_cast<int>(b.second));
    return lethal ? static_cast<double>(LETHAL_OBSTACLE) : best;
  };
  if (cells.size() == 1) return {edgeCost(cells[0], cells[0]), true};
  double cost = 0;
  for (std::size_t k = 0; k + 1 < cells.size(); ++k)
  {
    cost = std::max(cost, edgeCost(cells[k], cells[k + 1]));
    if (cost == static_cast<double>(LETHAL_OBSTACLE)) return {cost, true};
  }
  return {std::max(cost, edgeCost(cells.back(), cells.front())), true};
}
}  // namespace costmap_layers
