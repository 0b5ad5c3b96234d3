// KeepoutFilter: mask values to costs, the merge rule, update windows, masks in other frames and
// resolutions, invalid values, and the round trip through a LayeredCostmap.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/filters/keepout_filter.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;
using costmap_layers_test::GridKind;

namespace
{
OccupancyGridData makeMask(uint32_t w, uint32_t h, double res, double ox, double oy, int8_t fill,
                           const std::string& frame = "map")
{
  OccupancyGridData m;
  m.frame_id = frame;
  m.width = w;
  m.height = h;
  m.resolution = res;
  m.origin_x = ox;
  m.origin_y = oy;
  m.data.assign(static_cast<std::size_t>(w) * h, fill);
  return m;
}

struct Rig
{
  LayeredCostmap lc{"map", false, false};
  std::shared_ptr<FakeContext> ctx = std::make_shared<FakeContext>();
  std::shared_ptr<KeepoutFilter> filter = std::make_shared<KeepoutFilter>();

  Rig()
  {
    filter->initialize(&lc, "keepout", ctx);
    ctx->bind(*filter);
  }
  /// Puts the filter on a 10 x 10 master at 1 m and draws a lethal mask over cells 3..5 x 3..5 once.
  void drawLethalSquare()
  {
    lc.resizeMap(10, 10, 1.0, 0.0, 0.0);
    lc.addFilter(filter);
    ctx->publishGrid(GridKind::Mask, makeMask(3, 3, 1.0, 3.0, 3.0, 100));
    lc.updateMap(0, 0, 0);
  }
  void setMask(const OccupancyGridData& m)
  {
    ctx->publishGrid(GridKind::Mask, m);
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    filter->updateBounds(0, 0, 0, &x0, &y0, &x1, &y1);
  }
};

/// Expects master to equal `before` everywhere except the listed cells, which must hold `value`.
void expectOnly(const Costmap2D& master, const Costmap2D& before, int x0, int y0, int xn, int yn, int value)
{
  for (unsigned j = 0; j < master.getSizeInCellsY(); ++j)
    for (unsigned i = 0; i < master.getSizeInCellsX(); ++i)
    {
      const bool in = static_cast<int>(i) >= x0 && static_cast<int>(i) < xn && static_cast<int>(j) >= y0 &&
                      static_cast<int>(j) < yn;
      EXPECT_EQ(master.getCost(i, j), in ? value : before.getCost(i, j)) << i << "," << j;
    }
}
}  // namespace

TEST(KeepoutFilter, CostOfMaskValues)
{
  EXPECT_EQ(maskValueCost(100), 254);
  EXPECT_EQ(maskValueCost(50), 127);
  EXPECT_EQ(maskValueCost(99), 251);  // 251.46
  EXPECT_EQ(maskValueCost(1), 3);     // 2.54
  EXPECT_EQ(maskValueCost(25), 64);   // 63.5 rounds up
  EXPECT_EQ(maskValueCost(0), 0);
  EXPECT_EQ(maskValueCost(-1), 0);
  EXPECT_EQ(maskValueCost(101), 0);
  EXPECT_EQ(maskValueCost(127), 0);
  EXPECT_EQ(maskValueCost(-2), 0);
  EXPECT_EQ(maskValueCost(-128), 0);
  for (int v = 1; v <= 100; ++v)
    EXPECT_EQ(maskValueCost(static_cast<int8_t>(v)), std::lround(v * 254.0 / 100.0)) << v;
}

TEST(KeepoutFilter, MergeRule)
{
  EXPECT_EQ(mergeFilterCost(0, 127), 127);
  EXPECT_EQ(mergeFilterCost(200, 127), 200);  // higher master stays
  EXPECT_EQ(mergeFilterCost(127, 254), 254);
  EXPECT_EQ(mergeFilterCost(30, 0), 30);
  EXPECT_EQ(mergeFilterCost(255, 0), 255);  // unknown stays unknown ...
  EXPECT_EQ(mergeFilterCost(255, 127), 255);
  EXPECT_EQ(mergeFilterCost(255, 252), 255);
  EXPECT_EQ(mergeFilterCost(255, 253), 253);  // ... unless the cost is >= 253
  EXPECT_EQ(mergeFilterCost(255, 254), 254);
  EXPECT_EQ(mergeFilterCost(254, 253), 254);
}

