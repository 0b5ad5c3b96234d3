// Zones drawn as shapes: extent, fill and outline rules, overlay, validation and the checked edits of
// ZoneSet. Expected masks are derived by hand (cell indices written out in the comments) or by a brute
// force that uses another method than the code under test: integer arithmetic for circles, a
// same-side (sign of cross products) test for convex polygons, and a segment-versus-box test by
// sampling-free interval clipping in integer units.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <utility>

#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/core/zones/zone_shapes.hpp"
#include "zone_shape_helpers.hpp"

using namespace costmap_layers;

namespace
{
ZoneLayout layout(std::vector<ZoneShape> shapes, double resolution = 0.1, ZoneOverlay overlay = ZoneOverlay::Last)
{
  ZoneLayout l;
  l.resolution = resolution;
  l.overlay = overlay;
  l.shapes = std::move(shapes);
  return l;
}

std::set<std::pair<int, int>> cellsWith(const OccupancyGridData& g, int value)
{
  std::set<std::pair<int, int>> out;
  for (uint32_t j = 0; j < g.height; ++j)
    for (uint32_t i = 0; i < g.width; ++i)
      if (g.data[j * g.width + i] == value) out.insert({static_cast<int>(i), static_cast<int>(j)});
  return out;
}

std::set<std::pair<int, int>> block(int i0, int i1, int j0, int j1)
{
  std::set<std::pair<int, int>> out;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i)
      out.insert({i, j});
  return out;
}

// The rectangle used below: x in [0.32, 1.13], y in [0.47, 0.88], at 0.1 m/cell.
const std::vector<ZonePoint> kRect = {{0.32, 0.47}, {1.13, 0.47}, {1.13, 0.88}, {0.32, 0.88}};
}  // namespace

TEST(ZoneShapes, ExtentIsTheLatticeBoxPlusOneCell)
{
  // x: floor(0.32 / 0.1) - 1 = 2 .. floor(1.13 / 0.1) + 1 = 12 -> 11 columns from 0.2 m;
  // y: floor(0.47 / 0.1) - 1 = 3 .. floor(0.88 / 0.1) + 1 = 9 -> 7 rows from 0.3 m.
  const OccupancyGridData g = rasterizeZones(layout({polygon("r", kRect)}));
  EXPECT_EQ(g.width, 11u);
  EXPECT_EQ(g.height, 7u);
  EXPECT_NEAR(g.origin_x, 0.2, 1e-12);
  EXPECT_NEAR(g.origin_y, 0.3, 1e-12);
  EXPECT_EQ(g.frame_id, "map");
  EXPECT_DOUBLE_EQ(g.resolution, 0.1);
}

TEST(ZoneShapes, FilledRectangleHoldsTheCellsWhoseCentresAreInside)
{
  // Centres x = 0.25 + 0.1 i: inside (0.32, 1.13) for i = 1..8; y = 0.35 + 0.1 j: inside (0.47, 0.88)
  // for j = 2..5. Every other cell keeps default_value 0.
  const OccupancyGridData g = rasterizeZones(layout({polygon("r", kRect, 70)}));
  EXPECT_EQ(cellsWith(g, 70), block(1, 8, 2, 5));
  EXPECT_EQ(cellsWith(g, 0).size(), g.data.size() - 32);
}

TEST(ZoneShapes, OutlineRectangleIsTheRingOfCellsItsEdgesTouch)
{
  // Cell squares [0.2 + 0.1 i, +0.1] x [0.3 + 0.1 j, +0.1]: the left edge x = 0.32 lies in column 1,
  // the right edge 1.13 in column 9, the bottom y = 0.47 in row 1, the top 0.88 in row 5. The outline
  // is the ring of the 9 x 5 block: 45 - 7 * 3 = 24 cells.
  const OccupancyGridData g = rasterizeZones(layout({polygon("r", kRect, 55, false)}));
  auto expected = block(1, 9, 1, 5);
  for (const auto& c : block(2, 8, 2, 4))
    expected.erase(c);
  EXPECT_EQ(expected.size(), 24u);
  EXPECT_EQ(cellsWith(g, 55), expected);
}

