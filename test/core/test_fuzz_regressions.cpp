// Regression tests for the crashes the fuzz targets (test/fuzz) found, one readable test per bug.
// The raw crashing inputs are kept in test/fuzz/regressions/<target>/ and replayed by scripts/dev/fuzz.sh.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "costmap_layers/core/grid/costmap_2d.hpp"
#include "costmap_layers/core/filters/keepout_filter.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/filters/speed_filter.hpp"
#include "costmap_layers/core/layers/voxel_layer.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;

// fuzz_mask, regressions/mask/rolling_far_pose: a rolling costmap at a robot pose of -2.5e307 m cast
// the cell shift (about 1e308 cells) to int: undefined behaviour (UBSan: "outside the range of
// representable values of type 'int'").
TEST(FuzzRegressions, RollingWindowFollowsAFarAwayPoseWithoutIntOverflow)
{
  Costmap2D grid(10, 10, 0.5, 0.0, 0.0, 7);
  grid.setCost(3, 3, 254);
  grid.updateOrigin(-2.5e307, 1e300);
  EXPECT_EQ(grid.getSizeInCellsX(), 10u);
  EXPECT_LT(grid.getOriginX(), -1e307);
  EXPECT_GT(grid.getOriginY(), 1e299);
  for (unsigned y = 0; y < 10; ++y)
    for (unsigned x = 0; x < 10; ++x)
      EXPECT_EQ(grid.getCost(x, y), 7) << "no cell is kept after so far a move";
  // Back near the start: again a move of more than a grid, nothing kept, nothing overflows.
  grid.updateOrigin(0.0, 0.0);
  EXPECT_EQ(grid.getCost(3, 3), 7);
}

TEST(FuzzRegressions, NonFiniteRollingPoseMovesNothing)
{
  Costmap2D grid(4, 4, 1.0, 1.0, 2.0, 0);
  grid.setCost(1, 1, 254);
  grid.updateOrigin(std::numeric_limits<double>::quiet_NaN(), 0.0);
  grid.updateOrigin(0.0, std::numeric_limits<double>::infinity());
  EXPECT_EQ(grid.getOriginX(), 1.0);
  EXPECT_EQ(grid.getOriginY(), 2.0);
  EXPECT_EQ(grid.getCost(1, 1), 254);
}

TEST(FuzzRegressions, ShiftWithinTheGridStillKeepsTheOverlap)
{
  Costmap2D grid(4, 4, 1.0, 0.0, 0.0, 0);
  grid.setCost(2, 2, 254);
  grid.updateOrigin(1.0, 1.0);
  EXPECT_EQ(grid.getCost(1, 1), 254);
  EXPECT_EQ(Costmap2D::clampCellShift(1e300, 4), 5);
  EXPECT_EQ(Costmap2D::clampCellShift(-1e300, 4), -5);
  EXPECT_EQ(Costmap2D::clampCellShift(-3.0, 4), -3);
}

// The same far-away pose through LayeredCostmap with a filter (the fuzzed path) and a VoxelLayer, whose
// columns move by the same shift as its grid.
TEST(FuzzRegressions, RollingCostmapWithVoxelLayerAndFilterAtAFarAwayPose)
{
  LayeredCostmap lc("map", true, false);
  lc.resizeMap(8, 8, 0.5, 0.0, 0.0);
  auto voxel = std::make_shared<VoxelLayer>();
  voxel->initialize(&lc, "voxels", std::make_shared<FakeContext>());
  lc.addPlugin(voxel);
  auto keepout = std::make_shared<KeepoutFilter>();
  keepout->initialize(&lc, "keepout", std::make_shared<FakeContext>());
  lc.addFilter(keepout);
  lc.updateMap(0.0, 0.0, 0.0);
  lc.updateMap(-2.5e307, 3e305, 0.0);
  lc.updateMap(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0);
  lc.updateMap(1.0, 1.0, 0.0);
  // (After such a jump the lattice is anchored at -2.5e307, so the origin is only as exact as doubles
  // there are; it must stay finite and the grid keeps its size.)
  EXPECT_EQ(lc.getCostmap().getSizeInCellsX(), 8u);
  EXPECT_TRUE(std::isfinite(lc.getCostmap().getOriginX()));
  EXPECT_TRUE(std::isfinite(lc.getCostmap().getOriginY()));
}

