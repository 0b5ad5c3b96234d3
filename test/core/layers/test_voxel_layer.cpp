#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "beam_reference.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/costmap/costmap_clearing.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/grid/voxel_grid.hpp"
#include "costmap_layers/core/layers/voxel_layer.hpp"
#include "fake_context.hpp"
#include "sensor_test_helpers.hpp"

using namespace costmap_layers;
using namespace costmap_layers_test;

namespace
{
ParamValue voxelParams(std::initializer_list<std::pair<const char*, ParamValue>> layer_extra = {})
{
  ParamValue src = paramMap({{"data_type", S("PointCloud2")},
                             {"clearing", B(true)},
                             {"obstacle_max_range", D(100.0)},
                             {"raytrace_max_range", D(100.0)},
                             {"max_obstacle_height", D(5.0)}});
  ParamValue p = paramMap({{"observation_sources", S("cloud")}, {"max_obstacle_height", D(5.0)}});
  p.set("cloud", src);
  for (const auto& it : layer_extra)
    p.set(it.first, it.second);
  return p;
}

int count(const Costmap2D& c, uint8_t v)
{
  int n = 0;
  for (std::size_t k = 0; k < c.cellCount(); ++k)
    n += c.data()[k] == v;
  return n;
}

struct Rig
{
  explicit Rig(ParamValue params, bool track_unknown = true, bool rolling = false) : lc("map", rolling, track_unknown)
  {
    lc.resizeMap(10, 10, 1.0, 0.0, 0.0);
    ctx = std::make_shared<FakeContext>(std::move(params));
    layer = std::make_shared<VoxelLayer>();
    layer->initialize(&lc, "voxels", ctx);
    ctx->bind(*layer);
    lc.addPlugin(layer);
  }
  /// Points in the global frame seen from a sensor at `o` (no rotation).
  void cloud(const std::vector<XYZ>& pts, XYZ o)
  {
    std::vector<XYZ> local;
    for (const XYZ& p : pts)
      local.push_back({p.x - o.x, p.y - o.y, p.z - o.z});
    ASSERT_EQ(ctx->publishCloud("cloud", makeCloud(local), poseAt(o.x, o.y, o.z)), 1);
  }
  void update(double x = 0, double y = 0) { lc.updateMap(x, y, 0); }
  const Costmap2D& master() const { return lc.getCostmap(); }

  LayeredCostmap lc;
  std::shared_ptr<FakeContext> ctx;
  std::shared_ptr<VoxelLayer> layer;
};
}  // namespace

TEST(VoxelConfig, DefaultsFollowCostmap2dAndRejectsBadValues)
{
  const VoxelConfig c = parseVoxelConfig(ParamReader(ParamValue::makeMap(), "v"));
  EXPECT_DOUBLE_EQ(c.origin_z, 0.0);
  EXPECT_DOUBLE_EQ(c.z_resolution, 0.2);
  EXPECT_EQ(c.z_voxels, 10);
  EXPECT_EQ(c.unknown_threshold, 15);
  EXPECT_EQ(c.mark_threshold, 0);
  EXPECT_FALSE(c.publish_voxel_map);
  auto bad = [](const char* k, ParamValue v) {
    EXPECT_THROW(parseVoxelConfig(ParamReader(paramMap({{k, v}}), "v")), std::invalid_argument) << k;
  };
  bad("z_voxels", I(17));
  bad("z_voxels", I(0));
  bad("z_resolution", D(0.0));
  bad("z_resolution", D(-0.1));
  bad("unknown_threshold", I(-1));
  bad("mark_threshold", I(17));
  bad("publish_voxel_map", S("yes"));
  // Through the layer: the obstacle parameters and the voxel ones are both read.
  LayeredCostmap lc("map", false, true);
  lc.resizeMap(10, 10, 1.0, 0, 0);
  auto layer = std::make_shared<VoxelLayer>();
  EXPECT_THROW(layer->initialize(&lc, "v", std::make_shared<FakeContext>(paramMap({{"z_voxels", I(20)}}))),
               std::invalid_argument);
  auto ok = std::make_shared<VoxelLayer>();
  ok->initialize(&lc, "v",
                 std::make_shared<FakeContext>(paramMap({{"z_voxels", I(16)}, {"combination_method", I(0)}})));
  EXPECT_EQ(ok->voxels().sizeZ(), 16u);
  EXPECT_EQ(ok->config().combination_method, 0);
}

