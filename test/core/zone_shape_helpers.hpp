// Zone shapes as the zone tests write them (test/core/zones and test/io both build layouts).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "costmap_layers/core/zones/zone_shapes.hpp"

namespace costmap_layers
{
inline ZoneShape polygon(const std::string& name, std::vector<ZonePoint> points, int value = 100, bool fill = true)
{
  ZoneShape s;
  s.name = name;
  s.type = ZoneShapeType::Polygon;
  s.points = std::move(points);
  s.value = value;
  s.fill = fill;
  return s;
}

inline ZoneShape circle(const std::string& name, double cx, double cy, double r, int value = 100, bool fill = true)
{
  ZoneShape s;
  s.name = name;
  s.type = ZoneShapeType::Circle;
  s.center = {cx, cy};
  s.radius = r;
  s.value = value;
  s.fill = fill;
  return s;
}
}  // namespace costmap_layers
