// Unit tests of the ROS-free cost grid: coordinates, windows, origin moves, polygons and ray walks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <set>
#include <utility>
#include <vector>

#include "costmap_layers/core/grid/costmap_2d.hpp"

using costmap_layers::Costmap2D;
using costmap_layers::MapLocation;

namespace
{
using Cell = std::pair<int, int>;

/// A grid whose cell (x, y) holds 1 + x + 10 * y (never the default 0).
Costmap2D numberedGrid(unsigned int sx, unsigned int sy, double res = 1.0, double ox = 0.0, double oy = 0.0)
{
  Costmap2D g(sx, sy, res, ox, oy, 0);
  for (unsigned int y = 0; y < sy; ++y)
    for (unsigned int x = 0; x < sx; ++x)
      g.setCost(x, y, static_cast<uint8_t>(1 + x + 10 * y));
  return g;
}

std::vector<Cell> raytrace(const Costmap2D& g, unsigned int x0, unsigned int y0, unsigned int x1, unsigned int y1,
                           unsigned int max_length = 0xFFFFFFFFu, unsigned int min_length = 0)
{
  std::vector<Cell> cells;
  g.raytraceLine(
      [&](unsigned int index)
      {
        unsigned int mx, my;
        g.indexToCells(index, mx, my);
        cells.emplace_back(static_cast<int>(mx), static_cast<int>(my));
      },
      x0, y0, x1, y1, max_length, min_length);
  return cells;
}

std::vector<Cell> walk(int x0, int y0, int x1, int y1)
{
  std::vector<Cell> cells;
  Costmap2D::walkLine([&](int x, int y) { cells.emplace_back(x, y); }, x0, y0, x1, y1);
  return cells;
}

std::set<Cell> toSet(const std::vector<MapLocation>& cells)
{
  std::set<Cell> s;
  for (const auto& c : cells)
    s.emplace(static_cast<int>(c.x), static_cast<int>(c.y));
  return s;
}

bool adjacent8(const Cell& a, const Cell& b)
{
  return std::abs(a.first - b.first) <= 1 && std::abs(a.second - b.second) <= 1 && a != b;
}
}  // namespace

// ---------------------------------------------------------------- construction and coordinates

TEST(Costmap2DCoords, ConstructorSetsGeometryAndDefault)
{
  Costmap2D g(4, 3, 0.25, -1.0, 2.0, 42);
  EXPECT_EQ(g.getSizeInCellsX(), 4u);
  EXPECT_EQ(g.getSizeInCellsY(), 3u);
  EXPECT_DOUBLE_EQ(g.getResolution(), 0.25);
  EXPECT_DOUBLE_EQ(g.getOriginX(), -1.0);
  EXPECT_DOUBLE_EQ(g.getOriginY(), 2.0);
  EXPECT_DOUBLE_EQ(g.getSizeInMetersX(), 1.0);
  EXPECT_DOUBLE_EQ(g.getSizeInMetersY(), 0.75);
  EXPECT_EQ(g.getDefaultValue(), 42);
  ASSERT_EQ(g.cellCount(), 12u);
  for (std::size_t i = 0; i < g.cellCount(); ++i)
    EXPECT_EQ(g.data()[i], 42);
}

TEST(Costmap2DCoords, IndexIsRowMajor)
{
  Costmap2D g(5, 4, 1.0, 0, 0);
  EXPECT_EQ(g.getIndex(0, 0), 0u);
  EXPECT_EQ(g.getIndex(4, 0), 4u);
  EXPECT_EQ(g.getIndex(0, 1), 5u);
  EXPECT_EQ(g.getIndex(3, 2), 13u);
  unsigned int mx, my;
  g.indexToCells(13, mx, my);
  EXPECT_EQ(mx, 3u);
  EXPECT_EQ(my, 2u);
  g.setCost(3, 2, 99);
  EXPECT_EQ(g.getCost(13), 99);
  EXPECT_EQ(g.getCost(3, 2), 99);
  EXPECT_EQ(g.data()[13], 99);
}

