#include "costmap_layers/core/zones/zone_shapes.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "costmap_layers/core/rules/limits.hpp"

namespace costmap_layers
{
namespace
{
/// 17 significant digits: every double reads back to itself.
std::string exact(double v)
{
  char text[40];
  std::snprintf(text, sizeof(text), "%.17g", v);
  std::string s = text;
  // Keep it a YAML float (a plain "1" would read back as an int, which is fine, but "1.0" says metres).
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

bool finiteCoordinate(double v)
{
  return std::isfinite(v) && std::abs(v) <= limits::kMaxCoordinate;
}

/// Sign of the cross product (b - a) x (c - a): > 0 left turn, < 0 right turn, 0 collinear.
double orient(const ZonePoint& a, const ZonePoint& b, const ZonePoint& c)
{
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/// c lies on the closed segment ab, given that it is collinear with it.
bool onSegment(const ZonePoint& a, const ZonePoint& b, const ZonePoint& c)
{
  return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
         c.y <= std::max(a.y, b.y);
}

/// Whether the closed segments ab and cd share a point.
bool segmentsMeet(const ZonePoint& a, const ZonePoint& b, const ZonePoint& c, const ZonePoint& d)
{
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
  return (o1 == 0 && onSegment(a, b, c)) || (o2 == 0 && onSegment(a, b, d)) || (o3 == 0 && onSegment(c, d, a)) ||
         (o4 == 0 && onSegment(c, d, b));
}

std::string where(const ZoneShape& s)
{
  return "shapes/" + (s.name.empty() ? std::string("(unnamed)") : s.name);
}

InputError validatePolygon(const ZoneShape& s)
{
  const auto& p = s.points;
  const std::string at = where(s) + "/points";
  if (p.size() < 3)
    return InputError::of(at, where(s) + ": a polygon needs at least 3 points (got " + std::to_string(p.size()) + ")");
  if (p.size() > limits::kMaxZoneVertices)
    return InputError::of(at, where(s) + ": a polygon may have at most " + std::to_string(limits::kMaxZoneVertices) +
                                  " points (got " + std::to_string(p.size()) + ")");
  for (std::size_t k = 0; k < p.size(); ++k)
    if (!finiteCoordinate(p[k].x) || !finiteCoordinate(p[k].y))
      return InputError::of(at, where(s) + ": point " + std::to_string(k) + " (" + valueText(p[k].x) + ", " +
                                    valueText(p[k].y) + ") must be finite and within " +
                                    valueText(limits::kMaxCoordinate) + " m");
  const std::size_t n = p.size();
  double area2 = 0.0;
  for (std::size_t k = 0; k < n; ++k)
  {
    const ZonePoint& a = p[k];
    const ZonePoint& b = p[(k + 1) % n];
    if (a.x == b.x && a.y == b.y)
      return InputError::of(at, where(s) + ": points " + std::to_string(k) + " and " + std::to_string((k + 1) % n) +
                                    " are the same point (" + valueText(a.x) + ", " + valueText(a.y) +
                                    "): a zero-length edge");
    area2 += a.x * b.y - b.x * a.y;
  }
  // Neighbouring edges (k-1, k) and (k, k+1) share vertex k; they must not fold back over each other.
  for (std::size_t k = 0; k < n; ++k)
  {
    const ZonePoint& a = p[(k + n - 1) % n];
    const ZonePoint& b = p[k];
    const ZonePoint& c = p[(k + 1) % n];
    if (orient(a, b, c) == 0 && (a.x - b.x) * (c.x - b.x) + (a.y - b.y) * (c.y - b.y) > 0)
      return InputError::of(at, where(s) + ": the edges at point " + std::to_string(k) + " (" + valueText(b.x) + ", " +
                                    valueText(b.y) + ") fold back over each other (self-intersecting)");
  }
  // Any two edges that are not neighbours must not meet.
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
    {
      if (j == i + 1 || (i == 0 && j == n - 1)) continue;  // neighbours
      if (segmentsMeet(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]))
        return InputError::of(at, where(s) + ": edge " + std::to_string(i) + "-" + std::to_string((i + 1) % n) +
                                      " meets edge " + std::to_string(j) + "-" + std::to_string((j + 1) % n) +
                                      ": the polygon is self-intersecting");
    }
  // Last: a bow tie has zero signed area too, and is better named self-intersecting.
  if (area2 == 0.0) return InputError::of(at, where(s) + ": the polygon has zero area (all points on one line)");
  return InputError::none();
}

/// The bounding box of a shape [m].
void bounds(const ZoneShape& s, double& x0, double& y0, double& x1, double& y1)
{
  if (s.type == ZoneShapeType::Circle)
  {
    x0 = s.center.x - s.radius, x1 = s.center.x + s.radius;
    y0 = s.center.y - s.radius, y1 = s.center.y + s.radius;
    return;
  }
  x0 = y0 = std::numeric_limits<double>::infinity();
  x1 = y1 = -std::numeric_limits<double>::infinity();
  for (const auto& q : s.points)
  {
    x0 = std::min(x0, q.x), x1 = std::max(x1, q.x);
    y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
  }
}

/// The cell visits drawing a shape takes at resolution r, an upper bound (limits::kMaxZoneRasterWork):
/// its bounding box in cells (one more on every side, as the cell ranges are widened), plus rows times
/// vertices for a polygon. In double: the counts reach 1e22 for shapes the extent check refuses later.
double rasterWork(const ZoneShape& s, double r)
{
  double x0, y0, x1, y1;
  bounds(s, x0, y0, x1, y1);
  const double cols = std::floor(x1 / r) - std::floor(x0 / r) + 3.0;
  const double rows = std::floor(y1 / r) - std::floor(y0 / r) + 3.0;
  return cols * rows + (s.type == ZoneShapeType::Polygon ? rows * static_cast<double>(s.points.size()) : 0.0);
}

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
      if ((a.y > y) != (b.y > y)) xs.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
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

/// A number from a tree node, or a clear error.
double number(const ParamValue& v, const std::string& what)
{
  if (!v.isNumber()) throw std::invalid_argument(what + " must be a number (got " + v.toString() + ")");
  return v.asDouble();
}

ZonePoint point(const ParamValue& v, const std::string& what)
{
  if (!v.isList() || v.asList().size() != 2)
    throw std::invalid_argument(what + " must be a list [x, y] (got " + v.toString() + ")");
  return {number(v.asList()[0], what + "[0]"), number(v.asList()[1], what + "[1]")};
}

int maskValue(const ParamValue& v, const std::string& what)
{
  if (v.type() != ParamValue::Type::Int || v.asInt() < -1 || v.asInt() > 100)
    throw std::invalid_argument(what + " must be an integer in -1..100 (got " + v.toString() + ")");
  return static_cast<int>(v.asInt());
}

void checkKeys(const ParamValue& map, const std::vector<std::string>& known, const std::string& what)
{
  for (const auto& [key, value] : map.entries())
    if (std::find(known.begin(), known.end(), key) == known.end())
    {
      std::string list;
      for (const auto& k : known)
        list += (list.empty() ? "" : ", ") + k;
      throw std::invalid_argument(what + ": unknown field '" + key + "' (known: " + list + ")");
    }
}
}  // namespace

const char* zoneOverlayName(ZoneOverlay overlay)
{
  switch (overlay)
  {
    case ZoneOverlay::Max:
      return "max";
    case ZoneOverlay::Min:
      return "min";
    default:
      return "last";
  }
}

bool pointInZonePolygon(const std::vector<ZonePoint>& p, double x, double y)
{
  bool inside = false;
  const std::size_t n = p.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    const ZonePoint& a = p[k];
    const ZonePoint& b = p[(k + 1) % n];
    if ((a.y > y) != (b.y > y) && x < a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y)) inside = !inside;
  }
  return inside;
}