// fuzz_speed_limits, regressions/speed_limits/percent_of_huge_default: in percent mode with
// default_max_speed near DBL_MAX, default * percent / 100 overflowed to +inf, and +inf was published
// as the speed limit.
TEST(FuzzRegressions, PercentLimitOfAHugeDefaultStaysFinite)
{
  SpeedFilterConfig cfg;
  cfg.speed_limit_in_percent = true;
  cfg.default_max_speed = std::numeric_limits<double>::max();
  SpeedLimitsData limits;
  limits.limits = {{1, 100.0}, {2, 50.0}};
  const SpeedLimitTable table = buildSpeedLimitTable(limits, cfg, nullptr);
  ASSERT_TRUE(table.limit_mps[1].has_value());
  EXPECT_EQ(*table.limit_mps[1], std::numeric_limits<double>::max());
  ASSERT_TRUE(table.limit_mps[2].has_value());
  EXPECT_TRUE(std::isfinite(*table.limit_mps[2]));
  EXPECT_DOUBLE_EQ(*table.limit_mps[2], std::numeric_limits<double>::max() / 2);
  // Ordinary values are unchanged by the reordering.
  cfg.default_max_speed = 2.0;
  EXPECT_DOUBLE_EQ(*buildSpeedLimitTable(limits, cfg, nullptr).limit_mps[2], 1.0);
}

// fuzz_mask, regressions/mask/tiny_resolution_far_mask (found by a 5-minute run): master and mask at
// the same tiny resolution with the mask far away put the mask 1e15 cells off, and the whole-cell
// offset was cast to int (UBSan: "-1.0198e+15 is outside the range of representable values of type
// 'int'"). Such a mask now goes through the per-column path, which compares in double.
// (Resolutions below 1e-4 m/cell and origins beyond 1e7 m are now refused, so the farthest a mask can
// be is 1e7 / 1e-4 = 1e11 cells: still far beyond int, still the per-column path.)
TEST(FuzzRegressions, MaskBillionsOfCellsAwayAtTheSameResolution)
{
  constexpr double res = 1e-4;
  // A lethal 4x4 mask with its origin `cells` master cells to the right of the master's; the master's
  // costs after one update.
  auto drawWithMaskAt = [](double cells)
  {
    LayeredCostmap lc("map", false, false);
    lc.resizeMap(10, 10, res, 0.0, 0.0);
    auto keepout = std::make_shared<KeepoutFilter>();
    keepout->initialize(&lc, "keepout", std::make_shared<FakeContext>());
    lc.addFilter(keepout);
    OccupancyGridData mask;
    mask.frame_id = "map";
    mask.width = mask.height = 4;
    mask.resolution = res;
    mask.origin_x = cells * res;
    mask.data.assign(16, 100);
    EXPECT_EQ(keepout->setMask(std::make_shared<const OccupancyGridData>(mask)), "");
    lc.updateMap(0.0, 0.0, 0.0);
    return lc.getCostmap();
  };
  // 3 cells off (overlapping), a million cells either way (the offset path), 1e11 cells (the fuzzer's
  // case as far as the ranges now allow, the per-column path): drawn exactly where the mask lies,
  // nothing overflows.
  for (const double cells : {3.0, -1e6, 1e6, 1e11, -1e11})
  {
    const Costmap2D master = drawWithMaskAt(cells);
    for (unsigned y = 0; y < 10; ++y)
      for (unsigned x = 0; x < 10; ++x)
      {
        const bool under = cells == 3.0 && x >= 3 && x < 7 && y < 4;
        EXPECT_EQ(master.getCost(x, y), under ? 254 : 0) << cells << ": " << x << "," << y;
      }
  }
}