TEST(Costmap2DCoords, TwoByThreeAtOneMetre)
{
  Costmap2D g(2, 3, 1.0, 0.0, 0.0);
  double wx, wy;
  g.mapToWorld(0, 0, wx, wy);
  EXPECT_DOUBLE_EQ(wx, 0.5);
  EXPECT_DOUBLE_EQ(wy, 0.5);
  g.mapToWorld(1, 2, wx, wy);
  EXPECT_DOUBLE_EQ(wx, 1.5);
  EXPECT_DOUBLE_EQ(wy, 2.5);

  unsigned int mx = 77, my = 77;
  EXPECT_FALSE(g.worldToMap(2.0, 1.0, mx, my));  // x = 2.0 is the outer edge: outside
  EXPECT_TRUE(g.worldToMap(1.999, 2.999, mx, my));
  EXPECT_EQ(mx, 1u);
  EXPECT_EQ(my, 2u);
  EXPECT_TRUE(g.worldToMap(0.0, 0.0, mx, my));
  EXPECT_EQ(mx, 0u);
  EXPECT_EQ(my, 0u);
  EXPECT_FALSE(g.worldToMap(-0.001, 1.0, mx, my));
  EXPECT_FALSE(g.worldToMap(1.0, 3.0, mx, my));
  EXPECT_FALSE(g.worldToMap(1.0, -1.0, mx, my));
  EXPECT_FALSE(g.worldToMap(std::nan(""), 1.0, mx, my));

  int ix = -5, iy = -5;
  g.worldToMapEnforceBounds(2.0, 1.5, ix, iy);
  EXPECT_EQ(ix, 1);
  EXPECT_EQ(iy, 1);
  g.worldToMapEnforceBounds(100.0, 100.0, ix, iy);
  EXPECT_EQ(ix, 1);
  EXPECT_EQ(iy, 2);
  g.worldToMapEnforceBounds(-3.0, -0.5, ix, iy);
  EXPECT_EQ(ix, 0);
  EXPECT_EQ(iy, 0);
  g.worldToMapEnforceBounds(0.7, 2.2, ix, iy);
  EXPECT_EQ(ix, 0);
  EXPECT_EQ(iy, 2);
}

TEST(Costmap2DCoords, TwoByThreeAtTenCentimetres)
{
  Costmap2D g(2, 3, 0.1, -0.2, 0.2);
  double wx, wy;
  g.mapToWorld(0, 0, wx, wy);
  EXPECT_NEAR(wx, -0.15, 1e-12);
  EXPECT_NEAR(wy, 0.25, 1e-12);

  int ix = 0, iy = 0;
  g.worldToMapNoBounds(2.5, 0.2, ix, iy);
  EXPECT_EQ(ix, 27);
  EXPECT_EQ(iy, 0);
  g.worldToMapNoBounds(-0.25, 0.45, ix, iy);  // -0.5 cells truncates towards zero
  EXPECT_EQ(ix, 0);
  EXPECT_EQ(iy, 2);
  g.worldToMapNoBounds(-1.0, -0.9, ix, iy);
  EXPECT_EQ(ix, -8);
  EXPECT_EQ(iy, -11);

  unsigned int mx, my;
  EXPECT_TRUE(g.worldToMap(-0.15, 0.45, mx, my));
  EXPECT_EQ(mx, 0u);
  EXPECT_EQ(my, 2u);
  EXPECT_FALSE(g.worldToMap(0.05, 0.25, mx, my));
}

TEST(Costmap2DCoords, MapToWorldRoundTrips)
{
  Costmap2D g(7, 9, 0.05, -3.3, 12.1);
  for (unsigned int y = 0; y < 9; ++y)
    for (unsigned int x = 0; x < 7; ++x)
    {
      double wx, wy;
      g.mapToWorld(x, y, wx, wy);
      unsigned int mx, my;
      ASSERT_TRUE(g.worldToMap(wx, wy, mx, my));
      EXPECT_EQ(mx, x);
      EXPECT_EQ(my, y);
    }
}

TEST(Costmap2DCoords, CellDistanceRoundsUp)
{
  Costmap2D g(10, 10, 0.1, 0, 0);
  EXPECT_EQ(g.cellDistance(0.0), 0u);
  EXPECT_EQ(g.cellDistance(0.25), 3u);
  EXPECT_EQ(g.cellDistance(0.01), 1u);
  EXPECT_EQ(g.cellDistance(1.05), 11u);
  EXPECT_EQ(g.cellDistance(-0.5), 0u);  // negative distances clamp to zero
  Costmap2D h(10, 10, 1.0, 0, 0);
  EXPECT_EQ(h.cellDistance(2.0), 2u);
  EXPECT_EQ(h.cellDistance(2.0001), 3u);
}

TEST(Costmap2DCoords, CellDistanceOfHugeOrNonFiniteDistances)
{
  // raytrace_max_range may be any finite number up to DBL_MAX: the count saturates instead of an
  // undefined double -> unsigned conversion.
  Costmap2D g(10, 10, 0.1, 0, 0);
  EXPECT_EQ(g.cellDistance(1e300), 0xFFFFFFFFu);
  EXPECT_EQ(g.cellDistance(std::numeric_limits<double>::max()), 0xFFFFFFFFu);
  EXPECT_EQ(g.cellDistance(std::numeric_limits<double>::infinity()), 0xFFFFFFFFu);
  Costmap2D m(10, 10, 1.0, 0, 0);
  EXPECT_EQ(m.cellDistance(4294967294.0), 4294967294u);
  EXPECT_EQ(m.cellDistance(4294967294.5), 0xFFFFFFFFu);  // 2^32 - 1 cells
  EXPECT_EQ(m.cellDistance(4294967296.0), 0xFFFFFFFFu);
  EXPECT_EQ(g.cellDistance(std::numeric_limits<double>::quiet_NaN()), 0u);
  EXPECT_EQ(g.cellDistance(-std::numeric_limits<double>::infinity()), 0u);
}

