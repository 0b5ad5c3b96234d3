// PublishSchedule: no published window outlives the grid it was computed for (resizes, origin and
// resolution changes between publishes), and publishes fall on the intended period.
#include "costmap_layers/core/costmap/publish_schedule.hpp"

#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <random>

#include "costmap_layers/core/filters/costmap_filter.hpp"

using namespace costmap_layers;

namespace
{
bool inside(const CellWindow& w, const Costmap2D& grid)
{
  return w.x0 >= 0 && w.y0 >= 0 && w.xn <= static_cast<int>(grid.getSizeInCellsX()) &&
         w.yn <= static_cast<int>(grid.getSizeInCellsY());
}
}  // namespace

TEST(ClipWindow, Edges)
{
  EXPECT_TRUE(clipWindow(CellWindow{0, 0, 0, 0}, 10, 10).empty());
  EXPECT_TRUE(clipWindow(CellWindow{5, 5, 2, 2}, 10, 10).empty());  // inverted
  EXPECT_TRUE(clipWindow(CellWindow{10, 0, 20, 5}, 10, 10).empty());
  EXPECT_TRUE(clipWindow(CellWindow{INT_MIN, INT_MIN, -1, -1}, 10, 10).empty());
  const CellWindow all = clipWindow(CellWindow{INT_MIN, INT_MIN, INT_MAX, INT_MAX}, 10, 7);
  EXPECT_EQ(all.x0, 0);
  EXPECT_EQ(all.y0, 0);
  EXPECT_EQ(all.xn, 10);
  EXPECT_EQ(all.yn, 7);
  const CellWindow part = clipWindow(CellWindow{-3, 4, 5, 100}, 10, 7);
  EXPECT_EQ(part.x0, 0);
  EXPECT_EQ(part.y0, 4);
  EXPECT_EQ(part.xn, 5);
  EXPECT_EQ(part.yn, 7);
  EXPECT_TRUE(clipWindow(CellWindow{0, 0, 5, 5}, 0, 0).empty());
}

// The outside attack: a grid grown 100x100 -> 1000x1000 and shrunk back within one publish period made
// the node send a 1000-wide window read from a 10 000-cell buffer.
TEST(PublishSchedule, GrowAndShrinkWithinOnePeriodSendsTheWholeGridNotAStaleWindow)
{
  PublishSchedule s(1.0, false);
  Costmap2D grid(100, 100, 0.05, 0, 0);
  s.noteCycle(grid, CellWindow{0, 0, 100, 100});
  ASSERT_TRUE(s.due(0.0));
  EXPECT_TRUE(s.take(grid, false).full);  // the first publish is a full one
  grid.resizeMap(1000, 1000, 0.05, 0, 0);
  s.noteCycle(grid, CellWindow{0, 0, 1000, 1000});
  grid.resizeMap(100, 100, 0.05, 0, 0);
  s.noteCycle(grid, CellWindow{10, 10, 20, 20});
  EXPECT_FALSE(s.due(0.5));
  ASSERT_TRUE(s.due(1.0));
  const PublishDecision d = s.take(grid, false);
  EXPECT_TRUE(d.full);  // the geometry changed in between: the receiver needs the whole grid again
  // Nothing left over for the next publish either.
  s.noteCycle(grid, CellWindow{});
  ASSERT_TRUE(s.due(2.0));
  const PublishDecision next = s.take(grid, false);
  EXPECT_FALSE(next.full);
  EXPECT_TRUE(next.window.empty());
}

