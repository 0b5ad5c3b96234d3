// zoneCentroid(): where zone_server writes a shape's name. Expected points worked out by hand in the
// comments (area-weighted sums of rectangles and triangles whose centroids are known).
#include <gtest/gtest.h>

#include <vector>

#include "costmap_layers/core/zones/zone_set.hpp"

using namespace costmap_layers;

namespace
{
ZoneShape polygon(std::vector<ZonePoint> points)
{
  ZoneShape s;
  s.name = "p";
  s.type = ZoneShapeType::Polygon;
  s.points = std::move(points);
  return s;
}
}  // namespace

TEST(ZoneCentroid, TriangleIsItsCornersMean)
{
  // example/zones.yaml's corner_keepout: x = (12.8 + 15.4 + 15.4) / 3, y = (5.4 + 5.4 + 6.6) / 3 = 5.8.
  const ZonePoint c = zoneCentroid(polygon({{12.8, 5.4}, {15.4, 5.4}, {15.4, 6.6}}));
  EXPECT_NEAR(c.x, 43.6 / 3.0, 1e-12);
  EXPECT_NEAR(c.y, 5.8, 1e-12);
}

TEST(ZoneCentroid, ConcavePolygonIsWeightedByAreaNotVertices)
{
  // The L 0..4 x 0..1 (area 4, centre (2, 0.5)) plus 0..1 x 1..3 (area 2, centre (0.5, 2)):
  // x = (8 + 1) / 6 = 1.5, y = (2 + 4) / 6 = 1.0; its vertices' mean would be (5/3, 4/3).
  const ZonePoint c = zoneCentroid(polygon({{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}}));
  EXPECT_NEAR(c.x, 1.5, 1e-12);
  EXPECT_NEAR(c.y, 1.0, 1e-12);
}

TEST(ZoneCentroid, EitherWinding)
{
  // A rectangle 2..6 x -1..1 listed clockwise and counter-clockwise: its middle (4, 0) both times.
  for (const auto& pts : {std::vector<ZonePoint>{{2, -1}, {6, -1}, {6, 1}, {2, 1}},
                          std::vector<ZonePoint>{{2, -1}, {2, 1}, {6, 1}, {6, -1}}})
  {
    const ZonePoint c = zoneCentroid(polygon(pts));
    EXPECT_NEAR(c.x, 4.0, 1e-12);
    EXPECT_NEAR(c.y, 0.0, 1e-12);
  }
}

TEST(ZoneCentroid, FarFromTheOriginKeepsPrecision)
{
  // The same L moved by (1234567.3, 2345678.9): (1234568.8, 2345679.9). Summed in absolute coordinates
  // the cross products reach 3e12 m^2 and cancel to a few m^2: the result is then tens of metres off.
  const double X = 1234567.3, Y = 2345678.9;
  const ZonePoint c =
      zoneCentroid(polygon({{X, Y}, {X + 4, Y}, {X + 4, Y + 1}, {X + 1, Y + 1}, {X + 1, Y + 3}, {X, Y + 3}}));
  EXPECT_NEAR(c.x, 1234568.8, 1e-6);
  EXPECT_NEAR(c.y, 2345679.9, 1e-6);
}

TEST(ZoneCentroid, CircleIsItsCentre)
{
  ZoneShape s;
  s.type = ZoneShapeType::Circle;
  s.center = {14.2, 3.4};
  s.radius = 0.5;
  const ZonePoint c = zoneCentroid(s);
  EXPECT_EQ(c.x, 14.2);
  EXPECT_EQ(c.y, 3.4);
}

TEST(ZoneCentroid, ZeroAreaGivesTheVerticesMean)
{
  // Never a valid shape (validation refuses it), but no division by zero: (0 + 1 + 3) / 3, (0 + 1 + 3) / 3.
  const ZonePoint c = zoneCentroid(polygon({{0, 0}, {1, 1}, {3, 3}}));
  EXPECT_NEAR(c.x, 4.0 / 3.0, 1e-12);
  EXPECT_NEAR(c.y, 4.0 / 3.0, 1e-12);
}
