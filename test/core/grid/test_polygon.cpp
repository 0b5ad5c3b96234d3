// The one point-in-polygon rule (grid/polygon.hpp), with worked values, and a check that each former
// copy (KeepoutFilter's insidePolygon, the zones' pointInZonePolygon) is reproduced bit for bit on the
// points where they differed: on edges and vertices.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include <Eigen/Core>

#include "costmap_layers/core/grid/polygon.hpp"

namespace costmap_layers
{
namespace
{
struct Pt
{
  double x, y;
};

const std::vector<Pt> kSquare{{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}};

TEST(Polygon, UnitSquareHalfOpenRule)
{
  for (const CrossingOrigin o : {CrossingOrigin::EdgeStart, CrossingOrigin::EdgeEnd})
  {
    EXPECT_TRUE(pointInPolygon(kSquare, 0.5, 0.5, o));
    EXPECT_FALSE(pointInPolygon(kSquare, 1.5, 0.5, o));
    EXPECT_FALSE(pointInPolygon(kSquare, -0.5, 0.5, o));
    // Left edge: the right edge crosses at x = 1 > 0, the left one at 0, not right of 0: one crossing.
    EXPECT_TRUE(pointInPolygon(kSquare, 0.0, 0.5, o));
    // Right edge: nothing right of x = 1.
    EXPECT_FALSE(pointInPolygon(kSquare, 1.0, 0.5, o));
    // Bottom edge y = 0: the side edges have one end at y = 0 (not above) and one above: they count.
    EXPECT_TRUE(pointInPolygon(kSquare, 0.5, 0.0, o));
    // Top edge y = 1: no end point is above y = 1.
    EXPECT_FALSE(pointInPolygon(kSquare, 0.5, 1.0, o));
    // Vertices: only the bottom-left one is claimed.
    EXPECT_TRUE(pointInPolygon(kSquare, 0.0, 0.0, o));
    EXPECT_FALSE(pointInPolygon(kSquare, 1.0, 0.0, o));
    EXPECT_FALSE(pointInPolygon(kSquare, 1.0, 1.0, o));
    EXPECT_FALSE(pointInPolygon(kSquare, 0.0, 1.0, o));
  }
}

TEST(Polygon, ConcaveAndEigenVertices)
{
  // An L: (0,0) (2,0) (2,1) (1,1) (1,2) (0,2); the notch [1,2] x [1,2] is outside.
  const std::vector<Eigen::Vector2d> l{{0.0, 0.0}, {2.0, 0.0}, {2.0, 1.0}, {1.0, 1.0}, {1.0, 2.0}, {0.0, 2.0}};
  EXPECT_TRUE(pointInPolygon(l, 0.5, 0.5, CrossingOrigin::EdgeEnd));
  EXPECT_TRUE(pointInPolygon(l, 1.5, 0.5, CrossingOrigin::EdgeEnd));
  EXPECT_TRUE(pointInPolygon(l, 0.5, 1.5, CrossingOrigin::EdgeEnd));
  EXPECT_FALSE(pointInPolygon(l, 1.5, 1.5, CrossingOrigin::EdgeEnd));
  EXPECT_FALSE(pointInPolygon(l, 2.5, 0.5, CrossingOrigin::EdgeEnd));
}

TEST(Polygon, CrossingAbscissa)
{
  EXPECT_EQ(edgeCrossingX(0.0, 0.0, 2.0, 4.0, 1.0), 0.5);
  EXPECT_EQ(edgeCrossingX(2.0, 4.0, 0.0, 0.0, 1.0), 0.5);
  EXPECT_TRUE(edgeCrossesRay(0.0, 0.0, 2.0, 4.0, 0.25, 1.0));
  EXPECT_FALSE(edgeCrossesRay(0.0, 0.0, 2.0, 4.0, 0.5, 1.0));   // on the edge: not strictly left of it
  EXPECT_FALSE(edgeCrossesRay(0.0, 1.0, 2.0, 1.0, -1.0, 1.0));  // horizontal: never
}

TEST(Polygon, OriginDecidesOnlyOnTheEdge)
{
  // Triangle (0,0) (0.1,0.1) (0,0.4); (0.05, 0.25) is the midpoint of the edge (0.1,0.1)-(0,0.4).
  // From (0.1, 0.1): 0.1 + (0.25 - 0.1) * (0 - 0.1) / (0.4 - 0.1) = 0.050000000000000017 > 0.05: inside.
  // From (0, 0.4): 0 + (0.25 - 0.4) * (0.1 - 0) / (0.1 - 0.4) = 0.050000000000000003, which is the
  // double 0.05 itself, and 0.05 < 0.05 is false: outside.
  const std::vector<Pt> t{{0.0, 0.0}, {0.1, 0.1}, {0.0, 0.4}};
  EXPECT_EQ(edgeCrossingX(0.1, 0.1, 0.0, 0.4, 0.25), 0.050000000000000017);
  EXPECT_EQ(edgeCrossingX(0.0, 0.4, 0.1, 0.1, 0.25), 0.05);
  EXPECT_TRUE(pointInPolygon(t, 0.05, 0.25, CrossingOrigin::EdgeStart));
  EXPECT_FALSE(pointInPolygon(t, 0.05, 0.25, CrossingOrigin::EdgeEnd));
  // Off the edge the origin does not matter.
  EXPECT_TRUE(pointInPolygon(t, 0.02, 0.2, CrossingOrigin::EdgeStart));
  EXPECT_TRUE(pointInPolygon(t, 0.02, 0.2, CrossingOrigin::EdgeEnd));
  EXPECT_FALSE(pointInPolygon(t, 0.08, 0.3, CrossingOrigin::EdgeStart));
  EXPECT_FALSE(pointInPolygon(t, 0.08, 0.3, CrossingOrigin::EdgeEnd));
}

// The two copies this rule replaced, as they were written, to show that each caller's answers stay.
bool formerKeepoutInside(const std::vector<Eigen::Vector2d>& polygon, double px, double py)
{
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
  {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    if ((a.y() > py) != (b.y() > py) && px < (b.x() - a.x()) * (py - a.y()) / (b.y() - a.y()) + a.x()) inside = !inside;
  }
  return inside;
}

bool formerZoneInside(const std::vector<Pt>& p, double x, double y)
{
  bool inside = false;
  const std::size_t n = p.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    const Pt& a = p[k];
    const Pt& b = p[(k + 1) % n];
    if ((a.y > y) != (b.y > y) && x < a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y)) inside = !inside;
  }
  return inside;
}

