#include "costmap_layers/core/zones/zone_set.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "costmap_layers/core/zones/zone_raster.hpp"

namespace costmap_layers
{
std::vector<ZonePoint> zoneHandles(const ZoneShape& s)
{
  if (s.type == ZoneShapeType::Polygon) return s.points;
  return {s.center, {s.center.x + s.radius, s.center.y}};
}

ZonePoint zoneCentroid(const ZoneShape& s)
{
  if (s.type == ZoneShapeType::Circle || s.points.empty()) return s.center;
  const ZonePoint o = s.points.front();
  // Fan of triangles from the first vertex: each adds its signed double area and that times the sum of
  // its corners (the centroid of a triangle is its corners' mean).
  double area2 = 0.0, cx = 0.0, cy = 0.0, mx = 0.0, my = 0.0;
  for (std::size_t k = 0; k < s.points.size(); ++k)
  {
    const double ax = s.points[k].x - o.x, ay = s.points[k].y - o.y;
    mx += ax;
    my += ay;
    if (k == 0 || k + 1 == s.points.size()) continue;
    const double bx = s.points[k + 1].x - o.x, by = s.points[k + 1].y - o.y;
    const double a = ax * by - bx * ay;
    area2 += a;
    cx += a * (ax + bx);
    cy += a * (ay + by);
  }
  if (area2 == 0.0)
  {
    const double n = static_cast<double>(s.points.size());
    return {o.x + mx / n, o.y + my / n};
  }
  return {o.x + cx / (3.0 * area2), o.y + cy / (3.0 * area2)};
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
  return rasterizeValidLayout(layout_);
}

InputError ZoneSet::commit(ZoneLayout next, bool shapes_valid)
{
  const InputError e = shapes_valid ? validateLayoutOfValidShapes(next) : validateLayout(next);
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
                          "there is no shape named " + zoneNameText(name));
  next.shapes.erase(it);
  return commit(std::move(next), true);
}

InputError ZoneSet::moveHandle(const std::string& name, std::size_t index, double x, double y)
{
  const ZoneShape* found = find(name);
  if (!found) return InputError::of("shapes/(unknown)/name", "there is no shape named " + zoneNameText(name));
  ZoneShape s = *found;
  const std::size_t handles = zoneHandles(s).size();
  if (index >= handles)
    return InputError::of(
        zoneShapePath(s) + "/handle",
        zoneShapePath(s) + " has handles 0.." + std::to_string(handles - 1) + " (got " + std::to_string(index) + ")");
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
