// Nav2's GetCosts service (Costmap2DROS::getCostsCallback): the cost at a point of the master grid,
// or the cost of a footprint placed at a pose. Used by costmap_node's ~get_cost and costmap_tool --cost.
#pragma once

#include <cstddef>

#include "costmap_layers/core/grid/costmap_2d.hpp"
#include "costmap_layers/core/grid/footprint.hpp"

namespace costmap_layers
{
/// The most poses one query may hold; a longer list is refused whole (each pose of a footprint query
/// walks the footprint's outline: the bound keeps one request, made under the update lock, short).
constexpr std::size_t kMaxCostQueryPoses = 10000;

/// One answer of GetCosts: a cost 0..255 and whether it was found (Nav2's success flag).
struct CostAnswer
{
  double cost = 0;
  bool ok = false;
};

/// The cost of the cell holding (x, y). Off the grid: LETHAL_OBSTACLE and not ok, as Nav2 answers.
/// A non-finite coordinate: NO_INFORMATION and not ok (what Nav2 answers for a pose it cannot place).
CostAnswer pointCost(const Costmap2D& grid, double x, double y);

/// Nav2's FootprintCollisionChecker::footprintCostAtPose: the footprint turned by yaw and moved to
/// (x, y); the highest cost on its outline (each edge walked cell by cell, the closing edge too; the
/// inside is not looked at). A vertex off the grid gives LETHAL_OBSTACLE, still ok (as Nav2's success
/// stays true there). Nav2 stops at the first edge whose running maximum is exactly LETHAL_OBSTACLE,
/// and an edge holding a lethal cell counts as LETHAL_OBSTACLE even when it also holds NO_INFORMATION;
/// both kept, so that the answers are Nav2's. One vertex: its cell; no vertex: pointCost. A non-finite
/// x, y or yaw: NO_INFORMATION and not ok.
CostAnswer footprintCostAtPose(const Costmap2D& grid, double x, double y, double yaw, const Footprint& footprint);
}  // namespace costmap_layers