TEST(ZoneShapes, FilledTriangleMatchesASameSideTest)
{
  // A convex triangle, counter-clockwise: a point is inside when it lies left of all three edges.
  const std::vector<ZonePoint> tri = {{0.13, 0.21}, {2.37, 0.58}, {0.91, 1.93}};
  const OccupancyGridData g = rasterizeZones(layout({polygon("t", tri, 100)}, 0.05));
  auto left = [](const ZonePoint& a, const ZonePoint& b, double x, double y)
  { return (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x) > 0; };
  std::set<std::pair<int, int>> expected;
  for (uint32_t j = 0; j < g.height; ++j)
    for (uint32_t i = 0; i < g.width; ++i)
    {
      const double x = g.origin_x + (i + 0.5) * g.resolution, y = g.origin_y + (j + 0.5) * g.resolution;
      if (left(tri[0], tri[1], x, y) && left(tri[1], tri[2], x, y) && left(tri[2], tri[0], x, y))
        expected.insert({static_cast<int>(i), static_cast<int>(j)});
    }
  EXPECT_GT(expected.size(), 600u);  // area about 1.78 m^2 = about 713 cells of 0.0025 m^2
  EXPECT_EQ(cellsWith(g, 100), expected);
}

TEST(ZoneShapes, ConcavePolygonLeavesItsNotchOut)
{
  // A U shape (x 0.02..0.98, y 0.02..0.98) with the notch x 0.32..0.68, y 0.32..0.98, at 0.1 m/cell.
  // Extent: columns -1..10 (origin -0.1), rows -1..10. Centres 0.05 + 0.1 k sit at grid index k + 1.
  // Filled: every centre with 0.02 < c < 0.98 (k = 0..9), minus those with x in (0.32, 0.68) (k = 3..6)
  // and y > 0.32 (k = 3..9).
  const std::vector<ZonePoint> u = {{0.02, 0.02}, {0.98, 0.02}, {0.98, 0.98}, {0.68, 0.98},
                                    {0.68, 0.32}, {0.32, 0.32}, {0.32, 0.98}, {0.02, 0.98}};
  const OccupancyGridData g = rasterizeZones(layout({polygon("u", u, 90)}));
  auto expected = block(1, 10, 1, 10);
  for (const auto& c : block(4, 7, 4, 10))
    expected.erase(c);
  EXPECT_EQ(cellsWith(g, 90), expected);
}

TEST(ZoneShapes, FilledCircleMatchesIntegerArithmetic)
{
  // Centre (1.0, 1.0), radius 0.45, 0.1 m/cell. In units of 0.05 m every centre is odd: a cell is in
  // when (2a + 1 - 20)^2 + (2b + 1 - 20)^2 <= 9^2 for its lattice indices a, b (x = 0.1 a + 0.05).
  const OccupancyGridData g = rasterizeZones(layout({circle("c", 1.0, 1.0, 0.45, 40)}));
  std::set<std::pair<int, int>> expected;
  const long a0 = std::lround(g.origin_x / 0.1), b0 = std::lround(g.origin_y / 0.1);
  for (uint32_t j = 0; j < g.height; ++j)
    for (uint32_t i = 0; i < g.width; ++i)
    {
      const long dx = 2 * (a0 + static_cast<long>(i)) + 1 - 20, dy = 2 * (b0 + static_cast<long>(j)) + 1 - 20;
      if (dx * dx + dy * dy <= 81) expected.insert({static_cast<int>(i), static_cast<int>(j)});
    }
  // Counted by hand: odd dy = +-1, +-3, +-5 allow |dx| <= 7 (8 centres a row), dy = +-7 allows
  // |dx| <= 5 (6 centres), dy = +-9 none: 6 * 8 + 2 * 6 = 60. No centre ties (odd^2 + odd^2 != 81).
  EXPECT_EQ(expected.size(), 60u);
  EXPECT_EQ(cellsWith(g, 40), expected);
}