TEST(KeepoutFilter, LethalMaskInsideTheUpdateWindowOnly)
{
  Rig r;
  r.setMask(makeMask(3, 3, 1.0, 3.0, 3.0, 100));  // cells 3..5 x 3..5 of the master
  Costmap2D master(10, 10, 1.0, 0.0, 0.0, 0);
  const Costmap2D before = master;
  r.filter->updateCosts(master, 2, 2, 5, 5);    // window [2, 5) x [2, 5)
  expectOnly(master, before, 3, 3, 5, 5, 254);  // exactly (3..4, 3..4)
  const Costmap2D after_first = master;
  r.filter->updateCosts(master, 5, 5, 6, 6);
  expectOnly(master, after_first, 5, 5, 6, 6, 254);  // only (5, 5) more
  r.filter->updateCosts(master, 0, 0, 10, 10);
  expectOnly(master, before, 3, 3, 6, 6, 254);
  r.filter->updateCosts(master, 6, 0, 10, 10);  // a window beside the mask: nothing
  expectOnly(master, before, 3, 3, 6, 6, 254);
  EXPECT_TRUE(r.ctx->reports.empty());
  EXPECT_FALSE(r.filter->isClearable());
}

TEST(KeepoutFilter, SoftCostsAndTheMasterRule)
{
  Rig r;
  r.setMask(makeMask(3, 3, 1.0, 3.0, 3.0, 50));
  Costmap2D master(10, 10, 1.0, 0.0, 0.0, 0);
  master.setCost(4, 4, 200);
  master.setCost(3, 4, 100);
  master.setCost(5, 5, NO_INFORMATION);
  r.filter->updateCosts(master, 0, 0, 10, 10);
  EXPECT_EQ(master.getCost(3, 3), 127);
  EXPECT_EQ(master.getCost(5, 3), 127);
  EXPECT_EQ(master.getCost(4, 4), 200);  // higher master stays
  EXPECT_EQ(master.getCost(3, 4), 127);
  EXPECT_EQ(master.getCost(5, 5), NO_INFORMATION);
  EXPECT_EQ(master.getCost(2, 2), 0);
  EXPECT_EQ(master.getCost(6, 6), 0);
}

TEST(KeepoutFilter, UnknownMasterStaysUnknownUnderSoftCosts)
{
  for (const int8_t v : {int8_t{1}, int8_t{50}, int8_t{99}})
  {
    Rig r;
    r.setMask(makeMask(3, 3, 1.0, 3.0, 3.0, v));
    Costmap2D master(10, 10, 1.0, 0.0, 0.0, NO_INFORMATION);
    const Costmap2D before = master;
    r.filter->updateCosts(master, 0, 0, 10, 10);
    expectOnly(master, before, 0, 0, 0, 0, 0);  // nothing changed
  }
  Rig r;
  r.setMask(makeMask(3, 3, 1.0, 3.0, 3.0, 100));
  Costmap2D master(10, 10, 1.0, 0.0, 0.0, NO_INFORMATION);
  const Costmap2D before = master;
  r.filter->updateCosts(master, 0, 0, 10, 10);
  expectOnly(master, before, 3, 3, 6, 6, 254);
}

TEST(KeepoutFilter, FreeAndUnknownMaskValuesWriteNothing)
{
  for (const int8_t v : {int8_t{0}, int8_t{-1}})
  {
    Rig r;
    r.setMask(makeMask(3, 3, 1.0, 3.0, 3.0, v));
    Costmap2D master(10, 10, 1.0, 0.0, 0.0, 0);
    std::mt19937 rng(v + 5);
    for (unsigned j = 0; j < 10; ++j)
      for (unsigned i = 0; i < 10; ++i)
        master.setCost(i, j, static_cast<uint8_t>(rng() % 256));
    const Costmap2D before = master;
    r.filter->updateCosts(master, 0, 0, 10, 10);
    expectOnly(master, before, 0, 0, 0, 0, 0);
  }
}

TEST(KeepoutFilter, MaskInAnotherFrameIsShifted)
{
  Rig r;
  // odom -> map moves points by (+1, +1): a mask at (3, 3) in odom lies at (4, 4) in map.
  const Transform2D odom_to_map{1.0, 1.0, 0.0};
  r.ctx->transforms[{"map", "odom"}] = odom_to_map;
  r.ctx->transforms[{"odom", "map"}] = odom_to_map.inverse();
  r.setMask(makeMask(3, 3, 1.0, 3.0, 3.0, 100, "odom"));
  Costmap2D master(10, 10, 1.0, 0.0, 0.0, 0);
  const Costmap2D before = master;
  r.filter->updateCosts(master, 2, 2, 5, 5);
  expectOnly(master, before, 4, 4, 5, 5, 254);  // (3..4) shifted by one: only (4, 4) in the window
  r.filter->updateCosts(master, 0, 0, 10, 10);
  expectOnly(master, before, 4, 4, 7, 7, 254);
}