// ---------------------------------------------------------------- resize, reset, fill, copy

TEST(Costmap2DWindows, ResizeMapReallocatesWithDefault)
{
  Costmap2D g = numberedGrid(3, 3);
  g.setDefaultValue(9);
  g.resizeMap(6, 2, 0.5, 1.0, -2.0);
  EXPECT_EQ(g.getSizeInCellsX(), 6u);
  EXPECT_EQ(g.getSizeInCellsY(), 2u);
  EXPECT_DOUBLE_EQ(g.getResolution(), 0.5);
  EXPECT_DOUBLE_EQ(g.getOriginX(), 1.0);
  EXPECT_DOUBLE_EQ(g.getOriginY(), -2.0);
  ASSERT_EQ(g.cellCount(), 12u);
  for (std::size_t i = 0; i < g.cellCount(); ++i)
    EXPECT_EQ(g.getCost(static_cast<unsigned>(i)), 9);
}

TEST(Costmap2DWindows, ResetMapsSetsEverythingToDefault)
{
  Costmap2D g = numberedGrid(4, 4);
  g.setDefaultValue(255);
  g.resetMaps();
  for (std::size_t i = 0; i < g.cellCount(); ++i)
    EXPECT_EQ(g.getCost(static_cast<unsigned>(i)), 255);
}

TEST(Costmap2DWindows, ResetMapWindowOnlyTouchesWindow)
{
  Costmap2D g = numberedGrid(6, 5);
  g.resetMap(1, 2, 4, 4);  // [1,4) x [2,4)
  for (unsigned int y = 0; y < 5; ++y)
    for (unsigned int x = 0; x < 6; ++x)
    {
      const bool inside = x >= 1 && x < 4 && y >= 2 && y < 4;
      EXPECT_EQ(g.getCost(x, y), inside ? 0 : 1 + x + 10 * y) << x << "," << y;
    }
}

TEST(Costmap2DWindows, ResetMapClampsToGridAndIgnoresEmptyWindows)
{
  Costmap2D g = numberedGrid(4, 3);
  g.resetMap(2, 1, 100, 100);
  for (unsigned int y = 0; y < 3; ++y)
    for (unsigned int x = 0; x < 4; ++x)
      EXPECT_EQ(g.getCost(x, y), (x >= 2 && y >= 1) ? 0 : 1 + x + 10 * y) << x << "," << y;

  Costmap2D h = numberedGrid(4, 3);
  h.resetMap(3, 1, 3, 3);  // empty in x
  h.resetMap(0, 2, 4, 1);  // inverted in y
  h.resetMap(5, 0, 9, 3);  // entirely right of the grid
  for (unsigned int y = 0; y < 3; ++y)
    for (unsigned int x = 0; x < 4; ++x)
      EXPECT_EQ(h.getCost(x, y), 1 + x + 10 * y);
}

TEST(Costmap2DWindows, FillWindowWritesValue)
{
  Costmap2D g(5, 5, 1.0, 0, 0, 3);
  g.fillWindow(0, 3, 2, 5, 200);
  for (unsigned int y = 0; y < 5; ++y)
    for (unsigned int x = 0; x < 5; ++x)
      EXPECT_EQ(g.getCost(x, y), (x < 2 && y >= 3) ? 200 : 3);
}

TEST(Costmap2DWindows, CopyWindowCopiesToDestinationOffset)
{
  const Costmap2D src = numberedGrid(5, 4);
  Costmap2D dst(6, 6, 1.0, 0, 0, 250);
  ASSERT_TRUE(dst.copyWindow(src, 1, 1, 4, 3, 2, 3));  // 3 x 2 cells to (2,3)
  for (unsigned int y = 0; y < 6; ++y)
    for (unsigned int x = 0; x < 6; ++x)
    {
      const bool inside = x >= 2 && x < 5 && y >= 3 && y < 5;
      const unsigned int expected = inside ? src.getCost(x - 2 + 1, y - 3 + 1) : 250u;
      EXPECT_EQ(dst.getCost(x, y), expected) << x << "," << y;
    }
}

TEST(Costmap2DWindows, CopyWindowWholeGridAndExactFit)
{
  const Costmap2D src = numberedGrid(3, 2);
  Costmap2D dst(3, 2, 1.0, 0, 0, 0);
  ASSERT_TRUE(dst.copyWindow(src, 0, 0, 3, 2, 0, 0));
  for (unsigned int i = 0; i < 6; ++i)
    EXPECT_EQ(dst.getCost(i), src.getCost(i));

  Costmap2D dst2(5, 5, 1.0, 0, 0, 0);
  ASSERT_TRUE(dst2.copyWindow(src, 0, 0, 3, 2, 2, 3));  // touches the upper right corner exactly
  EXPECT_EQ(dst2.getCost(4, 4), src.getCost(2, 1));
  EXPECT_EQ(dst2.getCost(2, 3), src.getCost(0, 0));
}