TEST(ZoneShapes, CircleOutlineIsTheCellsTheCurveCrosses)
{
  // Centre (1.0, 1.0), radius 0.35 on 0.1 m cells: a cell is on the curve when its nearest point is
  // within 0.35 and its farthest corner beyond it. In units of 0.05 m (corners at even numbers, the
  // centre at 20), exact in integers: near^2 <= 49 <= far^2.
  const OccupancyGridData g = rasterizeZones(layout({circle("c", 1.0, 1.0, 0.35, 33, false)}));
  const long a0 = std::lround(g.origin_x / 0.1), b0 = std::lround(g.origin_y / 0.1);
  std::set<std::pair<int, int>> expected;
  for (uint32_t j = 0; j < g.height; ++j)
    for (uint32_t i = 0; i < g.width; ++i)
    {
      const long xa = 2 * (a0 + static_cast<long>(i)) - 20, xb = xa + 2;
      const long ya = 2 * (b0 + static_cast<long>(j)) - 20, yb = ya + 2;
      const long nx = xa > 0 ? xa : (xb < 0 ? xb : 0), ny = ya > 0 ? ya : (yb < 0 ? yb : 0);
      const long fx = std::max(std::labs(xa), std::labs(xb)), fy = std::max(std::labs(ya), std::labs(yb));
      if (nx * nx + ny * ny <= 49 && fx * fx + fy * fy >= 49)
        expected.insert({static_cast<int>(i), static_cast<int>(j)});
    }
  EXPECT_FALSE(expected.empty());
  EXPECT_EQ(cellsWith(g, 33), expected);
  // The ring encloses the centre cell without claiming it.
  EXPECT_EQ(cellsWith(g, 33).count({static_cast<int>(std::lround((1.0 - g.origin_x) / 0.1 - 0.5)),
                                    static_cast<int>(std::lround((1.0 - g.origin_y) / 0.1 - 0.5))}),
            0u);
}

TEST(ZoneShapes, OverlayRulesCombineOnlyWhereShapesOverlap)
{
  // Squares A (value 30) x 0.02..0.58 and B (value 80) x 0.42..0.98, both y 0.02..0.58, at 0.1.
  // Origin -0.1 in x and y: centres 0.05 + 0.1 k at index k + 1. A holds k = 0..5, B k = 4..9;
  // the overlap is k = 4, 5 (indices 5, 6); rows k = 0..5 (indices 1..6).
  const ZoneShape a = polygon("a", {{0.02, 0.02}, {0.58, 0.02}, {0.58, 0.58}, {0.02, 0.58}}, 30);
  const ZoneShape b = polygon("b", {{0.42, 0.02}, {0.98, 0.02}, {0.98, 0.58}, {0.42, 0.58}}, 80);
  const auto only_a = block(1, 4, 1, 6), overlap = block(5, 6, 1, 6), only_b = block(7, 10, 1, 6);
  auto merge = [](std::set<std::pair<int, int>> x, const std::set<std::pair<int, int>>& y)
  {
    x.insert(y.begin(), y.end());
    return x;
  };
  {
    const OccupancyGridData g = rasterizeZones(layout({a, b}, 0.1, ZoneOverlay::Last));
    EXPECT_EQ(cellsWith(g, 30), only_a);
    EXPECT_EQ(cellsWith(g, 80), merge(overlap, only_b));
  }
  {
    const OccupancyGridData g = rasterizeZones(layout({b, a}, 0.1, ZoneOverlay::Last));
    EXPECT_EQ(cellsWith(g, 30), merge(only_a, overlap));
  }
  {
    const OccupancyGridData g = rasterizeZones(layout({b, a}, 0.1, ZoneOverlay::Max));
    EXPECT_EQ(cellsWith(g, 80), merge(overlap, only_b));
  }
  {
    const OccupancyGridData g = rasterizeZones(layout({a, b}, 0.1, ZoneOverlay::Min));
    EXPECT_EQ(cellsWith(g, 30), merge(only_a, overlap));
  }
  {
    // default_value takes no part: with min and default 50, a value-80 shape still shows 80. B alone
    // starts at column floor(0.42 / 0.1) - 1 = 3 (origin 0.3): its centres 0.45..0.95 are columns 1..6.
    ZoneLayout l = layout({b}, 0.1, ZoneOverlay::Min);
    l.default_value = 50;
    EXPECT_EQ(cellsWith(rasterizeZones(l), 80), block(1, 6, 1, 6));
  }
}

TEST(ZoneShapes, PolygonsSharingAnEdgeThroughCentresNeverBothClaimACentre)
{
  // Binary-exact numbers (resolution 1/8): centres (k + 0.5) / 8 are computed exactly. The shared edge
  // x = 0.5625 runs through the centres of column k = 4. Left x 0.03125..0.5625 holds centres
  // 0.0625..0.4375 (k = 0..3) and, by the half-open rule, not those on its right edge; right
  // x 0.5625..1.21875 holds 0.5625..1.1875 (k = 4..9). Rows y 0.03125..0.59375: k = 0..4.
  const ZoneShape left =
      polygon("l", {{0.03125, 0.03125}, {0.5625, 0.03125}, {0.5625, 0.59375}, {0.03125, 0.59375}}, 10);
  const ZoneShape right =
      polygon("r", {{0.5625, 0.03125}, {1.21875, 0.03125}, {1.21875, 0.59375}, {0.5625, 0.59375}}, 20);
  EXPECT_EQ(cellsWith(rasterizeZones(layout({left}, 0.125)), 10).size(), 4u * 5u);
  EXPECT_EQ(cellsWith(rasterizeZones(layout({right}, 0.125)), 20).size(), 6u * 5u);
  // Together (min overlay: a double claim would show as 10 in column k = 4): 20 + 30 cells, disjoint.
  const OccupancyGridData both = rasterizeZones(layout({left, right}, 0.125, ZoneOverlay::Min));
  EXPECT_EQ(cellsWith(both, 10).size(), 20u);
  EXPECT_EQ(cellsWith(both, 20).size(), 30u);
}