TEST(KeepoutFilter, MaskOfAnotherResolution)
{
  Rig r;
  OccupancyGridData m = makeMask(4, 2, 0.5, 3.0, 3.0, 0);  // 2 m x 1 m at 0.5 m
  m.data = {100, 100, 50, 50, 0, 0, -1, 20};
  r.setMask(m);
  Costmap2D master(10, 10, 0.25, 2.5, 2.5, 0);  // master cells 0.25 m, from (2.5, 2.5)
  r.filter->updateCosts(master, 0, 0, 10, 10);
  for (unsigned j = 0; j < 10; ++j)
    for (unsigned i = 0; i < 10; ++i)
    {
      const double x = 2.5 + (i + 0.5) * 0.25, y = 2.5 + (j + 0.5) * 0.25;
      int expected = 0;
      if (x >= 3.0 && x < 5.0 && y >= 3.0 && y < 4.0)
        expected = maskValueCost(
            m.data[static_cast<std::size_t>((y - 3.0) / 0.5) * 4 + static_cast<std::size_t>((x - 3.0) / 0.5)]);
      EXPECT_EQ(master.getCost(i, j), expected) << i << "," << j;
    }
  EXPECT_EQ(master.getCost(3, 3), 254);  // (3.375, 3.375): mask cell (0, 0)
  EXPECT_EQ(master.getCost(9, 5), 51);   // (4.875, 3.875): mask cell (3, 1) = 20
}

// A mask finer than the costmap is sampled at each costmap cell's centre (as Nav2 does): a fence one
// mask cell wide between two centres vanishes. Said once per mask, naming both resolutions.
TEST(KeepoutFilter, AMaskFinerThanTheCostmapIsWarnedAbout)
{
  Rig r;
  r.lc.resizeMap(10, 10, 1.0, 0.0, 0.0);
  r.lc.addFilter(r.filter);
  OccupancyGridData m = makeMask(40, 40, 0.25, 0.0, 0.0, 0);  // 0.25 m cells
  for (unsigned j = 0; j < 40; ++j)
    m.data[j * 40 + 16] = 100;  // a fence at x in [4.0, 4.25): no costmap centre (x.5) lies in it
  r.ctx->publishGrid(GridKind::Mask, m);
  r.lc.updateMap(0, 0, 0);
  for (unsigned j = 0; j < 10; ++j)
    for (unsigned i = 0; i < 10; ++i)
      ASSERT_EQ(r.lc.getCostmap().getCost(i, j), 0) << i << "," << j;  // the fence is gone: why the warning
  EXPECT_EQ(r.ctx->countReports("0.25 m/cell is finer than the costmap's 1 m/cell"), 1);
  r.lc.updateMap(0, 0, 0);
  EXPECT_EQ(r.ctx->countReports("is finer than the costmap's"), 1);  // once per mask
  // A mask of the costmap's resolution or coarser: no warning.
  r.ctx->publishGrid(GridKind::Mask, makeMask(10, 10, 1.0, 0.0, 0.0, 100));
  r.lc.updateMap(0, 0, 0);
  EXPECT_EQ(r.ctx->countReports("is finer than the costmap's"), 1);
}

TEST(KeepoutFilter, InvalidValuesSkippedAndWarnedOncePerMask)
{
  Rig r;
  OccupancyGridData m = makeMask(3, 3, 1.0, 3.0, 3.0, 100);
  m.data[0] = 101;
  m.data[4] = -2;
  m.data[8] = 127;
  r.setMask(m);
  Costmap2D master(10, 10, 1.0, 0.0, 0.0, 7);
  r.filter->updateCosts(master, 0, 0, 10, 10);
  EXPECT_EQ(master.getCost(3, 3), 7);
  EXPECT_EQ(master.getCost(4, 4), 7);
  EXPECT_EQ(master.getCost(5, 5), 7);
  EXPECT_EQ(master.getCost(4, 3), 254);
  ASSERT_EQ(r.ctx->reports.size(), 1u);
  EXPECT_EQ(r.ctx->reports[0].severity, Severity::Warn);
  EXPECT_NE(r.ctx->reports[0].message.find("3 values outside -1..100"), std::string::npos) << r.ctx->reports[0].message;
  EXPECT_NE(r.ctx->reports[0].message.find("keepout"), std::string::npos);
  r.filter->updateCosts(master, 0, 0, 10, 10);  // the same mask: no second warning
  EXPECT_EQ(r.ctx->reports.size(), 1u);
  // A later mask with other bad values is named too (it was warned once per process before).
  m.data[8] = 100;
  r.setMask(m);
  r.filter->updateCosts(master, 0, 0, 10, 10);
  ASSERT_EQ(r.ctx->reports.size(), 2u);
  EXPECT_NE(r.ctx->reports[1].message.find("2 values outside -1..100"), std::string::npos) << r.ctx->reports[1].message;
}