TEST(Costmap2DWindows, CopyWindowRefusesWindowsThatDoNotFit)
{
  const Costmap2D src = numberedGrid(5, 4);
  Costmap2D dst(4, 4, 1.0, 0, 0, 250);
  const Costmap2D before = dst;
  auto unchanged = [&]()
  {
    for (unsigned int i = 0; i < dst.cellCount(); ++i)
      if (dst.getCost(i) != before.getCost(i)) return false;
    return true;
  };
  EXPECT_FALSE(dst.copyWindow(src, 0, 0, 6, 2, 0, 0));  // source window wider than the source
  EXPECT_TRUE(unchanged());
  EXPECT_FALSE(dst.copyWindow(src, 0, 0, 2, 5, 0, 0));  // source window taller than the source
  EXPECT_TRUE(unchanged());
  EXPECT_FALSE(dst.copyWindow(src, 0, 0, 5, 2, 0, 0));  // 5 wide does not fit a 4 wide destination
  EXPECT_TRUE(unchanged());
  EXPECT_FALSE(dst.copyWindow(src, 0, 0, 2, 2, 3, 0));  // 3 + 2 > 4
  EXPECT_TRUE(unchanged());
  EXPECT_FALSE(dst.copyWindow(src, 0, 0, 2, 2, 0, 3));  // 3 + 2 > 4
  EXPECT_TRUE(unchanged());
  EXPECT_FALSE(dst.copyWindow(src, 3, 0, 2, 2, 0, 0));  // inverted window
  EXPECT_TRUE(unchanged());
  EXPECT_FALSE(dst.copyWindow(src, 0, 3, 2, 2, 0, 0));  // inverted window
  EXPECT_TRUE(unchanged());
}

// ---------------------------------------------------------------- updateOrigin

namespace
{
/// What updateOrigin must produce, computed per new cell: the new origin is the old origin moved by
/// floor(shift / resolution) whole cells; a new cell keeps the old cell at the same place, if any.
void expectShifted(const Costmap2D& before, const Costmap2D& after, double req_x, double req_y)
{
  const double res = before.getResolution();
  const int cx = static_cast<int>(std::floor((req_x - before.getOriginX()) / res));
  const int cy = static_cast<int>(std::floor((req_y - before.getOriginY()) / res));
  EXPECT_NEAR(after.getOriginX(), before.getOriginX() + cx * res, 1e-9);
  EXPECT_NEAR(after.getOriginY(), before.getOriginY() + cy * res, 1e-9);
  ASSERT_EQ(after.getSizeInCellsX(), before.getSizeInCellsX());
  ASSERT_EQ(after.getSizeInCellsY(), before.getSizeInCellsY());
  for (unsigned int y = 0; y < after.getSizeInCellsY(); ++y)
    for (unsigned int x = 0; x < after.getSizeInCellsX(); ++x)
    {
      // Centre of the new cell in the world, then the old cell containing it.
      double wx, wy;
      after.mapToWorld(x, y, wx, wy);
      unsigned int ox, oy;
      const uint8_t expected = before.worldToMap(wx, wy, ox, oy) ? before.getCost(ox, oy) : before.getDefaultValue();
      EXPECT_EQ(after.getCost(x, y), expected) << "cell " << x << "," << y;
    }
}
}  // namespace

TEST(Costmap2DOrigin, ShiftByWholeCellsPositive)
{
  const Costmap2D before = numberedGrid(5, 4);
  Costmap2D g = before;
  g.updateOrigin(2.0, 1.0);
  expectShifted(before, g, 2.0, 1.0);
  // Spot checks written out: new (0,0) is old (2,1); the last two columns and the top row are new.
  EXPECT_EQ(g.getCost(0, 0), 1 + 2 + 10);
  EXPECT_EQ(g.getCost(2, 2), 1 + 4 + 30);
  EXPECT_EQ(g.getCost(3, 0), 0);
  EXPECT_EQ(g.getCost(0, 3), 0);
}

TEST(Costmap2DOrigin, ShiftByWholeCellsNegative)
{
  const Costmap2D before = numberedGrid(5, 4, 0.5, 1.0, -1.0);
  Costmap2D g = before;
  g.updateOrigin(0.5, -2.0);  // one cell left, two cells down
  expectShifted(before, g, 0.5, -2.0);
  EXPECT_EQ(g.getCost(1, 2), 1 + 0 + 0);  // old (0,0)
  EXPECT_EQ(g.getCost(0, 2), 0);
  EXPECT_EQ(g.getCost(4, 1), 0);
  EXPECT_EQ(g.getCost(4, 3), 1 + 3 + 10);
}