TEST(ZoneShapes, NoShapesIsOneDefaultCell)
{
  ZoneLayout l = layout({});
  l.default_value = -1;
  const OccupancyGridData g = rasterizeZones(l);
  EXPECT_EQ(g.width, 1u);
  EXPECT_EQ(g.height, 1u);
  EXPECT_EQ(g.origin_x, 0.0);
  ASSERT_EQ(g.data.size(), 1u);
  EXPECT_EQ(g.data[0], -1);
}

TEST(ZoneShapes, PointInPolygonHalfOpenRule)
{
  const std::vector<ZonePoint> sq = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_TRUE(pointInZonePolygon(sq, 0.5, 0.5));
  EXPECT_FALSE(pointInZonePolygon(sq, 1.5, 0.5));
  EXPECT_TRUE(pointInZonePolygon(sq, 0.0, 0.5));   // on the left edge: the crossing at 0 is not left of x
  EXPECT_FALSE(pointInZonePolygon(sq, 1.0, 0.5));  // on the right edge: no crossing right of it
  EXPECT_TRUE(pointInZonePolygon(sq, 0.5, 0.0));   // bottom edge: y = 0 counts as "not above"
  EXPECT_FALSE(pointInZonePolygon(sq, 0.5, 1.0));  // top edge
}

TEST(ZoneShapes, BadShapesAreRefusedNamingTheField)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case
  {
    ZoneShape shape;
    std::string field;
  };
  const std::vector<Case> cases = {
      {polygon("two", {{0, 0}, {1, 0}}), "shapes/two/points"},
      {polygon("nan", {{0, 0}, {nan, 0}, {1, 1}}), "shapes/nan/points"},
      {polygon("inf", {{0, 0}, {1, 0}, {1, std::numeric_limits<double>::infinity()}}), "shapes/inf/points"},
      {polygon("far", {{0, 0}, {2e7, 0}, {1, 1}}), "shapes/far/points"},
      {polygon("bowtie", {{0, 0}, {1, 1}, {1, 0}, {0, 1}}), "shapes/bowtie/points"},
      {polygon("dup", {{0, 0}, {1, 0}, {1, 0}, {0, 1}}), "shapes/dup/points"},
      {polygon("flat", {{0, 0}, {1, 0}, {2, 0}}), "shapes/flat/points"},
      {polygon("spike", {{0, 0}, {2, 0}, {2, 3}, {2, 2}, {0, 2}}), "shapes/spike/points"},
      {polygon("touch", {{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}}), "shapes/touch/points"},
      {polygon("v", {{0, 0}, {1, 0}, {1, 1}}, 101), "shapes/v/value"},
      {polygon("v2", {{0, 0}, {1, 0}, {1, 1}}, -2), "shapes/v2/value"},
      {polygon("", {{0, 0}, {1, 0}, {1, 1}}), "shapes/(unnamed)/name"},
      {polygon("a\nb", {{0, 0}, {1, 0}, {1, 1}}), "shapes/(bad name)/name"},
      {polygon("caf\xff", {{0, 0}, {1, 0}, {1, 1}}), "shapes/(bad name)/name"},
      {circle("r0", 0, 0, 0.0), "shapes/r0/radius"},
      {circle("rn", 0, 0, nan), "shapes/rn/radius"},
      {circle("cn", nan, 0, 1.0), "shapes/cn/center"},
  };
  for (const auto& c : cases)
  {
    const InputError e = validateShape(c.shape);
    EXPECT_EQ(e.field, c.field) << c.shape.name << ": " << e.message;
    EXPECT_FALSE(e.message.empty()) << c.shape.name;
  }
  // Valid ones pass: a triangle, a concave polygon, a circle.
  EXPECT_TRUE(validateShape(polygon("ok", {{0, 0}, {1, 0}, {1, 1}})).ok());
  EXPECT_TRUE(validateShape(polygon("u", {{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}})).ok());
  EXPECT_TRUE(validateShape(circle("c", 1, 1, 0.5)).ok());
}