TEST(PublishSchedule, EveryKindOfGeometryChangeDropsThePendingWindow)
{
  struct Change
  {
    const char* what;
    unsigned sx, sy;
    double res, ox, oy;
  };
  for (const Change& c : {Change{"size x", 50, 40, 0.1, 1, 2}, Change{"size y", 40, 50, 0.1, 1, 2},
                          Change{"resolution", 40, 40, 0.05, 1, 2}, Change{"origin x", 40, 40, 0.1, 1.5, 2},
                          Change{"origin y", 40, 40, 0.1, 1, -2}})
  {
    PublishSchedule s(10.0, false);
    Costmap2D grid(40, 40, 0.1, 1, 2);
    s.noteCycle(grid, CellWindow{});
    s.due(0.0);
    s.take(grid, false);
    s.noteCycle(grid, CellWindow{30, 30, 40, 40});  // pending in the old grid
    grid.resizeMap(c.sx, c.sy, c.res, c.ox, c.oy);
    s.noteCycle(grid, CellWindow{});
    ASSERT_TRUE(s.due(1.0)) << c.what;
    EXPECT_TRUE(s.take(grid, false).full) << c.what;
  }
}

TEST(PublishSchedule, WindowsAreClippedToTheGrid)
{
  PublishSchedule s(10.0, false);
  Costmap2D grid(20, 10, 0.1, 0, 0);
  s.noteCycle(grid, CellWindow{});
  s.due(0.0);
  s.take(grid, false);
  s.noteCycle(grid, CellWindow{-5, 3, 25, 40});
  s.noteCycle(grid, CellWindow{INT_MIN, INT_MIN, INT_MAX, 2});
  ASSERT_TRUE(s.due(0.1));
  const PublishDecision d = s.take(grid, false);
  ASSERT_FALSE(d.full);
  EXPECT_TRUE(inside(d.window, grid));
  EXPECT_EQ(d.window.x0, 0);
  EXPECT_EQ(d.window.y0, 0);
  EXPECT_EQ(d.window.xn, 20);
  EXPECT_EQ(d.window.yn, 10);
}

TEST(PublishSchedule, NewSubscriberAndAlwaysFullGiveFullGrids)
{
  Costmap2D grid(20, 10, 0.1, 0, 0);
  PublishSchedule s(10.0, false);
  s.noteCycle(grid, CellWindow{});
  s.due(0.0);
  s.take(grid, false);
  s.noteCycle(grid, CellWindow{1, 1, 2, 2});
  EXPECT_TRUE(s.take(grid, true).full);
  PublishSchedule always(10.0, true);
  for (int k = 0; k < 3; ++k)
  {
    always.noteCycle(grid, CellWindow{1, 1, 2, 2});
    EXPECT_TRUE(always.take(grid, false).full);
  }
}

// F Hz gives F publishes a second when cycles come at an unrelated rate (not F/2 to F, as scheduling
// on "last publish + period" did).
TEST(PublishSchedule, PublishesFallOnTheIntendedPeriod)
{
  struct Case
  {
    double publish_hz, cycle_hz;
  };
  for (const Case c : {Case{2.0, 5.0}, Case{5.0, 7.0}, Case{4.0, 20.0}, Case{10.0, 13.0}, Case{1.0, 1.7}})
  {
    PublishSchedule s(c.publish_hz, false);
    int publishes = 0;
    const int cycles = static_cast<int>(std::lround(100.0 * c.cycle_hz));  // 100 s of cycles
    for (int k = 0; k < cycles; ++k)
      publishes += s.due(k / c.cycle_hz) ? 1 : 0;
    // 100 s at publish_hz: one more for the publish at t = 0, at most one fewer for the phase.
    EXPECT_GE(publishes, static_cast<int>(100.0 * c.publish_hz)) << c.publish_hz << " Hz at " << c.cycle_hz;
    EXPECT_LE(publishes, static_cast<int>(100.0 * c.publish_hz) + 1) << c.publish_hz << " Hz at " << c.cycle_hz;
  }
}