TEST(Costmap2DOrigin, MixedDirectionsAndFractionalShiftSnaps)
{
  const Costmap2D before = numberedGrid(6, 5);
  Costmap2D g = before;
  g.updateOrigin(-1.7, 2.3);  // snaps to (-2, 2)
  EXPECT_DOUBLE_EQ(g.getOriginX(), -2.0);
  EXPECT_DOUBLE_EQ(g.getOriginY(), 2.0);
  expectShifted(before, g, -1.7, 2.3);

  Costmap2D h = before;
  h.updateOrigin(0.4, 0.9);  // less than a cell: nothing moves
  EXPECT_DOUBLE_EQ(h.getOriginX(), 0.0);
  EXPECT_DOUBLE_EQ(h.getOriginY(), 0.0);
  for (unsigned int i = 0; i < h.cellCount(); ++i)
    EXPECT_EQ(h.getCost(i), before.getCost(i));
}

TEST(Costmap2DOrigin, ShiftLargerThanTheMapClearsEverything)
{
  for (const auto& shift :
       std::vector<std::pair<double, double>>{{10.0, 0.0}, {-7.0, 0.0}, {0.0, 50.0}, {-100.0, -100.0}, {3.0, -4.0}})
  {
    Costmap2D g = numberedGrid(5, 4);
    g.setDefaultValue(255);
    g.updateOrigin(shift.first, shift.second);
    EXPECT_DOUBLE_EQ(g.getOriginX(), shift.first);
    EXPECT_DOUBLE_EQ(g.getOriginY(), shift.second);
    for (unsigned int i = 0; i < g.cellCount(); ++i)
      EXPECT_EQ(g.getCost(i), 255) << shift.first << "," << shift.second;
  }
}

TEST(Costmap2DOrigin, ManyShiftsMatchNaiveComputation)
{
  const std::vector<std::pair<int, int>> shifts = {{1, 0},  {0, 1},  {-1, 0}, {0, -1},
                                                   {3, -2}, {-4, 3}, {4, 4},  {-5, -1}};
  for (const auto& s : shifts)
  {
    const Costmap2D before = numberedGrid(7, 6, 0.25, -0.5, 0.75);
    Costmap2D g = before;
    const double nx = -0.5 + s.first * 0.25 + 0.01, ny = 0.75 + s.second * 0.25 + 0.01;
    g.updateOrigin(nx, ny);
    expectShifted(before, g, nx, ny);
  }
}

// followOrigin: the origin of a grid on the same lattice, reached by a sum of float steps (as a master
// moved by costmap_2d's rule is): rounded to whole cells, never floored, and taken exactly.
TEST(Costmap2DOrigin, FollowOriginRoundsToTheLatticeAndTakesTheOriginExactly)
{
  const Costmap2D before = numberedGrid(7, 6, 0.05, 0.0, 0.0);
  // -0.05 * 3 summed as 0 - 0.05 - 0.05 - 0.05 is -0.15000000000000002: the floor of its shift is -4.
  const double target_x = 0.0 - 0.05 - 0.05 - 0.05, target_y = 0.0 + 0.05 + 0.05;
  ASSERT_EQ(std::floor((target_x - 0.0) / 0.05), -4.0);
  Costmap2D g = before;
  const std::pair<int, int> shift = g.followOrigin(target_x, target_y);
  EXPECT_EQ(shift, std::make_pair(-3, 2));
  EXPECT_EQ(g.getOriginX(), target_x);
  EXPECT_EQ(g.getOriginY(), target_y);
  for (unsigned y = 0; y < 6; ++y)
    for (unsigned x = 0; x < 7; ++x)
    {
      const int ox = static_cast<int>(x) - 3, oy = static_cast<int>(y) + 2;  // the old cell now here
      const bool kept = ox >= 0 && oy >= 0 && ox < 7 && oy < 6;
      EXPECT_EQ(g.getCost(x, y), kept ? before.getCost(ox, oy) : 0) << x << "," << y;
    }
  // Less than half a cell away: no cell moves, the origin is taken.
  Costmap2D h = before;
  EXPECT_EQ(h.followOrigin(0.024, -0.024), std::make_pair(0, 0));
  EXPECT_EQ(h.getOriginX(), 0.024);
  for (unsigned int i = 0; i < h.cellCount(); ++i)
    EXPECT_EQ(h.getCost(i), before.getCost(i));
  // A non-finite origin moves nothing; a far one keeps no cell and is taken.
  EXPECT_EQ(h.followOrigin(std::nan(""), 0.0), std::make_pair(0, 0));
  EXPECT_EQ(h.getOriginX(), 0.024);
  EXPECT_EQ(h.followOrigin(1e12, 0.0).first, 8);
  EXPECT_EQ(h.getOriginX(), 1e12);
  for (unsigned int i = 0; i < h.cellCount(); ++i)
    EXPECT_EQ(h.getCost(i), 0);
}