TEST(KeepoutFilter, ThroughALayeredCostmapAndToggle)
{
  Rig r;
  r.drawLethalSquare();
  const Costmap2D& g = r.lc.getCostmap();
  for (unsigned j = 0; j < 10; ++j)
    for (unsigned i = 0; i < 10; ++i)
      EXPECT_EQ(g.getCost(i, j), (i >= 3 && i < 6 && j >= 3 && j < 6) ? 254 : 0) << i << "," << j;
  r.ctx->toggle(false);
  r.lc.updateMap(0, 0, 0);
  for (unsigned j = 0; j < 10; ++j)
    for (unsigned i = 0; i < 10; ++i)
      EXPECT_EQ(r.lc.getCostmap().getCost(i, j), 0) << i << "," << j;
  r.ctx->toggle(true);
  r.lc.updateMap(0, 0, 0);
  EXPECT_EQ(r.lc.getCostmap().getCost(4, 4), 254);
}

// dynamic_reconfigure's `enabled` is the same switch as the toggle service: off clears the filter's
// cells at the next update, on draws them again, and the two agree whichever was used last.
TEST(KeepoutFilter, ReconfiguredEnabledIsTheToggle)
{
  Rig r;
  r.drawLethalSquare();
  ASSERT_EQ(r.lc.getCostmap().getCost(4, 4), 254);
  ParamValue off = ParamValue::makeMap(), on = ParamValue::makeMap();
  off.set("enabled", ParamValue::makeBool(false));
  on.set("enabled", ParamValue::makeBool(true));
  r.filter->reconfigure(off);
  EXPECT_FALSE(r.filter->enabled());
  r.lc.updateMap(0, 0, 0);
  for (unsigned j = 0; j < 10; ++j)
    for (unsigned i = 0; i < 10; ++i)
      EXPECT_EQ(r.lc.getCostmap().getCost(i, j), 0) << i << "," << j;
  r.ctx->toggle(true);  // the service switches it back on
  r.lc.updateMap(0, 0, 0);
  EXPECT_EQ(r.lc.getCostmap().getCost(4, 4), 254);
  r.ctx->toggle(false);
  r.filter->reconfigure(on);  // and reconfigure too
  r.lc.updateMap(0, 0, 0);
  EXPECT_EQ(r.lc.getCostmap().getCost(4, 4), 254);
}

TEST(KeepoutFilter, OutOfOrderMaskIsDroppedAndThePreviousKept)
{
  Rig r;
  r.ctx->now_ns = 100'000'000'000;
  OccupancyGridData newer = makeMask(3, 3, 1.0, 3.0, 3.0, 100);
  newer.stamp_ns = 50'000'000'000;
  r.setMask(newer);
  // A free mask stamped a second earlier (a replayed latched message): dropped, reported once per
  // field, and the lethal mask still draws.
  OccupancyGridData older = makeMask(3, 3, 1.0, 3.0, 3.0, 0);
  older.stamp_ns = 49'000'000'000;
  EXPECT_EQ(r.filter->setMask(std::make_shared<const OccupancyGridData>(older)),
            "header.stamp 49.000 s is older than the mask in force (stamped 50.000 s): an out-of-order or "
            "replayed message");
  r.setMask(older);
  // Each rejection is reported under the same field key (the host logs one per throttle period).
  ASSERT_EQ(r.ctx->reports.size(), 2u);
  for (const auto& rep : r.ctx->reports)
  {
    EXPECT_EQ(rep.key, "mask/header.stamp");
    EXPECT_EQ(rep.severity, Severity::Error);
  }
  Costmap2D master(10, 10, 1.0, 0.0, 0.0, 0);
  const Costmap2D before = master;
  r.filter->updateCosts(master, 0, 0, 10, 10);
  expectOnly(master, before, 3, 3, 6, 6, 254);

  // The same stamp again (a mask server republishing) and an unstamped mask are accepted.
  OccupancyGridData same = makeMask(3, 3, 1.0, 3.0, 3.0, 100);
  same.stamp_ns = newer.stamp_ns;
  EXPECT_EQ(r.filter->setMask(std::make_shared<const OccupancyGridData>(same)), "");
  OccupancyGridData unstamped = makeMask(3, 3, 1.0, 3.0, 3.0, 100);
  EXPECT_EQ(r.filter->setMask(std::make_shared<const OccupancyGridData>(unstamped)), "");

  // After the clock went back below the stamp in force (a restarted simulation), older stamps are
  // accepted, or no mask would ever be again.
  newer.stamp_ns = 50'000'000'000;
  EXPECT_EQ(r.filter->setMask(std::make_shared<const OccupancyGridData>(newer)), "");
  r.ctx->now_ns = 10'000'000'000;
  older.stamp_ns = 5'000'000'000;
  EXPECT_EQ(r.filter->setMask(std::make_shared<const OccupancyGridData>(older)), "");
  EXPECT_EQ(r.filter->getMask()->stamp_ns, older.stamp_ns);
}