InputError validateShape(const ZoneShape& s)
{
  // A bad name never goes into the key or the message whole: a peer's megabyte name would become a
  // megabyte log line and a megabyte entry of the log's throttle table.
  if (s.name.empty())
    return InputError::of("shapes/(unnamed)/name", "shapes/(unnamed): a shape name has 1..64 characters (got 0)");
  if (s.name.size() > 64)
    return InputError::of("shapes/(bad name)/name", "shape name '" + s.name.substr(0, 64) +
                                                        "...': a shape name has 1..64 characters (got " +
                                                        std::to_string(s.name.size()) + ")");
  for (const char c : s.name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
      return InputError::of("shapes/(bad name)/name", "shape name '" + s.name.substr(0, 64) +
                                                          "' may hold only letters, digits, '_', '-' and '.'");
  if (s.value < -1 || s.value > 100)
    return InputError::of(where(s) + "/value",
                          where(s) + ": value must be in -1..100 (got " + std::to_string(s.value) + ")");
  if (s.type == ZoneShapeType::Polygon) return validatePolygon(s);
  if (!finiteCoordinate(s.center.x) || !finiteCoordinate(s.center.y))
    return InputError::of(where(s) + "/center", where(s) + ": center (" + valueText(s.center.x) + ", " +
                                                    valueText(s.center.y) + ") must be finite and within " +
                                                    valueText(limits::kMaxCoordinate) + " m");
  if (!std::isfinite(s.radius) || s.radius <= 0.0 || s.radius > limits::kMaxCoordinate)
    return InputError::of(where(s) + "/radius", where(s) + ": radius must be finite, > 0 and at most " +
                                                    valueText(limits::kMaxCoordinate) + " m (got " +
                                                    valueText(s.radius) + ")");
  return InputError::none();
}

ZoneGridExtent zoneGridExtent(const ZoneLayout& layout)
{
  ZoneGridExtent e;
  if (layout.shapes.empty()) return e;  // the single cell [0, R) x [0, R)
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for (const auto& s : layout.shapes)
  {
    double a, b, c, d;
    bounds(s, a, b, c, d);
    x0 = std::min(x0, a), y0 = std::min(y0, b), x1 = std::max(x1, c), y1 = std::max(y1, d);
  }
  const double r = layout.resolution;
  // |coordinates| <= 2e7 and R >= 1e-4: lattice indices stay below 3e11, exact in double and int64.
  const int64_t i0 = static_cast<int64_t>(std::floor(x0 / r)) - 1, i1 = static_cast<int64_t>(std::floor(x1 / r)) + 1;
  const int64_t j0 = static_cast<int64_t>(std::floor(y0 / r)) - 1, j1 = static_cast<int64_t>(std::floor(y1 / r)) + 1;
  const uint64_t w = static_cast<uint64_t>(i1 - i0 + 1), h = static_cast<uint64_t>(j1 - j0 + 1);
  if (w > limits::kMaxGridCells || h > limits::kMaxGridCells || w * h > limits::kMaxGridCells)
    throw std::invalid_argument("the shapes span " + valueText(x1 - x0) + " m x " + valueText(y1 - y0) + " m: at " +
                                valueText(r) + " m/cell that is " + std::to_string(w) + " x " + std::to_string(h) +
                                " cells, more than the " + std::to_string(limits::kMaxGridCells) +
                                " cells a mask may have (use a coarser resolution or smaller shapes)");
  e.origin_x = static_cast<double>(i0) * r;
  e.origin_y = static_cast<double>(j0) * r;
  e.width = static_cast<uint32_t>(w);
  e.height = static_cast<uint32_t>(h);
  return e;
}

namespace
{
/// validateLayout(); with shapes_valid the shapes are known to be valid each (a ZoneSet's, but one that
/// validateShape() has checked), and only what concerns the layout as a whole is checked.
InputError checkLayout(const ZoneLayout& layout, bool shapes_valid)
{
  if (!std::isfinite(layout.resolution) || layout.resolution < limits::kMinResolution ||
      layout.resolution > limits::kMaxResolution)
    return InputError::of("resolution", "resolution must be in [" + valueText(limits::kMinResolution) + ", " +
                                            valueText(limits::kMaxResolution) + "] m/cell (got " +
                                            valueText(layout.resolution) + ")");
  if (layout.default_value < -1 || layout.default_value > 100)
    return InputError::of("default_value",
                          "default_value must be in -1..100 (got " + std::to_string(layout.default_value) + ")");
  if (layout.frame_id.empty()) return InputError::of("frame_id", "frame_id is empty");
  if (layout.shapes.size() > limits::kMaxZoneShapes)
    return InputError::of("shapes", "at most " + std::to_string(limits::kMaxZoneShapes) + " shapes (got " +
                                        std::to_string(layout.shapes.size()) + ")");
  double pairs = 0.0;
  for (const auto& s : layout.shapes)
  {
    if (s.type != ZoneShapeType::Polygon) continue;
    if (s.points.size() > limits::kMaxZoneVertices) return validateShape(s);  // names the shape, at once
    pairs += static_cast<double>(s.points.size()) * static_cast<double>(s.points.size());
  }
  if (pairs > limits::kMaxZoneVertexPairs)
    return InputError::of("shapes", "the polygons have " + valueText(pairs) +
                                        " vertices squared in all (the self-intersection check is quadratic), more "
                                        "than the " +
                                        valueText(limits::kMaxZoneVertexPairs) +
                                        " allowed: use fewer or simpler polygons (e.g. 20 of 1000 vertices)");
  for (std::size_t k = 0; k < layout.shapes.size(); ++k)
  {
    if (!shapes_valid)
    {
      const InputError e = validateShape(layout.shapes[k]);
      if (!e.ok()) return e;
    }
    for (std::size_t m = 0; m < k; ++m)
      if (layout.shapes[m].name == layout.shapes[k].name)
        return InputError::of(where(layout.shapes[k]) + "/name",
                              "two shapes are named '" + layout.shapes[k].name + "' (names must be unique)");
  }
  try
  {
    (void)zoneGridExtent(layout);
  }
  catch (const std::invalid_argument& e)
  {
    return InputError::of("extent", e.what());
  }
  double work = 0.0;
  for (const auto& s : layout.shapes)
    work += rasterWork(s, layout.resolution);
  if (work > limits::kMaxZoneRasterWork)
    return InputError::of("extent", "drawing these " + std::to_string(layout.shapes.size()) + " shapes at " +
                                        valueText(layout.resolution) + " m/cell takes about " + valueText(work) +
                                        " cell visits (their bounding boxes, and rows times vertices of each "
                                        "polygon), more than the " +
                                        valueText(limits::kMaxZoneRasterWork) +
                                        " allowed (use a coarser resolution, or fewer large shapes)");
  return InputError::none();
}

/// The mask of a layout known to be valid.
OccupancyGridData rasterizeValid(const ZoneLayout& layout)
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
}  // namespace

InputError validateLayout(const ZoneLayout& layout)
{
  return checkLayout(layout, false);
}

OccupancyGridData rasterizeZones(const ZoneLayout& layout)
{
  const InputError error = validateLayout(layout);
  if (!error.ok()) throw std::invalid_argument(error.message);
  return rasterizeValid(layout);
}

ZoneShape parseZoneShape(const ParamValue& v, const std::string& what)
{
  if (!v.isMap()) throw std::invalid_argument(what + " must be a map (got " + v.toString() + ")");
  ZoneShape s;
  const ParamValue* name = v.find("name");
  if (!name || name->type() != ParamValue::Type::String)
    throw std::invalid_argument(what + ": 'name' must be set to a string");
  s.name = name->asString();
  const std::string at = what + " (" + s.name + ")";
  const ParamValue* type = v.find("type");
  if (!type || type->type() != ParamValue::Type::String ||
      (type->asString() != "polygon" && type->asString() != "circle"))
    throw std::invalid_argument(at + ": 'type' must be \"polygon\" or \"circle\" (got " +
                                (type ? type->toString() : std::string("nothing")) + ")");
  s.type = type->asString() == "circle" ? ZoneShapeType::Circle : ZoneShapeType::Polygon;
  if (s.type == ZoneShapeType::Polygon)
    checkKeys(v, {"name", "type", "value", "fill", "points"}, at);
  else
    checkKeys(v, {"name", "type", "value", "fill", "center", "radius"}, at);
  const ParamValue* value = v.find("value");
  if (!value) throw std::invalid_argument(at + ": 'value' (the mask value, -1..100) must be set");
  s.value = maskValue(*value, at + ": value");
  if (const ParamValue* fill = v.find("fill"))
  {
    if (fill->type() != ParamValue::Type::Bool)
      throw std::invalid_argument(at + ": fill must be true or false (got " + fill->toString() + ")");
    s.fill = fill->asBool();
  }
  if (s.type == ZoneShapeType::Polygon)
  {
    const ParamValue* pts = v.find("points");
    if (!pts || !pts->isList())
      throw std::invalid_argument(at + ": 'points' must be a list of [x, y] (got " +
                                  (pts ? pts->toString() : std::string("nothing")) + ")");
    if (pts->asList().size() > limits::kMaxZoneVertices)
      throw std::invalid_argument(at + ": at most " + std::to_string(limits::kMaxZoneVertices) + " points (got " +
                                  std::to_string(pts->asList().size()) + ")");
    for (std::size_t k = 0; k < pts->asList().size(); ++k)
      s.points.push_back(point(pts->asList()[k], at + ": points[" + std::to_string(k) + "]"));
  }
  else
  {
    const ParamValue* c = v.find("center");
    const ParamValue* r = v.find("radius");
    if (!c || !r) throw std::invalid_argument(at + ": a circle needs 'center' [x, y] and 'radius'");
    s.center = point(*c, at + ": center");
    s.radius = number(*r, at + ": radius");
  }
  const InputError e = validateShape(s);
  if (!e.ok()) throw std::invalid_argument(what + ": " + e.message);
  return s;
}

ZoneLayout parseZoneLayout(const ParamValue& tree, const std::string& what)
{
  // A file that is not meant as a zone file is not quoted: zone_server loads files a peer names, and the
  // answer goes back to that peer.
  if (!tree.isMap()) throw std::invalid_argument(what + ": not a zone file (its top level is not a map)");
  const std::vector<std::string> known = {"frame_id", "resolution", "default_value", "overlay", "shapes"};
  if (std::none_of(known.begin(), known.end(), [&](const std::string& k) { return tree.find(k) != nullptr; }))
    throw std::invalid_argument(what +
                                ": not a zone file (none of frame_id, resolution, default_value, overlay, "
                                "shapes at its top level)");
  checkKeys(tree, known, what);
  ZoneLayout l;
  if (const ParamValue* f = tree.find("frame_id"))
  {
    if (f->type() != ParamValue::Type::String) throw std::invalid_argument(what + ": frame_id must be a string");
    l.frame_id = f->asString();
  }
  if (const ParamValue* r = tree.find("resolution")) l.resolution = number(*r, what + ": resolution");
  if (const ParamValue* d = tree.find("default_value")) l.default_value = maskValue(*d, what + ": default_value");
  if (const ParamValue* o = tree.find("overlay"))
  {
    const std::string name = o->type() == ParamValue::Type::String ? o->asString() : "";
    if (name == "last")
      l.overlay = ZoneOverlay::Last;
    else if (name == "max")
      l.overlay = ZoneOverlay::Max;
    else if (name == "min")
      l.overlay = ZoneOverlay::Min;
    else
      throw std::invalid_argument(what + ": overlay must be \"last\", \"max\" or \"min\" (got " + o->toString() + ")");
  }
  if (const ParamValue* shapes = tree.find("shapes"))
  {
    if (!shapes->isList() && !shapes->isNull())
      throw std::invalid_argument(what + ": shapes must be a list (got " + shapes->toString() + ")");
    if (shapes->isList())
    {
      if (shapes->asList().size() > limits::kMaxZoneShapes)
        throw std::invalid_argument(what + ": at most " + std::to_string(limits::kMaxZoneShapes) + " shapes (got " +
                                    std::to_string(shapes->asList().size()) + ")");
      for (std::size_t k = 0; k < shapes->asList().size(); ++k)
        l.shapes.push_back(parseZoneShape(shapes->asList()[k], what + ": shapes[" + std::to_string(k) + "]"));
    }
  }
  const InputError e = validateLayout(l);
  if (!e.ok()) throw std::invalid_argument(what + ": " + e.message);
  return l;
}

std::string zoneLayoutToYaml(const ZoneLayout& l)
{
  std::ostringstream y;
  // Frame ids and names are quoted: a name like "1" or "yes" must read back as a string.
  auto quoted = [](const std::string& s)
  {
    std::string out = "\"";
    for (const char c : s)
      out += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
    return out + "\"";
  };
  y << "# zone_server shapes (written by zone_server's save service)\n";
  y << "frame_id: " << quoted(l.frame_id) << "\n";
  y << "resolution: " << exact(l.resolution) << "\n";
  y << "default_value: " << l.default_value << "\n";
  y << "overlay: " << zoneOverlayName(l.overlay) << "\n";
  if (l.shapes.empty())
  {
    y << "shapes: []\n";
    return y.str();
  }
  y << "shapes:\n";
  for (const auto& s : l.shapes)
  {
    y << "  - name: " << quoted(s.name) << "\n";
    y << "    type: " << (s.type == ZoneShapeType::Circle ? "circle" : "polygon") << "\n";
    y << "    value: " << s.value << "\n";
    y << "    fill: " << (s.fill ? "true" : "false") << "\n";
    if (s.type == ZoneShapeType::Circle)
    {
      y << "    center: [" << exact(s.center.x) << ", " << exact(s.center.y) << "]\n";
      y << "    radius: " << exact(s.radius) << "\n";
    }
    else
    {
      y << "    points:\n";
      for (const auto& p : s.points)
        y << "      - [" << exact(p.x) << ", " << exact(p.y) << "]\n";
    }
  }
  return y.str();
}

std::vector<ZonePoint> zoneHandles(const ZoneShape& s)
{
  if (s.type == ZoneShapeType::Polygon) return s.points;
  return {s.center, {s.center.x + s.radius, s.center.y}};
}

ZoneSet::ZoneSet(ZoneLayout layout)
{
  const InputError e = validateLayout(layout);
  if (!e.ok()) throw std::invalid_argument(e.message);
  layout_ = std::move(layout);
}

const ZoneShape* ZoneSet::find(const std::string& name) const
{
  for (const auto& s : layout_.shapes)
    if (s.name == name) return &s;
  return nullptr;
}

OccupancyGridData ZoneSet::rasterize() const
{
  return rasterizeValid(layout_);
}

InputError ZoneSet::commit(ZoneLayout next, bool shapes_valid)
{
  const InputError e = checkLayout(next, shapes_valid);
  if (!e.ok()) return e;
  layout_ = std::move(next);
  return InputError::none();
}

InputError ZoneSet::upsert(const ZoneShape& shape)
{
  const InputError e = validateShape(shape);
  if (!e.ok()) return e;
  ZoneLayout next = layout_;
  auto it =
      std::find_if(next.shapes.begin(), next.shapes.end(), [&](const ZoneShape& s) { return s.name == shape.name; });
  if (it != next.shapes.end())
    *it = shape;
  else
    next.shapes.push_back(shape);
  return commit(std::move(next), true);  // the others were valid, the new one is
}

InputError ZoneSet::remove(const std::string& name)
{
  ZoneLayout next = layout_;
  auto it = std::find_if(next.shapes.begin(), next.shapes.end(), [&](const ZoneShape& s) { return s.name == name; });
  if (it == next.shapes.end())
    return InputError::of("shapes/" + std::string("(unknown)") + "/name",
                          "there is no shape named '" + name.substr(0, 64) + "'");
  next.shapes.erase(it);
  return commit(std::move(next), true);
}

InputError ZoneSet::moveHandle(const std::string& name, std::size_t index, double x, double y)
{
  const ZoneShape* found = find(name);
  if (!found) return InputError::of("shapes/(unknown)/name", "there is no shape named '" + name.substr(0, 64) + "'");
  ZoneShape s = *found;
  const std::size_t handles = zoneHandles(s).size();
  if (index >= handles)
    return InputError::of(where(s) + "/handle", where(s) + " has handles 0.." + std::to_string(handles - 1) + " (got " +
                                                    std::to_string(index) + ")");
  if (s.type == ZoneShapeType::Polygon)
    s.points[index] = {x, y};
  else if (index == 0)
    s.center = {x, y};
  else
    s.radius = std::hypot(x - s.center.x, y - s.center.y);
  return upsert(s);
}

InputError ZoneSet::replace(const ZoneLayout& layout)
{
  return commit(layout, false);
}
}  // namespace costmap_layers