// ---------------------------------------------------------------- polygons

TEST(Costmap2DPolygons, OutlineOfSquare)
{
  Costmap2D g(10, 10, 1.0, 0, 0);
  std::vector<MapLocation> cells;
  g.polygonOutlineCells({{1, 1}, {3, 1}, {3, 3}, {1, 3}}, cells);
  const std::set<Cell> expected = {{1, 1}, {2, 1}, {3, 1}, {3, 2}, {3, 3}, {2, 3}, {1, 3}, {1, 2}};
  EXPECT_EQ(toSet(cells), expected);
  EXPECT_EQ(cells.size(), 12u);  // every edge includes both ends
  EXPECT_EQ(toSet(cells).count({2, 2}), 0u);
}

TEST(Costmap2DPolygons, OutlineOfTriangleIsConnectedAndHitsVertices)
{
  Costmap2D g(20, 20, 1.0, 0, 0);
  std::vector<MapLocation> cells;
  const std::vector<MapLocation> poly = {{2, 2}, {12, 5}, {4, 11}};
  g.polygonOutlineCells(poly, cells);
  const auto s = toSet(cells);
  for (const auto& v : poly)
    EXPECT_EQ(s.count({static_cast<int>(v.x), static_cast<int>(v.y)}), 1u);
  for (std::size_t k = 1; k < cells.size(); ++k)
  {
    const Cell a{static_cast<int>(cells[k - 1].x), static_cast<int>(cells[k - 1].y)};
    const Cell b{static_cast<int>(cells[k].x), static_cast<int>(cells[k].y)};
    EXPECT_TRUE(a == b || adjacent8(a, b)) << k;  // a == b where one edge ends and the next begins
  }
}

TEST(Costmap2DPolygons, EmptyPolygonGivesNothing)
{
  Costmap2D g(5, 5, 1.0, 0, 0);
  std::vector<MapLocation> cells;
  g.polygonOutlineCells({}, cells);
  g.convexFillCells({}, cells);
  EXPECT_TRUE(cells.empty());
}

TEST(Costmap2DPolygons, ConvexFillRectangle)
{
  Costmap2D g(10, 10, 1.0, 0, 0);
  std::vector<MapLocation> cells;
  g.convexFillCells({{1, 1}, {4, 1}, {4, 3}, {1, 3}}, cells);
  std::set<Cell> expected;
  for (int x = 1; x <= 4; ++x)
    for (int y = 1; y <= 3; ++y)
      expected.emplace(x, y);
  EXPECT_EQ(toSet(cells), expected);
  EXPECT_EQ(cells.size(), expected.size());  // no duplicates
}

TEST(Costmap2DPolygons, ConvexFillTriangle)
{
  Costmap2D g(10, 10, 1.0, 0, 0);
  std::vector<MapLocation> cells;
  g.convexFillCells({{0, 0}, {4, 0}, {0, 4}}, cells);
  std::set<Cell> expected;
  for (int x = 0; x <= 4; ++x)
    for (int y = 0; x + y <= 4; ++y)
      expected.emplace(x, y);
  EXPECT_EQ(toSet(cells), expected);
  EXPECT_EQ(cells.size(), 15u);
}

TEST(Costmap2DPolygons, ConvexFillContainsOutlineAndIsColumnConvex)
{
  Costmap2D g(30, 30, 1.0, 0, 0);
  const std::vector<MapLocation> poly = {{5, 3}, {20, 6}, {24, 18}, {11, 25}, {3, 14}};
  std::vector<MapLocation> outline, fill;
  g.polygonOutlineCells(poly, outline);
  g.convexFillCells(poly, fill);
  const auto f = toSet(fill), o = toSet(outline);
  for (const auto& c : o)
    EXPECT_EQ(f.count(c), 1u);
  // Every filled column is one contiguous span bounded by outline cells.
  for (int x = 0; x < 30; ++x)
  {
    int lo = 100, hi = -1, count = 0;
    for (const auto& c : f)
      if (c.first == x)
      {
        lo = std::min(lo, c.second);
        hi = std::max(hi, c.second);
        ++count;
      }
    if (count == 0) continue;
    EXPECT_EQ(count, hi - lo + 1) << x;
    EXPECT_EQ(o.count({x, lo}), 1u);
    EXPECT_EQ(o.count({x, hi}), 1u);
  }
  // An interior point is filled; points well outside are not.
  EXPECT_EQ(f.count({12, 12}), 1u);
  EXPECT_EQ(f.count({2, 2}), 0u);
  EXPECT_EQ(f.count({25, 25}), 0u);
}