TEST(VoxelGrid, BitsCountsAndThresholds)
{
  VoxelGrid g;
  EXPECT_THROW(g.resize(4, 4, 17), std::invalid_argument);
  g.resize(4, 3, 10);
  EXPECT_EQ(g.sizeX(), 4u);
  EXPECT_EQ(g.sizeY(), 3u);
  EXPECT_EQ(g.unknownColumn(), 0x3FFu);
  EXPECT_EQ(VoxelGrid::unknownCount(g.column(1, 1)), 10u);
  EXPECT_EQ(g.getVoxel(1, 1, 3), VoxelStatus::Unknown);
  EXPECT_EQ(g.getVoxel(9, 1, 3), VoxelStatus::Unknown);  // outside
  EXPECT_FALSE(g.markVoxel(1, 1, 3, 1));                 // one marked, threshold 1: not yet
  EXPECT_EQ(g.getVoxel(1, 1, 3), VoxelStatus::Marked);
  EXPECT_TRUE(g.markVoxel(1, 1, 4, 1));
  EXPECT_EQ(VoxelGrid::markedCount(g.column(1, 1)), 2u);
  EXPECT_EQ(VoxelGrid::unknownCount(g.column(1, 1)), 8u);
  EXPECT_EQ(g.getColumn(1, 1, 16, 1), VoxelStatus::Marked);
  EXPECT_EQ(g.getColumn(1, 1, 16, 2), VoxelStatus::Free);
  EXPECT_EQ(g.getColumn(1, 1, 7, 2), VoxelStatus::Unknown);
  g.clearVoxel(1, 1, 3);
  g.clearVoxel(1, 1, 5);
  EXPECT_EQ(g.getVoxel(1, 1, 3), VoxelStatus::Free);
  EXPECT_EQ(g.getVoxel(1, 1, 5), VoxelStatus::Free);
  EXPECT_EQ(VoxelGrid::markedCount(g.column(1, 1)), 1u);
  EXPECT_EQ(VoxelGrid::unknownCount(g.column(1, 1)), 7u);
  EXPECT_FALSE(g.markVoxel(7, 1, 0, 0));  // outside: ignored
  g.reset();
  EXPECT_EQ(g.column(1, 1), 0x3FFu);
}

TEST(VoxelGrid, ShiftKeepsSharedColumns)
{
  VoxelGrid g;
  g.resize(5, 5, 4);
  g.markVoxel(3, 2, 1, 0);
  g.shift(2, -1);  // new (x, y) = old (x + 2, y - 1)
  EXPECT_EQ(g.getVoxel(1, 3, 1), VoxelStatus::Marked);
  EXPECT_EQ(g.getVoxel(3, 2, 1), VoxelStatus::Unknown);
  int marked = 0;
  for (unsigned y = 0; y < 5; ++y)
    for (unsigned x = 0; x < 5; ++x)
      marked += VoxelGrid::markedCount(g.column(x, y));
  EXPECT_EQ(marked, 1);
  g.shift(10, 0);
  EXPECT_EQ(g.getVoxel(1, 3, 1), VoxelStatus::Unknown);
}

// costmap_2d's voxel_grid raytraceLine (bresenham3D) calls its action once more after its loop: the
// end voxel is cleared too.
TEST(VoxelGrid, WalkLineIncludesTheEndVoxelAndStaysInside)
{
  VoxelGrid g;
  g.resize(10, 10, 8);
  std::vector<std::array<unsigned, 3>> seen;
  auto at = [&](unsigned index, unsigned z) { seen.push_back({index % 10, index / 10, z}); };
  g.walkLine(at, 0.5, 0.5, 0.5, 6.5, 0.5, 6.5);
  ASSERT_EQ(seen.size(), 7u);
  for (unsigned i = 0; i < 7; ++i)
  {
    EXPECT_EQ(seen[i][0], i);
    EXPECT_EQ(seen[i][1], 0u);
    EXPECT_EQ(seen[i][2], i);
  }
  seen.clear();
  g.walkLine(at, 2.5, 2.5, 2.5, 2.7, 2.9, 2.1);  // inside one voxel: that voxel, once
  EXPECT_EQ(seen, (std::vector<std::array<unsigned, 3>>{{2, 2, 2}}));
  seen.clear();
  g.walkLine(at, 0.0, 0.0, 0.0, 9.999, 9.999, 7.999);
  ASSERT_FALSE(seen.empty());
  for (const auto& s : seen)
    EXPECT_TRUE(s[0] < 10 && s[1] < 10 && s[2] < 8);
  EXPECT_EQ(seen.back(), (std::array<unsigned, 3>{9, 9, 7}));
  for (std::size_t k = 1; k < seen.size(); ++k)
    EXPECT_NE(seen[k], seen[k - 1]);  // each voxel once
}