TEST(ZoneShapes, ShapeNamesAreLabelsInUtf8)
{
  // The shared rule for names people give (labelProblem: 1..kMaxNameLength bytes, no control
  // character), plus UTF-8, which a zone file (YAML) must hold to read a name back.
  const std::vector<ZonePoint> tri = {{0, 0}, {1, 0}, {1, 1}};
  for (const std::string good : {std::string("corner keepout"), std::string("zone #2 (dock)"), std::string("a/b"),
                                 std::string("a/0"), std::string(" x "),
                                 std::string("K\xc3\xbc"
                                             "che"),
                                 std::string("\xef\xbf\xbf"), std::string("\xf4\x8f\xbf\xbf"), std::string("\xc2\x85"),
                                 std::string(kMaxNameLength, 'n')})
    EXPECT_TRUE(validateShape(polygon(good, tri)).ok()) << good << ": " << validateShape(polygon(good, tri)).message;
  for (const std::string bad :
       {std::string(kMaxNameLength + 1, 'n'), std::string("a\nb"), std::string("a\x7f"), std::string("\tx"),
        std::string("a\0b", 3), std::string("\xff"), std::string("\xc0\xaf"), std::string("\xed\xa0\x80"),
        std::string("\xf4\x90\x80\x80"), std::string("ab\xe2\x82"), std::string("\x80")})
  {
    const InputError e = validateShape(polygon(bad, tri));
    EXPECT_EQ(e.field, "shapes/(bad name)/name") << bad;
    EXPECT_EQ(e.message.find('\n'), std::string::npos) << e.message;
  }
  EXPECT_EQ(validateShape(polygon("", tri)).field, "shapes/(unnamed)/name");
}

TEST(ZoneShapes, Utf8ErrorsAreFoundWhereTheyStart)
{
  EXPECT_EQ(utf8ErrorAt(""), std::string::npos);
  EXPECT_EQ(utf8ErrorAt("plain"), std::string::npos);
  EXPECT_EQ(utf8ErrorAt("\xe2\x80\xa8\xf0\x9f\x98\x80"), std::string::npos);  // U+2028, U+1F600
  EXPECT_EQ(utf8ErrorAt("ab\xff"), 2u);
  EXPECT_EQ(utf8ErrorAt("a\xc1\xbf"), 1u);                         // overlong '\x7f'
  EXPECT_EQ(utf8ErrorAt("a\xe0\x9f\xbf"), 1u);                     // overlong U+07FF
  EXPECT_EQ(utf8ErrorAt("\xed\x9f\xbf\xed\xa0\x80"), 3u);          // U+D7FF fine, U+D800 a surrogate
  EXPECT_EQ(utf8ErrorAt("\xf0\x8f\xbf\xbf"), 0u);                  // overlong U+FFFF
  EXPECT_EQ(utf8ErrorAt("\xf4\x8f\xbf\xbf\xf4\x90\x80\x80"), 4u);  // U+10FFFF fine, past it not
  EXPECT_EQ(utf8ErrorAt("\xc3"), 0u);                              // cut short
  EXPECT_EQ(utf8ErrorAt("\xc3\xa9\xc3("), 2u);
}

TEST(ZoneShapes, TheLayoutFrameIsATfFrameId)
{
  ZoneLayout l = layout({polygon("a", kRect)});
  // The "map\nodom" (read back from a file as "map odom"), and others of the class.
  for (const std::string bad : {std::string("map\nodom"), std::string("map odom"), std::string(""),
                                std::string(kMaxNameLength + 1, 'f'), std::string("kar\xc3\xa9"), std::string("map\r")})
  {
    l.frame_id = bad;
    const InputError e = validateLayout(l);
    EXPECT_EQ(e.field, "frame_id") << bad;
    EXPECT_EQ(e.message.find_first_of("\n\r"), std::string::npos) << e.message;
    ZoneSet set(layout({polygon("a", kRect)}));
    EXPECT_EQ(set.replace(l).field, "frame_id");
    EXPECT_EQ(set.layout().frame_id, "map");
  }
  for (const std::string good : {std::string("odom"), std::string("/robot1/map"), std::string(kMaxNameLength, 'f')})
  {
    l.frame_id = good;
    EXPECT_TRUE(validateLayout(l).ok()) << good;
  }
}