TEST(Costmap2DPolygons, SetConvexPolygonCostWritesCellsInside)
{
  Costmap2D g(10, 10, 0.5, 0.0, 0.0, 0);
  const std::vector<Eigen::Vector2d> poly = {{0.6, 0.6}, {2.1, 0.6}, {2.1, 1.6}, {0.6, 1.6}};  // cells (1..4, 1..3)
  ASSERT_TRUE(g.setConvexPolygonCost(poly, 254));
  for (unsigned int y = 0; y < 10; ++y)
    for (unsigned int x = 0; x < 10; ++x)
      EXPECT_EQ(g.getCost(x, y), (x >= 1 && x <= 4 && y >= 1 && y <= 3) ? 254 : 0) << x << "," << y;
}

TEST(Costmap2DPolygons, SetConvexPolygonCostRefusesVertexOutside)
{
  Costmap2D g(10, 10, 0.5, 0.0, 0.0, 0);
  const std::vector<Eigen::Vector2d> poly = {{0.6, 0.6}, {5.1, 0.6}, {2.1, 1.6}};  // 5.1 > 5.0: outside
  EXPECT_FALSE(g.setConvexPolygonCost(poly, 254));
  for (unsigned int i = 0; i < g.cellCount(); ++i)
    EXPECT_EQ(g.getCost(i), 0);
  const std::vector<Eigen::Vector2d> neg = {{-0.1, 0.6}, {2.0, 0.6}, {2.1, 1.6}};
  EXPECT_FALSE(g.setConvexPolygonCost(neg, 254));
  for (unsigned int i = 0; i < g.cellCount(); ++i)
    EXPECT_EQ(g.getCost(i), 0);
}

// ---------------------------------------------------------------- raytraceLine and walkLine

// costmap_2d's raytraceLine (costmap_2d.h, bresenham2D; Nav2's raytrace_line_2d.hpp the same): the loop
// visits one cell per step of the major axis, up to max_length scaled to the line, and one more call
// after the loop visits the cell where it stopped: the end cell itself when the line is not cut.
TEST(Costmap2DRaytrace, HorizontalIncludesEndCell)
{
  Costmap2D g(10, 10, 1.0, 0, 0);
  const std::vector<Cell> expected = {{0, 3}, {1, 3}, {2, 3}, {3, 3}, {4, 3}, {5, 3}};
  EXPECT_EQ(raytrace(g, 0, 3, 5, 3), expected);
}

TEST(Costmap2DRaytrace, VerticalDownwardsAndLeftwards)
{
  Costmap2D g(10, 10, 1.0, 0, 0);
  const std::vector<Cell> down = {{2, 5}, {2, 4}, {2, 3}, {2, 2}, {2, 1}};
  EXPECT_EQ(raytrace(g, 2, 5, 2, 1), down);
  const std::vector<Cell> left = {{9, 0}, {8, 0}, {7, 0}, {6, 0}};
  EXPECT_EQ(raytrace(g, 9, 0, 6, 0), left);
}

TEST(Costmap2DRaytrace, DiagonalAndShallowLine)
{
  Costmap2D g(10, 10, 1.0, 0, 0);
  const std::vector<Cell> diag = {{0, 0}, {1, 1}, {2, 2}, {3, 3}};
  EXPECT_EQ(raytrace(g, 0, 0, 3, 3), diag);
  const std::vector<Cell> anti = {{5, 0}, {4, 1}, {3, 2}, {2, 3}};
  EXPECT_EQ(raytrace(g, 5, 0, 2, 3), anti);
  // (0,0) -> (5,2): Bresenham steps in y after the 2nd and 4th x step.
  const std::vector<Cell> shallow = {{0, 0}, {1, 0}, {2, 1}, {3, 1}, {4, 2}, {5, 2}};
  EXPECT_EQ(raytrace(g, 0, 0, 5, 2), shallow);
}

TEST(Costmap2DRaytrace, SameStartAndEndVisitsThatCell)
{
  Costmap2D g(10, 10, 1.0, 0, 0);
  EXPECT_EQ(raytrace(g, 4, 4, 4, 4), (std::vector<Cell>{{4, 4}}));  // no step, then the call after the loop
}

TEST(Costmap2DRaytrace, GeneralLinesAreConnectedAndEndAtTheEnd)
{
  Costmap2D g(40, 40, 1.0, 0, 0);
  const std::vector<std::pair<Cell, Cell>> lines = {{{3, 7}, {31, 12}},  {{31, 12}, {3, 7}},  {{20, 20}, {2, 39}},
                                                    {{0, 39}, {39, 0}},  {{17, 4}, {18, 35}}, {{10, 10}, {11, 10}},
                                                    {{39, 39}, {0, 30}}, {{5, 5}, {5, 6}}};
  for (const auto& l : lines)
  {
    const Cell a = l.first, b = l.second;
    const auto cells = raytrace(g, a.first, a.second, b.first, b.second);
    const int major = std::max(std::abs(b.first - a.first), std::abs(b.second - a.second));
    ASSERT_EQ(static_cast<int>(cells.size()), major + 1);
    EXPECT_EQ(cells.front(), a);
    EXPECT_EQ(cells.back(), b);
    EXPECT_EQ(std::count(cells.begin(), cells.end(), b), 1);
    for (std::size_t k = 1; k < cells.size(); ++k)
      EXPECT_TRUE(adjacent8(cells[k - 1], cells[k]));
    // Each visited cell lies within half a cell of the ideal line (Bresenham's guarantee, minor axis).
    for (const auto& c : cells)
    {
      const double dx = b.first - a.first, dy = b.second - a.second;
      const double cross = std::fabs((c.first - a.first) * dy - (c.second - a.second) * dx);
      const double minor_err = cross / std::max(std::fabs(dx), std::fabs(dy));
      EXPECT_LE(minor_err, 0.5 + 1e-9);
    }
  }
}