TEST(Polygon, EachCallerKeepsItsFormerAnswersOnEdgesAndVertices)
{
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> coordinate(-10.0, 10.0), along(0.0, 1.0);
  std::size_t origins_differ = 0;
  for (int round = 0; round < 20000; ++round)
  {
    std::vector<Pt> zone(3 + round % 4);
    std::vector<Eigen::Vector2d> footprint;
    for (Pt& q : zone)
    {
      q = {coordinate(random), coordinate(random)};
      footprint.emplace_back(q.x, q.y);
    }
    for (std::size_t k = 0; k < zone.size(); ++k)
    {
      const Pt& a = zone[k];
      const Pt& b = zone[(k + 1) % zone.size()];
      const double s = along(random);
      for (const Pt& q :
           {a, Pt{a.x + s * (b.x - a.x), a.y + s * (b.y - a.y)}, Pt{coordinate(random), coordinate(random)}})
      {
        ASSERT_EQ(pointInPolygon(zone, q.x, q.y, CrossingOrigin::EdgeStart), formerZoneInside(zone, q.x, q.y));
        ASSERT_EQ(pointInPolygon(footprint, q.x, q.y, CrossingOrigin::EdgeEnd),
                  formerKeepoutInside(footprint, q.x, q.y));
        origins_differ += formerZoneInside(zone, q.x, q.y) != formerKeepoutInside(footprint, q.x, q.y) ? 1 : 0;
      }
    }
  }
  // The former copies did differ on edges: one shared rule had to keep the origin per caller.
  EXPECT_GT(origins_differ, 0u);
}
}  // namespace
}  // namespace costmap_layers
