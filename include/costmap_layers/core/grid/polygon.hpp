// The point-in-polygon rule of the package, in one place: the even-odd crossing number with a
// half-open rule. The ray from (x, y) runs toward +x; an edge counts when exactly one of its end points
// lies above the point ("above" meaning y_end > y, so an end point at the point's own y counts as
// below) and the crossing lies strictly right of it (x < x_cross). Two polygons sharing an edge
// therefore never both claim a point on it, and a horizontal edge never counts.
//
// The abscissa of the crossing is interpolated from one end point of the edge. Algebraically the end
// point does not matter; in floating point it does for a point lying exactly on an edge or vertex
// (the two ways round differ in the last bit of x_cross). Each caller keeps the end it has always
// used, so that its answers on edges stay what they were:
//  - CrossingOrigin::EdgeStart (zones: pointInZonePolygon(), the zone rasteriser's scan lines):
//    edge k runs from vertex k to k + 1 and interpolates from vertex k;
//  - CrossingOrigin::EdgeEnd (KeepoutFilter's footprint test): interpolates from vertex k + 1.
// Off the edges the two give the same answer.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace costmap_layers
{
enum class CrossingOrigin
{
  EdgeStart,  ///< x_cross interpolated from vertex k of edge (k, k + 1)
  EdgeEnd     ///< x_cross interpolated from vertex k + 1
};

/// The abscissa where the line through (ox, oy) and (ex, ey) has ordinate y, interpolated from
/// (ox, oy). Only meaningful when oy != ey (the crossing rule calls it only then).
inline double edgeCrossingX(double ox, double oy, double ex, double ey, double y)
{
  return ox + (y - oy) * (ex - ox) / (ey - oy);
}

/// Whether the edge between (ax, ay) and (bx, by) crosses the ray from (x, y) toward +x by the rule
/// above, interpolating from (ax, ay).
inline bool edgeCrossesRay(double ax, double ay, double bx, double by, double x, double y)
{
  return (ay > y) != (by > y) && x < edgeCrossingX(ax, ay, bx, by, y);
}

namespace polygon_detail
{
// The vertex types the callers use: Eigen vectors (x()) and plain structs with x / y members.
inline double xOf(const Eigen::Vector2d& p)
{
  return p.x();
}
inline double yOf(const Eigen::Vector2d& p)
{
  return p.y();
}
template <typename Point>
double xOf(const Point& p)
{
  return p.x;
}
template <typename Point>
double yOf(const Point& p)
{
  return p.y;
}
}  // namespace polygon_detail

/// Whether (x, y) lies inside the polygon by the crossing rule above. The vertices are in order and the
/// chain closes by itself; callers pass at least 3 (fewer make no area, and the answer means nothing).
/// Units are the caller's (metres, or grid cells).
template <typename Point>
bool pointInPolygon(const std::vector<Point>& polygon, double x, double y, CrossingOrigin origin)
{
  using polygon_detail::xOf;
  using polygon_detail::yOf;
  bool inside = false;
  const std::size_t n = polygon.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    const Point& s = polygon[k];
    const Point& e = polygon[(k + 1) % n];
    const bool crosses = origin == CrossingOrigin::EdgeStart ? edgeCrossesRay(xOf(s), yOf(s), xOf(e), yOf(e), x, y)
                                                             : edgeCrossesRay(xOf(e), yOf(e), xOf(s), yOf(s), x, y);
    if (crosses) inside = !inside;
  }
  return inside;
}
}  // namespace costmap_layers