TEST(PublishSchedule, StallsAndClockJumpsNeitherBurstNorStop)
{
  PublishSchedule s(10.0, false);
  EXPECT_TRUE(s.due(0.0));
  EXPECT_FALSE(s.due(0.05));
  EXPECT_TRUE(s.due(5.0));    // a 5 s stall: one publish, not 50
  EXPECT_FALSE(s.due(5.01));  // and the schedule restarts from there
  EXPECT_TRUE(s.due(5.15));
  EXPECT_TRUE(s.due(1.0));  // the clock went back: publish and restart, never wait for 5.2
  EXPECT_FALSE(s.due(1.05));
  EXPECT_TRUE(s.due(1.15));
  EXPECT_FALSE(s.due(NAN));
  PublishSchedule never(0.0, false);
  EXPECT_FALSE(never.due(0.0));
  EXPECT_FALSE(never.due(100.0));
  PublishSchedule bad(NAN, false);
  EXPECT_FALSE(bad.due(0.0));
}

TEST(ValidateGridUpdate, OverflowFreeAtEveryEdge)
{
  EXPECT_TRUE(validateGridUpdate(0, 0, 10, 10, 100, 10, 10).ok());
  EXPECT_TRUE(validateGridUpdate(9, 9, 1, 1, 1, 10, 10).ok());
  EXPECT_TRUE(validateGridUpdate(0, 0, 0, 0, 0, 10, 10).ok());
  struct Bad
  {
    int64_t x, y;
    uint32_t w, h;
    std::size_t n;
    const char* field;
    const char* needle;
  };
  // x = -5 with a width that wraps int32 + uint32 back into range; sizes whose product overflows 32 bits.
  for (const Bad& b :
       {Bad{-5, 0, 10, 1, 10, "x", "x=-5"}, Bad{0, INT32_MIN, 1, 1, 1, "x", "y=-2147483648"},
        Bad{1, 0, UINT32_MAX, 1, UINT32_MAX, "width", "leaves"}, Bad{INT32_MAX, 0, UINT32_MAX, 0, 0, "width", "leaves"},
        Bad{0, 0, 65536, 65536, 0, "data", "data has 0"}, Bad{0, 0, 2, 2, 3, "data", "data has 3"}})
  {
    const InputError e = validateGridUpdate(b.x, b.y, b.w, b.h, b.n, 10, 10);
    EXPECT_EQ(e.field, b.field) << e.message;
    EXPECT_NE(e.message.find(b.needle), std::string::npos) << e.message;
  }
}

// Property: over random sequences of resizes, origin moves and changed windows (any int values), no
// published window ever leaves the grid it is sent with, and a geometry change is always followed by a
// full publish.
TEST(PublishSchedule, RandomSequencesNeverPublishAWindowOutsideItsGrid)
{
  std::mt19937 rng(20261201);
  std::uniform_int_distribution<int> coin(0, 3), size(1, 300), any(INT_MIN, INT_MAX), near(-50, 350);
  for (int run = 0; run < 50; ++run)
  {
    PublishSchedule s(5.0, false);
    Costmap2D grid(static_cast<unsigned>(size(rng)), static_cast<unsigned>(size(rng)), 0.05, 0, 0);
    bool geometry_changed = true;
    double t = 0.0;
    for (int step = 0; step < 200; ++step)
    {
      if (coin(rng) == 0)
      {
        grid.resizeMap(static_cast<unsigned>(size(rng)), static_cast<unsigned>(size(rng)), coin(rng) ? 0.05 : 0.1,
                       0.5 * coin(rng), 0.0);
        geometry_changed = true;
      }
      const bool wild = coin(rng) == 0;
      const CellWindow w = wild ? CellWindow{any(rng), any(rng), any(rng), any(rng)}
                                : CellWindow{near(rng), near(rng), near(rng), near(rng)};
      s.noteCycle(grid, w);
      t += 0.1;
      if (!s.due(t)) continue;
      const PublishDecision d = s.take(grid, false);
      if (geometry_changed) EXPECT_TRUE(d.full) << "run " << run << " step " << step;
      geometry_changed = false;
      if (!d.full && !d.window.empty())
      {
        ASSERT_TRUE(inside(d.window, grid))
            << d.window.x0 << "," << d.window.y0 << " .. " << d.window.xn << "," << d.window.yn << " on "
            << grid.getSizeInCellsX() << "x" << grid.getSizeInCellsY();
      }
    }
  }
}
