#include "costmap_layers/core/zones/zone_layout.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "costmap_layers/core/rules/limits.hpp"

namespace costmap_layers
{
std::string zoneShapePath(const ZoneShape& s)
{
  return "shapes/" + (s.name.empty() ? std::string("(unnamed)") : s.name);
}

namespace
{
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
  return zoneShapePath(s);
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

std::string zoneNameText(const std::string& name)
{
  std::string shown;
  for (const char c : name.substr(0, 64))
    shown += c >= ' ' && c < 127 ? c : '?';
  return "'" + shown + (name.size() > 64 ? "...' (" + std::to_string(name.size()) + " bytes)" : "'");
}

std::size_t utf8ErrorAt(const std::string& text)
{
  const std::size_t n = text.size();
  for (std::size_t k = 0; k < n;)
  {
    const auto b = [&](std::size_t i) { return i < n ? static_cast<unsigned char>(text[i]) : 0u; };
    const unsigned c = b(k);
    // The second byte's range rules out overlong forms, surrogates and code points past U+10FFFF.
    std::size_t length = 0;
    unsigned lo = 0x80, hi = 0xBF;
    if (c < 0x80)
      length = 1;
    else if (c >= 0xC2 && c <= 0xDF)
      length = 2;
    else if (c >= 0xE0 && c <= 0xEF)
    {
      length = 3;
      if (c == 0xE0) lo = 0xA0;
      if (c == 0xED) hi = 0x9F;
    }
    else if (c >= 0xF0 && c <= 0xF4)
    {
      length = 4;
      if (c == 0xF0) lo = 0x90;
      if (c == 0xF4) hi = 0x8F;
    }
    else
      return k;
    for (std::size_t i = 1; i < length; ++i)
    {
      const unsigned d = b(k + i);
      if (d < (i == 1 ? lo : 0x80u) || d > (i == 1 ? hi : 0xBFu)) return k;
    }
    k += length;
  }
  return std::string::npos;
}

InputError validateShape(const ZoneShape& s)
{
  // A bad name never goes into the key or the message whole: a peer's megabyte name would become a
  // megabyte log line and a megabyte entry of the log's throttle table.
  if (const std::string why = labelProblem(s.name); !why.empty())
    return s.name.empty() ? InputError::of("shapes/(unnamed)/name", "a shape name is empty")
                          : InputError::of("shapes/(bad name)/name", "shape " + why);
  // A zone file is YAML, which holds Unicode text: bytes that are not UTF-8 would not read back.
  if (const std::size_t at = utf8ErrorAt(s.name); at != std::string::npos)
    return InputError::of("shapes/(bad name)/name",
                          "shape " + zoneNameText(s.name) + " is not UTF-8 at byte " + std::to_string(at));
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
  if (const std::string why = frameIdProblem(layout.frame_id); !why.empty())
    return InputError::of("frame_id", "frame_id " + why);
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
}  // namespace

InputError validateLayout(const ZoneLayout& layout)
{
  return checkLayout(layout, false);
}

InputError validateLayoutOfValidShapes(const ZoneLayout& layout)
{
  return checkLayout(layout, true);
}
}  // namespace costmap_layers
