#include "costmap_layers/core/zones/zone_raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "costmap_layers/core/grid/polygon.hpp"

namespace costmap_layers
{
namespace
{
/// Writes one shape's claimed cells into values with the overlay rule; claimed marks cells already set.
class Painter
{
public:
  Painter(OccupancyGridData& grid, std::vector<uint8_t>& claimed, ZoneOverlay overlay, int8_t value)
      : g_(grid), claimed_(claimed), overlay_(overlay), value_(value)
  {
  }
  void paint(int64_t i, int64_t j)
  {
    const std::size_t k = static_cast<std::size_t>(j) * g_.width + static_cast<std::size_t>(i);
    if (!claimed_[k])
    {
      claimed_[k] = 1;
      g_.data[k] = value_;
      return;
    }
    switch (overlay_)
    {
      case ZoneOverlay::Last:
        g_.data[k] = value_;
        break;
      case ZoneOverlay::Max:
        g_.data[k] = std::max(g_.data[k], value_);
        break;
      case ZoneOverlay::Min:
        g_.data[k] = std::min(g_.data[k], value_);
        break;
    }
  }
  double cx(int64_t i) const { return g_.origin_x + (static_cast<double>(i) + 0.5) * g_.resolution; }
  double cy(int64_t j) const { return g_.origin_y + (static_cast<double>(j) + 0.5) * g_.resolution; }
  double x0(int64_t i) const { return g_.origin_x + static_cast<double>(i) * g_.resolution; }
  double y0(int64_t j) const { return g_.origin_y + static_cast<double>(j) * g_.resolution; }
  double res() const { return g_.resolution; }
  int64_t width() const { return g_.width; }
  int64_t height() const { return g_.height; }
  /// Columns (or rows) whose closed cell interval [x0(i), x0(i) + R] meets [lo, hi], clamped to the grid.
  void cellRange(double lo, double hi, double origin, int64_t size, int64_t& first, int64_t& last) const
  {
    const double r = g_.resolution;
    first = static_cast<int64_t>(std::floor((lo - origin) / r)) - 1;
    last = static_cast<int64_t>(std::floor((hi - origin) / r)) + 1;
    // Tighten by the exact test on the same expressions the cells use.
    while (first < last && origin + static_cast<double>(first) * r + r < lo)
      ++first;
    while (last >= first && origin + static_cast<double>(last) * r > hi)
      --last;
    first = std::max<int64_t>(first, 0);
    last = std::min<int64_t>(last, size - 1);
  }

private:
  OccupancyGridData& g_;
  std::vector<uint8_t>& claimed_;
  ZoneOverlay overlay_;
  int8_t value_;
};

void fillPolygon(Painter& pt, const std::vector<ZonePoint>& p)
{
  std::vector<double> xs;
  const std::size_t n = p.size();
  // Only the rows of the polygon's bounding box have crossings (rasterWork() counts these rows).
  double y_lo = std::numeric_limits<double>::infinity(), y_hi = -y_lo;
  for (const auto& q : p)
    y_lo = std::min(y_lo, q.y), y_hi = std::max(y_hi, q.y);
  int64_t j0, j1;
  pt.cellRange(y_lo, y_hi, pt.y0(0), pt.height(), j0, j1);
  for (int64_t j = j0; j <= j1; ++j)
  {
    const double y = pt.cy(j);
    xs.clear();
    for (std::size_t k = 0; k < n; ++k)
    {
      const ZonePoint& a = p[k];
      const ZonePoint& b = p[(k + 1) % n];
      if ((a.y > y) != (b.y > y)) xs.push_back(edgeCrossingX(a.x, a.y, b.x, b.y, y));
    }
    std::sort(xs.begin(), xs.end());
    // Inside when an odd number of crossings lies strictly right of the centre: [xs[2m], xs[2m+1]).
    for (std::size_t m = 0; m + 1 < xs.size(); m += 2)
    {
      const double lo = xs[m], hi = xs[m + 1];
      int64_t i = static_cast<int64_t>(std::floor((lo - pt.x0(0)) / pt.res())) - 1;
      i = std::max<int64_t>(i, 0);
      while (i < pt.width() && pt.cx(i) < lo)
        ++i;
      for (; i < pt.width() && pt.cx(i) < hi; ++i)
        pt.paint(i, j);
    }
  }
}

void fillCircle(Painter& pt, const ZoneShape& s)
{
  // Every centre within the radius lies in a cell whose square meets the bounding box.
  int64_t j0, j1, i0, i1;
  pt.cellRange(s.center.y - s.radius, s.center.y + s.radius, pt.y0(0), pt.height(), j0, j1);
  pt.cellRange(s.center.x - s.radius, s.center.x + s.radius, pt.x0(0), pt.width(), i0, i1);
  const double r2 = s.radius * s.radius;
  for (int64_t j = j0; j <= j1; ++j)
  {
    const double dy = pt.cy(j) - s.center.y;
    for (int64_t i = i0; i <= i1; ++i)
    {
      const double dx = pt.cx(i) - s.center.x;
      if (dx * dx + dy * dy <= r2) pt.paint(i, j);
    }
  }
}

/// The cells whose closed squares the closed segment ab meets.
void outlineSegment(Painter& pt, const ZonePoint& a, const ZonePoint& b, double r)
{
  int64_t j0, j1;
  pt.cellRange(std::min(a.y, b.y), std::max(a.y, b.y), pt.y0(0), pt.height(), j0, j1);
  for (int64_t j = j0; j <= j1; ++j)
  {
    const double sy0 = pt.y0(j), sy1 = sy0 + r;
    double xlo, xhi;
    if (a.y == b.y)
    {
      if (a.y < sy0 || a.y > sy1) continue;
      xlo = std::min(a.x, b.x), xhi = std::max(a.x, b.x);
    }
    else
    {
      // The part of the segment with y in [sy0, sy1]: parameters t in [0, 1].
      double t0 = (sy0 - a.y) / (b.y - a.y), t1 = (sy1 - a.y) / (b.y - a.y);
      if (t0 > t1) std::swap(t0, t1);
      t0 = std::max(t0, 0.0), t1 = std::min(t1, 1.0);
      if (t0 > t1) continue;
      const double xa = t0 == 0.0 ? a.x : (t0 == 1.0 ? b.x : a.x + t0 * (b.x - a.x));
      const double xb = t1 == 0.0 ? a.x : (t1 == 1.0 ? b.x : a.x + t1 * (b.x - a.x));
      xlo = std::min(xa, xb), xhi = std::max(xa, xb);
    }
    int64_t i0, i1;
    pt.cellRange(xlo, xhi, pt.x0(0), pt.width(), i0, i1);
    for (int64_t i = i0; i <= i1; ++i)
      pt.paint(i, j);
  }
}

/// The cells whose closed squares the circle's curve meets: nearest point of the square within the
/// radius and farthest corner at or beyond it.
void outlineCircle(Painter& pt, const ZoneShape& s, double r)
{
  int64_t j0, j1, i0, i1;
  pt.cellRange(s.center.y - s.radius, s.center.y + s.radius, pt.y0(0), pt.height(), j0, j1);
  pt.cellRange(s.center.x - s.radius, s.center.x + s.radius, pt.x0(0), pt.width(), i0, i1);
  const double r2 = s.radius * s.radius;
  for (int64_t j = j0; j <= j1; ++j)
  {
    const double ya = pt.y0(j), yb = ya + r;
    const double ny = std::clamp(s.center.y, ya, yb) - s.center.y;
    const double fy = std::max(std::abs(ya - s.center.y), std::abs(yb - s.center.y));
    for (int64_t i = i0; i <= i1; ++i)
    {
      const double xa = pt.x0(i), xb = xa + r;
      const double nx = std::clamp(s.center.x, xa, xb) - s.center.x;
      const double fx = std::max(std::abs(xa - s.center.x), std::abs(xb - s.center.x));
      if (nx * nx + ny * ny <= r2 && fx * fx + fy * fy >= r2) pt.paint(i, j);
    }
  }
}
}  // namespace

bool pointInZonePolygon(const std::vector<ZonePoint>& p, double x, double y)
{
  return pointInPolygon(p, x, y, CrossingOrigin::EdgeStart);
}

OccupancyGridData rasterizeValidLayout(const ZoneLayout& layout)
{
  const ZoneGridExtent e = zoneGridExtent(layout);
  OccupancyGridData g;
  g.frame_id = layout.frame_id;
  g.resolution = layout.resolution;
  g.origin_x = e.origin_x;
  g.origin_y = e.origin_y;
  g.width = e.width;
  g.height = e.height;
  g.data.assign(static_cast<std::size_t>(e.width) * e.height, static_cast<int8_t>(layout.default_value));
  std::vector<uint8_t> claimed(g.data.size(), 0);
  for (const auto& s : layout.shapes)
  {
    Painter pt(g, claimed, layout.overlay, static_cast<int8_t>(s.value));
    if (s.type == ZoneShapeType::Circle)
    {
      if (s.fill)
        fillCircle(pt, s);
      else
        outlineCircle(pt, s, layout.resolution);
    }
    else if (s.fill)
      fillPolygon(pt, s.points);
    else
      for (std::size_t k = 0; k < s.points.size(); ++k)
        outlineSegment(pt, s.points[k], s.points[(k + 1) % s.points.size()], layout.resolution);
  }
  return g;
}

OccupancyGridData rasterizeZones(const ZoneLayout& layout)
{
  const InputError error = validateLayout(layout);
  if (!error.ok()) throw std::invalid_argument(error.message);
  return rasterizeValidLayout(layout);
}
}  // namespace costmap_layers