TEST(ZoneShapes, HugeExtentIsRefusedBeforeAnyAllocation)
{
  // 1000 km x 1000 km at 1 mm: 1e18 cells, far past limits::kMaxGridCells.
  ZoneLayout l = layout({polygon("a", {{-5e5, -5e5}, {5e5, -5e5}, {0, 5e5}})}, 1e-3);
  const InputError e = validateLayout(l);
  EXPECT_EQ(e.field, "extent");
  EXPECT_THROW(rasterizeZones(l), std::invalid_argument);
  // Two shapes far apart make a huge extent too.
  l = layout({circle("a", -9e6, 0, 1), circle("b", 9e6, 0, 1)}, 0.05);
  EXPECT_EQ(validateLayout(l).field, "extent");
}

TEST(ZoneShapes, AHugeBadNameStaysOutOfTheKeyAndTheMessage)
{
  // A peer's name of a million characters: the key is fixed and the message short, so neither the log
  // line nor the log's throttle table grows with it.
  const ZoneShape s = polygon(std::string(1000000, 'x'), {{0, 0}, {1, 0}, {1, 1}});
  const InputError e = validateShape(s);
  EXPECT_EQ(e.field, "shapes/(bad name)/name");
  EXPECT_LT(e.message.size(), 300u) << e.message.substr(0, 300);
  EXPECT_NE(e.message.find("1000000"), std::string::npos) << e.message;
}

TEST(ZoneShapes, LayoutsTooSlowToDrawAreRefused)
{
  // Circles of radius 4000 m at 0.5 m/cell: each bounding box spans floor(8000) - floor(-8000) + 3 =
  // 16003 cells a side, 256 096 009 cells. Three take 768 288 027 visits (allowed), four
  // 1 024 384 036, more than limits::kMaxZoneRasterWork = 1e9; each grid is within kMaxGridCells.
  std::vector<ZoneShape> circles;
  for (int k = 0; k < 3; ++k)
    circles.push_back(circle("c" + std::to_string(k), 0, 0, 4000.0));
  EXPECT_TRUE(validateLayout(layout(circles, 0.5)).ok());
  circles.push_back(circle("c3", 0, 0, 4000.0));
  const InputError e = validateLayout(layout(circles, 0.5));
  EXPECT_EQ(e.field, "extent");
  EXPECT_NE(e.message.find("cell visits"), std::string::npos) << e.message;

  // One polygon of 1000 vertices, 1 m wide and 400 km tall, at 0.05 m/cell: 8e6 rows of 23 cells
  // (1.8e8 cells, a grid within kMaxGridCells), but each row seeks its crossings among 1000 edges:
  // 8e9 visits. Its right side holds 998 vertices on the line x = 1.
  std::vector<ZonePoint> comb;
  for (int k = 0; k < 998; ++k)
    comb.push_back({1.0, 4e5 * k / 997.0});
  comb.push_back({0.0, 4e5});
  comb.push_back({0.0, 0.0});
  const ZoneShape tall = polygon("tall", comb);
  ASSERT_EQ(tall.points.size(), 1000u);
  EXPECT_TRUE(validateShape(tall).ok()) << validateShape(tall).message;
  const ZoneLayout l = layout({tall}, 0.05);
  EXPECT_NO_THROW(zoneGridExtent(l));
  EXPECT_EQ(validateLayout(l).field, "extent");
  EXPECT_THROW(rasterizeZones(l), std::invalid_argument);
  // The same polygon 4 km tall: 8e4 rows, 8e7 visits, drawn.
  std::vector<ZonePoint> small;
  for (int k = 0; k < 998; ++k)
    small.push_back({1.0, 4e3 * k / 997.0});
  small.push_back({0.0, 4e3});
  small.push_back({0.0, 0.0});
  EXPECT_TRUE(validateLayout(layout({polygon("small", small)}, 0.05)).ok());
}

TEST(ZoneShapes, LayoutChecks)
{
  ZoneLayout l = layout({polygon("a", kRect), polygon("a", kRect)});
  EXPECT_EQ(validateLayout(l).field, "shapes/a/name");
  l = layout({polygon("a", kRect)}, 0.0);
  EXPECT_EQ(validateLayout(l).field, "resolution");
  l = layout({polygon("a", kRect)});
  l.default_value = 101;
  EXPECT_EQ(validateLayout(l).field, "default_value");
  l = layout({polygon("a", kRect)});
  l.frame_id.clear();
  EXPECT_EQ(validateLayout(l).field, "frame_id");
}