TEST(Costmap2DRaytrace, MaxLengthStopsEarly)
{
  Costmap2D g(20, 20, 1.0, 0, 0);
  // 4 steps, then the cell where they stopped.
  const std::vector<Cell> five = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}};
  EXPECT_EQ(raytrace(g, 0, 0, 10, 0, 4), five);
  EXPECT_EQ(raytrace(g, 0, 0, 10, 0, 100).size(), 11u);  // longer than the ray: up to the end cell
  EXPECT_EQ(raytrace(g, 0, 0, 10, 0, 0), (std::vector<Cell>{{0, 0}}));
  // Diagonal (0,0)-(6,6) is 8.49 cells long; max_length 3 scales the 6 major steps by 3/8.49: 2 steps.
  const unsigned int steps = static_cast<unsigned int>(3.0 / std::hypot(6.0, 6.0) * 6.0);
  const auto diag = raytrace(g, 0, 0, 6, 6, 3);
  ASSERT_EQ(diag.size(), steps + 1);
  EXPECT_EQ(diag, (std::vector<Cell>{{0, 0}, {1, 1}, {2, 2}}));
  for (const auto& c : diag)
    EXPECT_LE(std::hypot(c.first, c.second), 3.0);
}

TEST(Costmap2DRaytrace, MinLengthSkipsTheStart)
{
  Costmap2D g(20, 20, 1.0, 0, 0);
  const std::vector<Cell> from3 = {{3, 0}, {4, 0}, {5, 0}, {6, 0}, {7, 0}, {8, 0}, {9, 0}, {10, 0}};
  EXPECT_EQ(raytrace(g, 0, 0, 10, 0, 0xFFFFFFFFu, 3), from3);
  const std::vector<Cell> back = {{7, 5}, {6, 5}, {5, 5}, {4, 5}};
  EXPECT_EQ(raytrace(g, 10, 5, 4, 5, 0xFFFFFFFFu, 3), back);
  EXPECT_TRUE(raytrace(g, 0, 0, 2, 0, 0xFFFFFFFFu, 3).empty());  // the ray is shorter than min_length
  // Diagonal with min_length: starts at the cell min_length along the ray (truncated), 3/sqrt(2) = 2.12.
  const auto diag = raytrace(g, 0, 0, 6, 6, 0xFFFFFFFFu, 3);
  EXPECT_EQ(diag, (std::vector<Cell>{{2, 2}, {3, 3}, {4, 4}, {5, 5}, {6, 6}}));
}

TEST(Costmap2DWalkLine, IncludesBothEnds)
{
  EXPECT_EQ(walk(0, 0, 3, 0), (std::vector<Cell>{{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
  EXPECT_EQ(walk(2, 5, 2, 2), (std::vector<Cell>{{2, 5}, {2, 4}, {2, 3}, {2, 2}}));
  EXPECT_EQ(walk(0, 0, 2, 2), (std::vector<Cell>{{0, 0}, {1, 1}, {2, 2}}));
  EXPECT_EQ(walk(4, 4, 4, 4), (std::vector<Cell>{{4, 4}}));
  EXPECT_EQ(walk(-2, 1, 0, 0).front(), (Cell{-2, 1}));  // negative coordinates are fine
}

TEST(Costmap2DWalkLine, GeneralLinesAreConnected)
{
  const std::vector<std::pair<Cell, Cell>> lines = {
      {{0, 0}, {7, 3}}, {{7, 3}, {0, 0}}, {{-3, 5}, {4, -9}}, {{2, 2}, {2, -6}}, {{10, 1}, {-10, 2}}};
  for (const auto& l : lines)
  {
    const auto cells = walk(l.first.first, l.first.second, l.second.first, l.second.second);
    const int major = std::max(std::abs(l.second.first - l.first.first), std::abs(l.second.second - l.first.second));
    ASSERT_EQ(static_cast<int>(cells.size()), major + 1);
    EXPECT_EQ(cells.front(), l.first);
    EXPECT_EQ(cells.back(), l.second);
    for (std::size_t k = 1; k < cells.size(); ++k)
      EXPECT_TRUE(adjacent8(cells[k - 1], cells[k]));
  }
}