// A filter whose mask never came did nothing and said nothing. Now each update says so, naming the topic.
TEST(KeepoutFilter, WaitingForTheMaskIsReported)
{
  Rig r;
  r.lc.resizeMap(10, 10, 1.0, 0.0, 0.0);
  r.lc.addFilter(r.filter);
  r.lc.updateMap(0, 0, 0);
  r.ctx->now_ns += 1'999'999'999;
  r.lc.updateMap(0, 0, 0);
  EXPECT_EQ(r.ctx->countReports("no mask yet"), 0);  // the start-up grace: 2 s from the first update
  r.ctx->now_ns += 1;
  r.lc.updateMap(0, 0, 0);
  ASSERT_EQ(r.ctx->countReports("keepout: no mask yet on /map_filter"), 1);
  EXPECT_EQ(r.ctx->reports.back().key, "waiting");
  r.ctx->publishGrid(GridKind::Mask, makeMask(3, 3, 1.0, 3.0, 3.0, 100));
  r.ctx->reports.clear();
  r.lc.updateMap(0, 0, 0);
  EXPECT_EQ(r.ctx->countReports("no mask yet"), 0);
  // Switched off, it waits for nothing.
  Rig off;
  off.lc.resizeMap(10, 10, 1.0, 0.0, 0.0);
  off.lc.addFilter(off.filter);
  off.filter->setEnabled(false);
  off.lc.updateMap(0, 0, 0);
  EXPECT_EQ(off.ctx->countReports("no mask yet"), 0);
}

TEST(KeepoutFilter, ARollingWindowDrawsTheZoneInCellsItMovesOnto)
{
  // A 10 m x 10 m window at 1 m following the robot; a mask lethal for x in [5, 8) m everywhere.
  LayeredCostmap lc{"map", true, false};
  auto ctx = std::make_shared<FakeContext>();
  auto filter = std::make_shared<KeepoutFilter>();
  filter->initialize(&lc, "keepout", ctx);
  ctx->bind(*filter);
  lc.resizeMap(10, 10, 1.0, -5.0, -5.0);
  lc.addFilter(filter);
  OccupancyGridData mask = makeMask(40, 40, 1.0, -20.0, -20.0, 0);
  for (uint32_t j = 0; j < 40; ++j)
    for (uint32_t i = 25; i < 28; ++i)
      mask.data[j * 40 + i] = 100;
  ctx->publishGrid(GridKind::Mask, mask);
  lc.updateMap(0.0, 0.0, 0.0);  // window [-5, 5): the zone is outside
  for (unsigned j = 0; j < 10; ++j)
    for (unsigned i = 0; i < 10; ++i)
      ASSERT_EQ(lc.getCostmap().getCost(i, j), FREE_SPACE) << i << "," << j;
  // Two moves without a new mask: the window's cells over x in [5, 8) m must be lethal each time.
  for (const double rx : {2.0, 4.0})
  {
    lc.updateMap(rx, 0.0, 0.0);
    const Costmap2D& m = lc.getCostmap();
    ASSERT_DOUBLE_EQ(m.getOriginX(), rx - 5.0);
    for (unsigned j = 0; j < 10; ++j)
      for (unsigned i = 0; i < 10; ++i)
      {
        const double x = m.getOriginX() + i + 0.5;
        EXPECT_EQ(m.getCost(i, j), x >= 5.0 && x < 8.0 ? LETHAL_OBSTACLE : FREE_SPACE)
            << "robot x " << rx << ", cell " << i << "," << j;
      }
  }
}