TEST(ZoneSet, EditsAreCheckedAndABadOneKeepsTheLastGoodLayout)
{
  ZoneSet set(layout({polygon("r", kRect, 70)}));
  const OccupancyGridData before = rasterizeZones(set.layout());
  // Dragging vertex 2 across the opposite edge makes a bow tie: refused, nothing changes.
  EXPECT_EQ(set.moveHandle("r", 2, 0.5, 0.2).field, "shapes/r/points");
  EXPECT_EQ(rasterizeZones(set.layout()).data, before.data);
  EXPECT_FALSE(set.moveHandle("r", 9, 0.0, 0.0).ok());     // no handle 9
  EXPECT_FALSE(set.moveHandle("nope", 0, 0.0, 0.0).ok());  // no such shape
  EXPECT_FALSE(set.upsert(polygon("bad", {{0, 0}, {1, 1}})).ok());
  EXPECT_FALSE(set.remove("nope").ok());
  EXPECT_EQ(set.layout().shapes.size(), 1u);
  // A good drag: vertex 1 (1.13, 0.47) to (1.43, 0.47); columns now reach centre 1.35 (i = 11).
  // The extent grows to floor(1.43 / 0.1) + 1 = 15: columns 2..15, origin 0.2.
  ASSERT_TRUE(set.moveHandle("r", 1, 1.43, 0.47).ok());
  const OccupancyGridData g = rasterizeZones(set.layout());
  EXPECT_EQ(g.width, 14u);
  // The moved polygon (0.32,0.47) (1.43,0.47) (1.13,0.88) (0.32,0.88): a trapezoid whose right side
  // x(y) = 1.43 - 0.3 (y - 0.47) / 0.41; rows j = 2..5 (y = 0.55, 0.65, 0.75, 0.85) reach
  // x < 1.3715, 1.2983, 1.2254, 1.1524: last centres 1.35 (i 11), 1.25 (10), 1.15 (9), 1.15 (9).
  std::set<std::pair<int, int>> expected;
  const int last_i[] = {11, 10, 9, 9};
  for (int j = 2; j <= 5; ++j)
    for (int i = 1; i <= last_i[j - 2]; ++i)
      expected.insert({i, j});
  EXPECT_EQ(cellsWith(g, 70), expected);
  // Circles: handle 0 moves the centre, handle 1 sets the radius.
  ASSERT_TRUE(set.upsert(circle("c", 3.0, 3.0, 0.5, 20)).ok());
  ASSERT_TRUE(set.moveHandle("c", 1, 3.0, 3.8).ok());
  EXPECT_DOUBLE_EQ(set.find("c")->radius, 0.8);
  ASSERT_TRUE(set.moveHandle("c", 0, 4.0, 3.0).ok());
  EXPECT_DOUBLE_EQ(set.find("c")->center.x, 4.0);
  EXPECT_DOUBLE_EQ(set.find("c")->radius, 0.8);
  // Replacing keeps the place in the list; removing drops it.
  ASSERT_TRUE(set.upsert(polygon("r", kRect, 10)).ok());
  EXPECT_EQ(set.layout().shapes[0].value, 10);
  ASSERT_TRUE(set.remove("r").ok());
  EXPECT_EQ(set.layout().shapes.size(), 1u);
  EXPECT_EQ(set.layout().shapes[0].name, "c");
}

namespace
{
/// A regular n-gon of radius r about (cx, cy): valid, not self-intersecting.
ZoneShape ngon(const std::string& name, std::size_t n, double cx, double cy, double r)
{
  std::vector<ZonePoint> p;
  for (std::size_t k = 0; k < n; ++k)
    p.push_back({cx + r * std::cos(2.0 * M_PI * k / n), cy + r * std::sin(2.0 * M_PI * k / n)});
  return polygon(name, std::move(p));
}
}  // namespace