TEST(VoxelLayer, MarksIn3D)
{
  Rig rig(voxelParams());
  // z levels of 0.2 m from 0: 0.3 -> level 1, 1.9 -> level 9, 2.1 -> above the grid (not marked).
  rig.cloud({{5.5, 5.5, 0.3}, {6.5, 5.5, 1.9}, {7.5, 5.5, 2.1}}, {5.5, 2.5, 0.3});
  rig.update();
  EXPECT_EQ(rig.master().getCost(5, 5), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.master().getCost(6, 5), LETHAL_OBSTACLE);
  EXPECT_NE(rig.master().getCost(7, 5), LETHAL_OBSTACLE);
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 2);
  EXPECT_EQ(rig.layer->voxels().getVoxel(5, 5, 1), VoxelStatus::Marked);
  EXPECT_EQ(rig.layer->voxels().getVoxel(6, 5, 9), VoxelStatus::Marked);
  EXPECT_EQ(rig.layer->voxels().getVoxel(5, 5, 2), VoxelStatus::Unknown);
}

TEST(VoxelLayer, ClearsOnlyTheVoxelsARayCrosses)
{
  Rig rig(voxelParams());
  rig.cloud({{5.5, 5.5, 0.3}}, {0.5, 5.5, 0.3});
  rig.update();
  ASSERT_EQ(rig.master().getCost(5, 5), LETHAL_OBSTACLE);
  for (unsigned x = 0; x < 5; ++x)
    EXPECT_EQ(rig.master().getCost(x, 5), FREE_SPACE) << x;

  // A ray at 1.5 m passes over the obstacle: it stays.
  rig.cloud({{9.5, 5.5, 1.5}}, {0.5, 5.5, 1.5});
  rig.update();
  EXPECT_EQ(rig.master().getCost(5, 5), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.layer->voxels().getVoxel(5, 5, 7), VoxelStatus::Free);
  EXPECT_EQ(rig.layer->voxels().getVoxel(5, 5, 1), VoxelStatus::Marked);
  EXPECT_EQ(rig.master().getCost(9, 5), LETHAL_OBSTACLE);

  // A ray at the obstacle's height clears it.
  rig.cloud({{9.5, 5.5, 0.3}}, {0.5, 5.5, 0.3});
  rig.update();
  EXPECT_EQ(rig.layer->voxels().getVoxel(5, 5, 1), VoxelStatus::Free);
  EXPECT_EQ(rig.master().getCost(5, 5), FREE_SPACE);
  EXPECT_EQ(rig.master().getCost(9, 5), LETHAL_OBSTACLE);  // two voxels marked there now
}

TEST(VoxelLayer, UnknownThresholdDecidesClearedCells)
{
  // 10 levels, one cleared: 9 unknown. Threshold 8 -> unknown, 9 -> free.
  for (int threshold : {8, 9})
  {
    Rig rig(voxelParams({{"unknown_threshold", I(threshold)}}));
    rig.cloud({{6.5, 5.5, 0.3}}, {0.5, 5.5, 0.3});
    rig.update();
    const uint8_t expected = threshold == 8 ? NO_INFORMATION : FREE_SPACE;
    for (unsigned x = 0; x < 6; ++x)
      EXPECT_EQ(rig.layer->costmap().getCost(x, 5), expected) << threshold << " " << x;
  }
}

