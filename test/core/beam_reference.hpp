// An independent geometric reference for clearing rays (no Costmap2D raytracing): which cells a beam
// from a sensor origin towards a reading may clear and which it must clear.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "costmap_layers/core/grid/costmap_2d.hpp"

namespace costmap_layers_test
{
/// One clearing-only beam, checked against plain geometry (no Costmap2D call): the beam is the segment
/// from the origin O towards the reading P, cut at raytrace_max_range R and at the grid's border.
struct BeamCase
{
  double ox, oy, px, py;  // [m] as the layer sees them (P rounded to float like the buffered points)
  double r_min, r_max;    // [m] raytrace_min_range, raytrace_max_range
};

/// Where the ray from O along u leaves [x0, x1] x [y0, y1] (O inside): the slab method.
inline double exitDistance(double ox, double oy, double ux, double uy, double x0, double y0, double x1, double y1)
{
  double s = std::numeric_limits<double>::infinity();
  if (ux > 0) s = std::min(s, (x1 - ox) / ux);
  if (ux < 0) s = std::min(s, (x0 - ox) / ux);
  if (uy > 0) s = std::min(s, (y1 - oy) / uy);
  if (uy < 0) s = std::min(s, (y0 - oy) / uy);
  return s;
}

/// Violations of the geometric reference for the cells `cleared` (cell centres) of one beam, as text.
inline std::string checkBeam(const BeamCase& b, const costmap_layers::Costmap2D& grid, uint8_t cleared_value,
                             double lateral_cells, bool check_direction)
{
  const double h = grid.getResolution();
  const double dx = b.px - b.ox, dy = b.py - b.oy, d = std::hypot(dx, dy);
  const double ux = dx / d, uy = dy / d;
  const double x0 = grid.getOriginX(), y0 = grid.getOriginY();
  const double exit =
      exitDistance(b.ox, b.oy, ux, uy, x0, y0, x0 + grid.getSizeInMetersX(), y0 + grid.getSizeInMetersY());
  const double reach = std::min({d, b.r_max, exit});  // how far along the beam clearing goes
  std::ostringstream err;
  std::vector<std::pair<double, double>> centres;
  for (unsigned j = 0; j < grid.getSizeInCellsY(); ++j)
    for (unsigned i = 0; i < grid.getSizeInCellsX(); ++i)
    {
      if (grid.getCost(i, j) != cleared_value) continue;
      const double cx = x0 + (i + 0.5) * h, cy = y0 + (j + 0.5) * h;
      centres.push_back({cx, cy});
      const double along = (cx - b.ox) * ux + (cy - b.oy) * uy;
      const double across = std::fabs((cx - b.ox) * uy - (cy - b.oy) * ux);
      // At most lateral_cells beside the beam (see the callers for why).
      if (across > lateral_cells * h)
        err << " cell (" << i << "," << j << ") " << across / h << " cells beside the beam;";
      // Never beyond the reading nor the range (rounded up to whole cells, costmap_2d's cellDistance).
      if (along > std::min(d, b.r_max + h) + 0.75 * h)
        err << " cell (" << i << "," << j << ") " << along << " m along, reach " << reach << ";";
      if (std::hypot(cx - b.ox, cy - b.oy) < b.r_min - 1.25 * h)
        err << " cell (" << i << "," << j << ") inside raytrace_min_range;";
    }
  // A beam cut by the range keeps its direction: the line runs from the origin's cell towards the
  // reading (cut at the grid), not towards the cell where the range ends. Both ends of that line lie
  // within sqrt(2)/2 cell of the beam, so at `along` it strays from the beam moved to the origin cell's
  // centre by at most sqrt(2) cells * along / length, plus half a cell of Bresenham.
  const double length = std::min(d, exit);
  const double ocx = x0 + (std::floor((b.ox - x0) / h) + 0.5) * h, ocy = y0 + (std::floor((b.oy - y0) / h) + 0.5) * h;
  if (check_direction && d > b.r_max && length > 4 * h)
  {
    for (const auto& c : centres)
    {
      const double along = (c.first - ocx) * ux + (c.second - ocy) * uy;
      const double across = std::fabs((c.first - ocx) * uy - (c.second - ocy) * ux);
      const double allowed = 0.5 * h + std::sqrt(2.0) * h * std::max(0.0, along) / (length - 1.5 * h) + 1e-9;
      if (across > allowed)
      {
        err << " a cell " << across / h << " cells beside the beam from the origin's cell (allowed " << allowed / h
            << ");";
        break;
      }
    }
  }
  // Every stretch of the beam between min range + 1.5 cells and its reach - 1.5 cells has a cleared
  // cell within 1.5 cells (Bresenham visits one cell per column of the major axis).
  for (double s = b.r_min + 1.5 * h; s <= reach - 1.5 * h; s += 0.25 * h)
  {
    const double qx = b.ox + s * ux, qy = b.oy + s * uy;
    bool found = false;
    for (const auto& c : centres)
      found = found || std::hypot(c.first - qx, c.second - qy) <= 1.5 * h;
    if (!found)
    {
      err << " nothing cleared near " << s << " m along (reach " << reach << ");";
      break;
    }
  }
  return err.str();
}
}  // namespace costmap_layers_test