// The self-intersection check is quadratic per polygon, and every edit re-checked every shape: at the
// documented limits (1000 polygons of 1000 vertices) one handle drag took 13 s, twice over (the edit,
// then the drawing), on zone_server's only thread. Now the sum of n^2 is bounded (2e7: about 0.1 s for
// a whole check), an edit checks only the shape it changes, and a ZoneSet draws without checking again.
TEST(ZoneSet, TheVertexPairsOfALayoutAreBounded)
{
  std::vector<ZoneShape> shapes;
  for (std::size_t k = 0; k < 20; ++k)
    shapes.push_back(ngon("p" + std::to_string(k), 1000, 3.0 * static_cast<double>(k), 0.0, 1.0));
  ZoneSet set(layout(shapes));  // 20 x 1000^2 = 2e7: the limit itself is allowed
  shapes.push_back(ngon("one_more", 1000, 70.0, 0.0, 1.0));
  const InputError e = validateLayout(layout(shapes));
  EXPECT_EQ(e.field, "shapes");
  EXPECT_NE(e.message.find("vertices squared"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("2.1e+07"), std::string::npos) << e.message;  // the layout's figure, named
  EXPECT_THROW(ZoneSet{layout(shapes)}, std::invalid_argument);
  // The same through an edit: refused, the last good layout stays.
  EXPECT_EQ(set.upsert(shapes.back()).field, "shapes");
  EXPECT_EQ(set.layout().shapes.size(), 20u);
  // At the limit no other polygon fits, not even a triangle; replacing a big one by a square does.
  EXPECT_EQ(set.upsert(ngon("small", 3, 70.0, 0.0, 1.0)).field, "shapes");
  ASSERT_TRUE(set.upsert(polygon("p19", {{56, -1}, {58, -1}, {58, 1}, {56, 1}})).ok());
  ASSERT_TRUE(set.upsert(ngon("small", 3, 70.0, 0.0, 1.0)).ok());
  // An edit of a big one works, and a ZoneSet draws what the checked path draws.
  ASSERT_TRUE(set.moveHandle("p3", 0, 10.2, 0.0).ok());
  EXPECT_EQ(set.rasterize().data, rasterizeZones(set.layout()).data);
  // A bow tie made by a drag is still found (the changed shape is checked).
  EXPECT_EQ(set.moveHandle("p19", 0, 57.5, 2.0).field, "shapes/p19/points");
}

namespace
{
ParamValue pt(double x, double y)
{
  return ParamValue::makeList({ParamValue::makeDouble(x), ParamValue::makeDouble(y)});
}
ParamValue shapeTree()
{
  ParamValue s = ParamValue::makeMap();
  s.set("name", ParamValue::makeString("dock"));
  s.set("type", ParamValue::makeString("polygon"));
  s.set("value", ParamValue::makeInt(100));
  s.set("points", ParamValue::makeList({pt(0, 0), pt(1, 0), pt(1, 1)}));
  return s;
}
ParamValue fileTree(ParamValue shape)
{
  ParamValue t = ParamValue::makeMap();
  t.set("frame_id", ParamValue::makeString("map"));
  t.set("resolution", ParamValue::makeDouble(0.05));
  t.set("overlay", ParamValue::makeString("max"));
  t.set("shapes", ParamValue::makeList({std::move(shape)}));
  return t;
}
}  // namespace

TEST(ZoneLayoutParse, ReadsAFileTreeAndRefusesBadFieldsByName)
{
  const ZoneLayout l = parseZoneLayout(fileTree(shapeTree()), "zones.yaml");
  ASSERT_EQ(l.shapes.size(), 1u);
  EXPECT_EQ(l.overlay, ZoneOverlay::Max);
  EXPECT_EQ(l.shapes[0].points.size(), 3u);
  EXPECT_TRUE(l.shapes[0].fill);

  auto refused = [](ParamValue tree, const std::string& needle)
  {
    try
    {
      parseZoneLayout(tree, "zones.yaml");
      ADD_FAILURE() << "accepted, expected an error with " << needle;
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  ParamValue s = shapeTree();
  s.set("colour", ParamValue::makeString("red"));
  refused(fileTree(s), "unknown field 'colour'");
  s = shapeTree();
  s.set("points", ParamValue::makeList({pt(0, 0), pt(1, 0)}));
  refused(fileTree(s), "at least 3 points");
  s = shapeTree();
  s.set("points", ParamValue::makeList({pt(0, 0), ParamValue::makeList({ParamValue::makeString("x")}), pt(1, 1)}));
  refused(fileTree(s), "points[1]");
  s = shapeTree();
  s.set("value", ParamValue::makeDouble(50.5));
  refused(fileTree(s), "value must be an integer in -1..100");
  s = shapeTree();
  s.set("type", ParamValue::makeString("ellipse"));
  refused(fileTree(s), "'type' must be");
  ParamValue t = fileTree(shapeTree());
  t.set("overlay", ParamValue::makeString("sum"));
  refused(t, "overlay must be");
  t = fileTree(shapeTree());
  t.set("origin", pt(0, 0));
  refused(t, "unknown field 'origin'");
}