TEST(VoxelLayer, MarkThresholdNeedsMoreVoxels)
{
  Rig rig(voxelParams({{"mark_threshold", I(1)}}));
  rig.cloud({{5.5, 5.5, 0.3}}, {5.5, 2.5, 0.3});
  rig.update();
  EXPECT_NE(rig.master().getCost(5, 5), LETHAL_OBSTACLE);
  rig.cloud({{5.5, 5.5, 0.3}, {5.5, 5.5, 0.9}}, {5.5, 2.5, 0.3});
  rig.update();
  EXPECT_EQ(rig.master().getCost(5, 5), LETHAL_OBSTACLE);
}

TEST(VoxelLayer, RollingWindowMovesTheColumns)
{
  ParamValue p = voxelParams();
  p.set("cloud", paramMap({{"data_type", S("PointCloud2")}, {"observation_persistence", D(0.1)}}));
  Rig rig(p, true, true);
  rig.ctx->now_ns = 1'000'000'000;
  rig.cloud({{6.5, 5.5, 0.3}}, {5.0, 5.0, 0.3});
  rig.update(5.0, 5.0);
  ASSERT_EQ(rig.layer->voxels().getVoxel(6, 5, 1), VoxelStatus::Marked);
  rig.ctx->now_ns = 2'000'000'000;
  rig.update(7.0, 5.0);  // origin (2, 0)
  EXPECT_EQ(rig.layer->voxels().getVoxel(4, 5, 1), VoxelStatus::Marked);
  EXPECT_EQ(rig.layer->voxels().getVoxel(6, 5, 1), VoxelStatus::Unknown);
  EXPECT_EQ(rig.layer->costmap().getCost(4, 5), LETHAL_OBSTACLE);
}

TEST(VoxelLayer, OriginOutsideTheColumnsClearsNothing)
{
  Rig rig(voxelParams());
  rig.cloud({{5.5, 5.5, 0.3}}, {0.5, 5.5, 2.5});  // above the 2 m of voxels
  rig.update();
  EXPECT_EQ(rig.master().getCost(5, 5), LETHAL_OBSTACLE);
  EXPECT_EQ(count(rig.master(), FREE_SPACE), 0);
  EXPECT_EQ(rig.ctx->countReports("outside the voxel grid"), 1);
}

TEST(VoxelLayer, ResetAndFootprintClearing)
{
  Rig rig(voxelParams());
  rig.lc.setFootprint({{-0.4, -0.4}, {0.4, -0.4}, {0.4, 0.4}, {-0.4, 0.4}});
  rig.cloud({{5.5, 5.5, 0.3}, {2.5, 2.5, 0.3}}, {2.5, 5.5, 0.3});
  rig.update(5.5, 5.5);
  EXPECT_EQ(rig.master().getCost(5, 5), FREE_SPACE);  // under the robot
  EXPECT_EQ(rig.master().getCost(2, 2), LETHAL_OBSTACLE);
  rig.layer->reset();
  EXPECT_EQ(rig.layer->voxels().getVoxel(2, 2, 1), VoxelStatus::Unknown);
  EXPECT_EQ(count(rig.layer->costmap(), NO_INFORMATION), 100);
}

// A "clear costmaps" request (move_base's clear-costmap recovery, the node's ~clear_around_robot) clears
// a cell's column with it. Before, only the 2-D cell was cleared: a phantom voxel left in the column
// kept the cell lethal after a real obstacle in it had been marked and cleared again.
TEST(VoxelLayer, AClearedCellLosesItsColumn)
{
  Rig rig(voxelParams());
  rig.cloud({{5.5, 5.5, 1.5}}, {0.5, 5.5, 1.5});  // a phantom at level 7
  rig.update();
  ASSERT_EQ(rig.master().getCost(5, 5), LETHAL_OBSTACLE);
  ASSERT_EQ(clearClearableLayersAround(rig.lc, 0.5, 0.5, 1.0), 1);  // keeps the cell (0, 0) only
  EXPECT_EQ(rig.layer->voxels().getVoxel(5, 5, 7), VoxelStatus::Unknown);
  EXPECT_NE(rig.layer->costmap().getCost(5, 5), LETHAL_OBSTACLE);

  // (The cloud buffered last would mark the phantom again on the next update, as in costmap_2d: the
  // next cloud replaces it.)
  rig.cloud({{5.5, 5.5, 0.3}}, {0.5, 5.5, 0.3});  // a real obstacle at level 1 ...
  rig.update();
  ASSERT_EQ(rig.master().getCost(5, 5), LETHAL_OBSTACLE);
  rig.cloud({{9.5, 5.5, 0.3}}, {0.5, 5.5, 0.3});  // ... that goes: a ray at its height passes
  rig.update();
  EXPECT_EQ(rig.master().getCost(5, 5), FREE_SPACE);

  // costmap_2d's clearArea form, with invert: the cells between are cleared, columns included.
  rig.cloud({{5.5, 5.5, 1.5}}, {0.5, 5.5, 1.5});
  rig.update();
  ASSERT_EQ(rig.layer->voxels().getVoxel(5, 5, 7), VoxelStatus::Marked);
  ASSERT_TRUE(clearLayerArea(*rig.layer, 4, 4, 6, 6, true));  // only (5, 5) is between
  EXPECT_EQ(rig.layer->voxels().getVoxel(5, 5, 7), VoxelStatus::Unknown);
  EXPECT_EQ(rig.layer->voxels().getVoxel(9, 5, 1), VoxelStatus::Marked);  // not between: kept
}

TEST(VoxelLayer, ClearingRaysFollowTheBeamPropertyTest)
{
  // As ObstacleLayer's: random beams at the sensor's height (so the 3-D walk is the 2-D one) checked
  // against plain geometry. The voxel walk samples the exact segment from the exact origin (cut at the
  // range along the segment itself, which keeps its direction), so every cleared column holds a point
  // of the beam: its centre lies within sqrt(2)/2 cell of it, which pins the direction more tightly
  // than the check from the origin's cell that the 2-D layer gets.
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const double ranges[][2] = {{0.0, 0.45}, {0.0, 1.0}, {0.5, 2.35}, {1.2, 3.0}};  // {min, max} [m]
  int failures = 0, beams = 0;
  for (const auto& range : ranges)
  {
    ParamValue src = paramMap({{"data_type", S("PointCloud2")},
                               {"clearing", B(true)},
                               {"marking", B(false)},
                               {"raytrace_min_range", D(range[0])},
                               {"raytrace_max_range", D(range[1])},
                               {"max_obstacle_height", D(5.0)}});
    ParamValue p = paramMap({{"observation_sources", S("cloud")},
                             {"max_obstacle_height", D(5.0)},
                             {"footprint_clearing_enabled", B(false)}});
    p.set("cloud", src);
    LayeredCostmap lc("map", false, true);
    lc.resizeMap(80, 80, 0.1, -4.0, -4.0);
    auto ctx = std::make_shared<FakeContext>(p);
    auto layer = std::make_shared<VoxelLayer>();
    layer->initialize(&lc, "voxels", ctx);
    ctx->bind(*layer);
    lc.addPlugin(layer);
    for (int k = 0; k < 150; ++k)
    {
      const double ox = -2.0 + 4.0 * uni(rng), oy = -2.0 + 4.0 * uni(rng);
      const double angle = k % 8 == 0 ? (k / 8 % 8) * M_PI / 4 : 2 * M_PI * uni(rng);
      const double dist = k % 5 == 0 ? 30.0 : range[1] * (0.2 + 3.8 * uni(rng));
      const float lx = static_cast<float>(dist * std::cos(angle)), ly = static_cast<float>(dist * std::sin(angle));
      layer->reset();
      ASSERT_EQ(ctx->publishCloud("cloud", makeCloud({{lx, ly, 0.0}}), poseAt(ox, oy, 0.5)), 1);
      lc.updateMap(0, 0, 0);
      const BeamCase b{ox, oy, static_cast<float>(ox + lx), static_cast<float>(oy + ly), range[0], range[1]};
      const std::string err = checkBeam(b, layer->costmap(), FREE_SPACE, 0.75, false);
      ++beams;
      if (!err.empty() && ++failures <= 10)
        ADD_FAILURE() << "origin (" << ox << ", " << oy << ") angle " << angle << " dist " << dist << " range ["
                      << range[0] << ", " << range[1] << "]:" << err;
    }
  }
  EXPECT_EQ(failures, 0) << "of " << beams << " beams";
}
