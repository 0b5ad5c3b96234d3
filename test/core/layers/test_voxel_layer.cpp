#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "beam_reference.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/costmap/costmap_clearing.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
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

/// One cloud source whose rays clear up to raytrace_max_range, at any distance. The source keeps points
/// from -10 to 10 m high (a source drops the others, for clearing too, as costmap_2d's buffer does);
/// hits up to the layer's max_height [m] are marked (2.0 is the grid's top: costmap_2d's default, and
/// the height its voxel layer cuts rays at).
ParamValue rangeParams(double raytrace_max_range, double max_height = 5.0)
{
  ParamValue p = voxelParams({{"max_obstacle_height", D(max_height)}, {"footprint_clearing_enabled", B(false)}});
  p.set("cloud", paramMap({{"data_type", S("PointCloud2")},
                           {"clearing", B(true)},
                           {"obstacle_max_range", D(100.0)},
                           {"raytrace_max_range", D(raytrace_max_range)},
                           {"min_obstacle_height", D(-10.0)},
                           {"max_obstacle_height", D(10.0)}}));
  return p;
}

using Voxel = std::array<unsigned, 3>;

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

// voxel_grid's raytraceLine (bresenham3D) between whole voxels: the axis with the largest change drives
// the walk (x on a tie), the others follow error terms that start at half the step count, and the
// action is called once more after the loop, so the end voxel is visited too. Worked by hand.
TEST(VoxelGrid, TraceLineIsVoxelGridsBresenham)
{
  VoxelGrid g;
  g.resize(10, 10, 8);
  using Visit = std::array<unsigned, 4>;  // x, y, z, step
  std::vector<Visit> seen;
  auto at = [&](unsigned index, unsigned z, unsigned k) { seen.push_back({index % 10, index / 10, z, k}); };
  // (0,0,0) -> (5,2,1): x drives 5 steps; y's error 2 + 2 per step and z's 2 + 1 move on at 5.
  g.traceLine(at, 0, 0, 0, 5, 2, 1, 100);
  EXPECT_EQ(seen,
            (std::vector<Visit>{{0, 0, 0, 0}, {1, 0, 0, 1}, {2, 1, 0, 2}, {3, 1, 1, 3}, {4, 2, 1, 4}, {5, 2, 1, 5}}));
  seen.clear();
  g.traceLine(at, 0, 0, 0, 5, 2, 1, 2);  // cut after step 2: that voxel is the last one
  EXPECT_EQ(seen, (std::vector<Visit>{{0, 0, 0, 0}, {1, 0, 0, 1}, {2, 1, 0, 2}}));
  seen.clear();
  g.traceLine(at, 0, 0, 0, 6, 0, 6, 100);  // x and z change alike: x drives, z steps with it
  ASSERT_EQ(seen.size(), 7u);
  for (unsigned i = 0; i < 7; ++i)
    EXPECT_EQ(seen[i], (Visit{i, 0, i, i}));
  seen.clear();
  // Downwards, z drives 7 steps; x's error 3 + 1 per step moves on at 7 (after step 3).
  g.traceLine(at, 2, 2, 7, 3, 2, 0, 100);
  EXPECT_EQ(seen, (std::vector<Visit>{{2, 2, 7, 0},
                                      {2, 2, 6, 1},
                                      {2, 2, 5, 2},
                                      {2, 2, 4, 3},
                                      {3, 2, 3, 4},
                                      {3, 2, 2, 5},
                                      {3, 2, 1, 6},
                                      {3, 2, 0, 7}}));
  seen.clear();
  g.traceLine(at, 2, 2, 2, 2, 2, 2, 100);  // one voxel: visited once
  EXPECT_EQ(seen, (std::vector<Visit>{{2, 2, 2, 0}}));
  seen.clear();
  g.traceLine(at, 0, 0, 0, 10, 0, 0, 100);  // an end outside the grid: nothing
  g.traceLine(at, 0, 0, 8, 0, 0, 0, 100);
  EXPECT_TRUE(seen.empty());
  EXPECT_EQ(VoxelGrid::lineSteps(2, 2, 7, 3, 2, 0), 7u);
  EXPECT_EQ(VoxelGrid::lineSteps(9, 0, 0, 0, 4, 3), 9u);
}

// voxel_grid's walk as it is written there: the axis with the largest change moves every step, the two
// others each follow an error term that starts at half the driving change and moves them on when it
// reaches it (x drives on a tie with y or z, y on a tie with z). traceLine reaches the same voxels
// another way (every axis through an error term, moves as masks), so the two are compared on random
// lines in every direction, with and without a cut.
TEST(VoxelGrid, TraceLineMatchesTheDrivingAxisWalkOnRandomLines)
{
  const int nx = 23, ny = 17, nz = 16;
  VoxelGrid g;
  g.resize(nx, ny, nz);
  using Visit = std::array<int, 4>;  // x, y, z, step
  auto reference = [&](std::array<int, 3> a, std::array<int, 3> b, int last_step)
  {
    std::array<int, 3> change{}, dir{};
    for (int i = 0; i < 3; ++i)
    {
      change[i] = std::abs(b[i] - a[i]);
      dir[i] = b[i] > a[i] ? 1 : -1;
    }
    const int drive = change[0] >= change[1] && change[0] >= change[2] ? 0 : change[1] >= change[2] ? 1 : 2;
    const int steps = change[drive];
    std::array<int, 3> error{steps / 2, steps / 2, steps / 2};
    std::vector<Visit> walk;
    std::array<int, 3> v = a;
    for (int k = 0; k <= std::min(steps, last_step); ++k)
    {
      walk.push_back({v[0], v[1], v[2], k});
      v[drive] += dir[drive];
      for (int i = 0; i < 3; ++i)
      {
        if (i == drive) continue;
        error[i] += change[i];
        if (error[i] >= steps)
        {
          error[i] -= steps;
          v[i] += dir[i];
        }
      }
    }
    return walk;
  };
  std::mt19937 rng(2026);
  std::uniform_int_distribution<int> ux(0, nx - 1), uy(0, ny - 1), uz(0, nz - 1), cut(0, 30);
  int differing = 0;
  for (int n = 0; n < 20000; ++n)
  {
    const std::array<int, 3> a{ux(rng), uy(rng), uz(rng)};
    // Every fifth line runs along an axis or a diagonal, where changes tie.
    std::array<int, 3> b{ux(rng), uy(rng), uz(rng)};
    if (n % 5 == 0)
    {
      const int d = std::min({nx - 1 - a[0], ny - 1 - a[1], nz - 1 - a[2]});
      b = {a[0] + d * (n / 5 % 2), a[1] + d * (n / 10 % 2), a[2] + d};
    }
    const int last = n % 3 == 0 ? cut(rng) : 1000;
    std::vector<Visit> seen;
    g.traceLine(
        [&](unsigned index, unsigned z, unsigned k) {
          seen.push_back({int(index % nx), int(index / nx), int(z), int(k)});
        },
        a[0], a[1], a[2], b[0], b[1], b[2], last);
    if (seen != reference(a, b, last) && ++differing <= 5)
      ADD_FAILURE() << "(" << a[0] << ", " << a[1] << ", " << a[2] << ") -> (" << b[0] << ", " << b[1] << ", " << b[2]
                    << ") cut at " << last;
  }
  EXPECT_EQ(differing, 0);
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

// The rays of the tests below, worked by hand with costmap_2d's rule (VoxelLayer::raytraceFreespace
// into voxel_grid's clearVoxelLineInMap): the line runs from the sensor's voxel towards the reading's
// (cut at the grid only) in voxel units (x / resolution, y / resolution, (z - origin_z) /
// z_resolution); its walk takes one step per voxel of the driving axis and stops after
// R = ceil(raytrace_max_range / resolution) cells measured along the line in those units: step k lies
// k * L / n along a line of length L and n steps, and k * L / n <= R is cleared, the last voxel too.
// Grid: 10 x 10 cells of 1 m, 10 levels of 0.2 m from z = 0. Each case was checked against a
// transcription of costmap_2d's and Nav2's code as well (also with their two-cell shortening of the
// ray, which changes none of these cases; see the README).

// The case: a cloud point beyond raytrace_max_range, marks on its ray. The sensor at
// (0.5, 5.5, 0.3) is voxel (0, 5, 1), the point (9.5, 5.5, 0.3) voxel (9, 5, 1): L = n = 9 and step k is
// cell x = k. Range 2.4 m is R = 3 cells: x = 0..3 cleared, the marks at x = 4..8 kept. Before, the
// range cut the ray at 2.4 m (x = 2.9) and the mark at x = 3 stayed. A range of exactly 2 m is 2 cells.
TEST(VoxelLayer, ACloudPointBeyondTheRangeClearsItsRayUpToTheRangeInWholeCells)
{
  const std::pair<double, unsigned> cases[] = {{2.4, 3}, {2.0, 2}, {2.0001, 3}, {3.0, 3}, {0.5, 1}};
  for (const auto& [range, last] : cases)
  {
    Rig rig(rangeParams(range));
    std::vector<XYZ> marks;
    for (unsigned x = 1; x <= 8; ++x)
      marks.push_back({x + 0.5, 5.5, 0.3});
    rig.cloud(marks, {0.5, 5.5, 0.3});
    rig.update();
    for (unsigned x = 1; x <= 8; ++x)
      ASSERT_EQ(rig.layer->voxels().getVoxel(x, 5, 1), VoxelStatus::Marked) << range << " " << x;
    rig.cloud({{9.5, 5.5, 0.3}}, {0.5, 5.5, 0.3});
    rig.update();
    for (unsigned x = 1; x <= 8; ++x)
    {
      const bool cleared = x <= last;
      EXPECT_EQ(rig.layer->voxels().getVoxel(x, 5, 1), cleared ? VoxelStatus::Free : VoxelStatus::Marked)
          << "range " << range << " x " << x;
      EXPECT_EQ(rig.master().getCost(x, 5), cleared ? FREE_SPACE : LETHAL_OBSTACLE) << "range " << range << " x " << x;
    }
    EXPECT_EQ(rig.master().getCost(9, 5), LETHAL_OBSTACLE);  // the point itself is marked
  }
}

// The same class in 3-D: costmap_2d measures the line in voxel units, so a z voxel counts as one cell
// whatever z_resolution is, and the walk follows whole voxels.
TEST(VoxelLayer, RaysBeyondTheRangeInThreeDimensionsStopAsCostmap2dStops)
{
  auto marked = [](const Rig& rig, const Voxel& v)
  { return rig.layer->voxels().getVoxel(v[0], v[1], v[2]) == VoxelStatus::Marked; };
  auto expectCleared =
      [&](const Rig& rig, std::initializer_list<Voxel> cleared, std::initializer_list<Voxel> kept, const char* what)
  {
    for (const Voxel& v : cleared)
      EXPECT_EQ(rig.layer->voxels().getVoxel(v[0], v[1], v[2]), VoxelStatus::Free)
          << what << ": (" << v[0] << "," << v[1] << "," << v[2] << ")";
    for (const Voxel& v : kept)
      EXPECT_TRUE(marked(rig, v)) << what << ": (" << v[0] << "," << v[1] << "," << v[2] << ")";
  };
  {
    // Rising: sensor (0.5, 5.5, 0.1) = voxel units (0.5, 5.5, 0.5), point (6.5, 5.5, 1.3) = (6.5, 5.5, 6.5),
    // 6.1 m away. L = sqrt(72) = 8.49, n = 6 (x drives, z steps with it): k * 1.41 <= 3 for k <= 2, so
    // (0,5,0), (1,5,1), (2,5,2) are cleared; (3,5,3) is kept (a 3 m cut in metres reached z level 3).
    Rig rig(rangeParams(3.0));
    rig.cloud({{2.5, 5.5, 0.5}, {3.5, 5.5, 0.7}}, {0.5, 5.5, 0.1});
    rig.update();
    ASSERT_TRUE(marked(rig, {2, 5, 2}) && marked(rig, {3, 5, 3}));
    rig.cloud({{6.5, 5.5, 1.3}}, {0.5, 5.5, 0.1});
    rig.update();
    expectCleared(rig, {{1, 5, 1}, {2, 5, 2}}, {{3, 5, 3}}, "rising");
    EXPECT_EQ(rig.master().getCost(2, 5), FREE_SPACE);
    EXPECT_EQ(rig.master().getCost(3, 5), LETHAL_OBSTACLE);
  }
  {
    // Straight up, beyond the range and above the grid: the line ends in the top voxel (level 9), from
    // z = 0.5 voxel units: L = 9.5, n = 9, k * 1.056 <= 3 for k <= 2: levels 0..2 cleared, 3..5 kept
    // (a 3 m cut in metres cleared the whole column).
    Rig rig(rangeParams(3.0, 2.0));
    rig.cloud({{5.5, 5.5, 0.3}, {5.5, 5.5, 0.5}, {5.5, 5.5, 0.7}, {5.5, 5.5, 0.9}, {5.5, 5.5, 1.1}}, {5.5, 5.5, 0.1});
    rig.update();
    for (unsigned z = 1; z <= 5; ++z)
      ASSERT_TRUE(marked(rig, {5, 5, z})) << z;
    rig.cloud({{5.5, 5.5, 9.0}}, {5.5, 5.5, 0.1});
    rig.update();
    expectCleared(rig, {{5, 5, 0}, {5, 5, 1}, {5, 5, 2}}, {{5, 5, 3}, {5, 5, 4}, {5, 5, 5}}, "up");
    EXPECT_EQ(rig.layer->voxels().getVoxel(5, 5, 6), VoxelStatus::Unknown);
    EXPECT_EQ(rig.master().getCost(5, 5), LETHAL_OBSTACLE);
  }
  {
    // Straight down from level 9 (z = 9.5 voxel units) to the floor: levels 9, 8, 7 cleared, 6, 5 kept.
    Rig rig(rangeParams(3.0, 2.0));
    rig.cloud({{5.5, 5.5, 1.1}, {5.5, 5.5, 1.3}, {5.5, 5.5, 1.5}, {5.5, 5.5, 1.7}}, {5.5, 5.5, 1.9});
    rig.update();
    for (unsigned z = 5; z <= 8; ++z)
      ASSERT_TRUE(marked(rig, {5, 5, z})) << z;
    rig.cloud({{5.5, 5.5, -5.0}}, {5.5, 5.5, 1.9});
    rig.update();
    expectCleared(rig, {{5, 5, 9}, {5, 5, 8}, {5, 5, 7}}, {{5, 5, 6}, {5, 5, 5}}, "down");
  }
  {
    // Cut by the grid's top: sensor (0.5, 5.5, 1.1) = (0.5, 5.5, 5.5), point (9.5, 5.5, 2.5) leaves the top
    // (z = 2) at x = 6.29, voxel (6, 5, 9). n = 6 (x drives; z's error 3 + 4 per step moves on at 6),
    // L = 7.33: k * 1.22 <= 3 for k <= 2. The walk: (0,5,5) (1,5,6) (2,5,6) | (3,5,7) (4,5,8) (5,5,8) (6,5,9).
    Rig rig(rangeParams(3.0, 2.0));
    rig.cloud({{2.5, 5.5, 1.3}, {3.5, 5.5, 1.5}, {6.5, 5.5, 1.9}}, {0.5, 5.5, 1.1});
    rig.update();
    ASSERT_TRUE(marked(rig, {2, 5, 6}) && marked(rig, {3, 5, 7}) && marked(rig, {6, 5, 9}));
    rig.cloud({{9.5, 5.5, 2.5}}, {0.5, 5.5, 1.1});
    rig.update();
    expectCleared(rig, {{2, 5, 6}}, {{3, 5, 7}, {6, 5, 9}}, "top, 3 m");
    // With a range past the top, the whole walk, its top voxel included.
    Rig far(rangeParams(20.0, 2.0));
    far.cloud({{2.5, 5.5, 1.3}, {3.5, 5.5, 1.5}, {6.5, 5.5, 1.9}, {2.5, 5.5, 1.5}}, {0.5, 5.5, 1.1});
    far.update();
    ASSERT_TRUE(marked(far, {2, 5, 7}));
    far.cloud({{9.5, 5.5, 2.5}}, {0.5, 5.5, 1.1});
    far.update();
    // (2,5,7) lies beside the walk: the exact segment crosses it, voxel_grid's walk does not.
    expectCleared(far, {{2, 5, 6}, {3, 5, 7}, {6, 5, 9}}, {{2, 5, 7}}, "top, 20 m");
  }
}

// A ray leaving the map, beyond the range or not. Through x = 0: sensor (7.5, 2.5, 0.3), point
// (-12.5, 7.5, 0.3) leaves at (0, 4.375): the walk (7,2) (6,2) (5,3) (4,3) (3,3) (2,3) (1,4) (0,4) on
// level 1 (n = 7, y's error 3 + 2 per step moves on at 7), L = 7.73. Range 20: all of it, the border
// voxel too; range 3: k * 1.10 <= 3 for k <= 2, so (7,2) (6,2) (5,3). Through x = 10: sensor
// (6.5, 5.5, 0.3), point (20.5, 9, 0.3) leaves at (10, 6.375): the walk (6,5) (7,5) (8,6) (9,6), as in
// Nav2 (costmap_2d's voxel layer puts the end on the border itself, outside its grid, and clears
// nothing for such a ray; its obstacle layer clears to the border cell).
TEST(VoxelLayer, ARayLeavingTheMapClearsUpToTheRangeOrTheBorder)
{
  auto run = [](double range, const std::vector<XYZ>& marks, XYZ sensor, XYZ point,
                std::initializer_list<Voxel> cleared, std::initializer_list<Voxel> kept)
  {
    Rig rig(rangeParams(range));
    rig.cloud(marks, sensor);
    rig.update();
    for (const XYZ& m : marks)
      ASSERT_EQ(rig.layer->voxels().getVoxel(static_cast<unsigned>(m.x), static_cast<unsigned>(m.y), 1),
                VoxelStatus::Marked);
    rig.cloud({point}, sensor);
    rig.update();
    for (const Voxel& v : cleared)
      EXPECT_EQ(rig.layer->voxels().getVoxel(v[0], v[1], v[2]), VoxelStatus::Free)
          << "range " << range << " (" << v[0] << "," << v[1] << "," << v[2] << ")";
    for (const Voxel& v : kept)
      EXPECT_EQ(rig.layer->voxels().getVoxel(v[0], v[1], v[2]), VoxelStatus::Marked)
          << "range " << range << " (" << v[0] << "," << v[1] << "," << v[2] << ")";
  };
  const std::vector<XYZ> low = {{5.5, 3.5, 0.3}, {4.5, 3.5, 0.3}, {1.5, 4.5, 0.3}, {0.5, 4.5, 0.3}, {5.5, 2.5, 0.3}};
  run(20.0, low, {7.5, 2.5, 0.3}, {-12.5, 7.5, 0.3}, {{5, 3, 1}, {4, 3, 1}, {1, 4, 1}, {0, 4, 1}}, {{5, 2, 1}});
  run(3.0, low, {7.5, 2.5, 0.3}, {-12.5, 7.5, 0.3}, {{5, 3, 1}}, {{4, 3, 1}, {1, 4, 1}, {0, 4, 1}, {5, 2, 1}});
  const std::vector<XYZ> high = {{7.5, 5.5, 0.3}, {8.5, 6.5, 0.3}, {9.5, 6.5, 0.3}, {8.5, 5.5, 0.3}};
  run(20.0, high, {6.5, 5.5, 0.3}, {20.5, 9.0, 0.3}, {{7, 5, 1}, {8, 6, 1}, {9, 6, 1}}, {{8, 5, 1}});
  run(2.0, high, {6.5, 5.5, 0.3}, {20.5, 9.0, 0.3}, {{7, 5, 1}}, {{8, 6, 1}, {9, 6, 1}, {8, 5, 1}});
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
  // against plain geometry. voxel_grid's walk runs between whole voxels, from the origin's towards the
  // reading's (cut at the grid only, so a beam beyond the range keeps its direction): as for the 2-D
  // layer, 1.25 cells beside the beam at most, and the direction checked from the origin's cell.
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
      const std::string err = checkBeam(b, layer->costmap(), FREE_SPACE, 1.25, true);
      ++beams;
      if (!err.empty() && ++failures <= 10)
        ADD_FAILURE() << "origin (" << ox << ", " << oy << ") angle " << angle << " dist " << dist << " range ["
                      << range[0] << ", " << range[1] << "]:" << err;
    }
  }
  EXPECT_EQ(failures, 0) << "of " << beams << " beams";
}

// publish_voxel_map: the voxel outputs (costmap_2d's voxel_grid, and a cube list and a cloud for RViz)
// exist only when asked for, and a snapshot is built only while the host says someone reads one.
TEST(VoxelOutputs, NoneWithoutPublishVoxelMap)
{
  Rig rig(voxelParams());
  EXPECT_TRUE(rig.layer->outputs().empty());
}

TEST(VoxelOutputs, SnapshotOnlyWhileWanted)
{
  Rig rig(voxelParams({{"publish_voxel_map", B(true)}}), true);
  const auto& outs = rig.layer->outputs();
  ASSERT_EQ(outs.size(), 3u);
  const std::array<std::pair<OutputKind, const char*>, 3> expected{{{OutputKind::VoxelGrid, "voxel_grid"},
                                                                    {OutputKind::VoxelMarkers, "voxel_markers"},
                                                                    {OutputKind::VoxelCloud, "voxel_cloud"}}};
  for (std::size_t i = 0; i < 3; ++i)
  {
    EXPECT_EQ(outs[i].kind, expected[i].first);
    EXPECT_EQ(outs[i].topic, expected[i].second);
    EXPECT_TRUE(outs[i].on_demand);
    EXPECT_TRUE(outs[i].layer_namespace);
  }
  std::vector<OutputEvent> events;
  rig.layer->setOutputListener([&](const OutputEvent& e) { events.push_back(e); });
  // A hit at (5.5, 2.5, 0.5) m: column (5, 2), level 2 of 0.2 m voxels.
  rig.cloud({{5.5, 2.5, 0.5}}, {0.5, 2.5, 0.5});
  rig.update();
  EXPECT_TRUE(events.empty()) << "nobody reads: nothing is built";

  rig.layer->setOutputWanted("voxel_cloud", true);
  rig.layer->setOutputWanted("voxel_grid", true);
  rig.update();
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].kind, OutputKind::VoxelGrid);
  EXPECT_EQ(events[1].kind, OutputKind::VoxelCloud);
  ASSERT_TRUE(events[0].voxels);
  EXPECT_EQ(events[0].voxels.get(), events[1].voxels.get()) << "one copy per cycle, shared";
  const VoxelGridData& g = *events[0].voxels;
  EXPECT_EQ(g.size_x, 10u);
  EXPECT_EQ(g.size_y, 10u);
  EXPECT_EQ(g.size_z, 10u);
  EXPECT_DOUBLE_EQ(g.origin_x, 0.0);
  EXPECT_DOUBLE_EQ(g.origin_y, 0.0);
  EXPECT_DOUBLE_EQ(g.origin_z, 0.0);
  EXPECT_DOUBLE_EQ(g.resolution, 1.0);
  EXPECT_DOUBLE_EQ(g.z_resolution, 0.2);
  ASSERT_EQ(g.data.size(), 100u);
  const uint32_t hit = g.data[2 * 10 + 5];
  EXPECT_EQ(hit & ((1u << 18) | (1u << 2)), (1u << 18) | (1u << 2)) << std::hex << hit;
  std::vector<VoxelPoint> marked;
  EXPECT_EQ(voxelCentres(g, VoxelStatus::Marked, marked), 1u);
  ASSERT_EQ(marked.size(), 1u);
  EXPECT_FLOAT_EQ(marked[0].x, 5.5f);
  EXPECT_FLOAT_EQ(marked[0].y, 2.5f);
  EXPECT_FLOAT_EQ(marked[0].z, 0.5f);
  EXPECT_EQ(marked[0].level, 2u);

  // Readers gone: nothing more is built; a listener set later gets no old snapshot (not latched).
  rig.layer->setOutputWanted("voxel_cloud", false);
  rig.layer->setOutputWanted("voxel_grid", false);
  events.clear();
  rig.update();
  EXPECT_TRUE(events.empty());
  std::vector<OutputEvent> late;
  rig.layer->setOutputListener([&](const OutputEvent& e) { late.push_back(e); });
  EXPECT_TRUE(late.empty());
  // A topic the layer does not have is never wanted by mistake.
  rig.layer->setOutputWanted("max_speed", true);
  rig.update();
  EXPECT_TRUE(late.empty());
}

TEST(VoxelOutputs, CentresByStateLevelsInUseOnlyAndCut)
{
  VoxelGridData g;
  g.size_x = 2;
  g.size_y = 1;
  g.size_z = 3;
  g.origin_x = 1.0;
  g.origin_y = 2.0;
  g.origin_z = 0.5;
  g.resolution = 0.5;
  g.z_resolution = 0.1;
  // Column 0: level 0 marked, level 1 unknown, level 2 free. Column 1: level 2 marked, and a marked
  // level 5 above size_z, which is not part of the grid.
  g.data = {(1u << 16) | 1u | (1u << 1), (1u << 18) | (1u << 2) | (1u << 21) | (1u << 5)};
  std::vector<VoxelPoint> p;
  ASSERT_EQ(voxelCentres(g, VoxelStatus::Marked, p), 2u);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_FLOAT_EQ(p[0].x, 1.25f);
  EXPECT_FLOAT_EQ(p[0].y, 2.25f);
  EXPECT_FLOAT_EQ(p[0].z, 0.55f);
  EXPECT_FLOAT_EQ(p[1].x, 1.75f);
  EXPECT_FLOAT_EQ(p[1].z, 0.75f);
  EXPECT_EQ(p[1].level, 2u);
  ASSERT_EQ(voxelCentres(g, VoxelStatus::Unknown, p), 1u);
  EXPECT_FLOAT_EQ(p[0].x, 1.25f);
  EXPECT_FLOAT_EQ(p[0].z, 0.65f);
  ASSERT_EQ(voxelCentres(g, VoxelStatus::Free, p), 3u);
  EXPECT_FLOAT_EQ(p[0].z, 0.75f);  // column 0, level 2
  EXPECT_FLOAT_EQ(p[1].x, 1.75f);  // column 1, levels 0 and 1
  EXPECT_FLOAT_EQ(p[2].z, 0.65f);
  // At most max_points are kept; the count says how many there were.
  EXPECT_EQ(voxelCentres(g, VoxelStatus::Marked, p, 1), 2u);
  EXPECT_EQ(p.size(), 1u);
  // A grid whose data is shorter than its size, or with no columns, is read as far as it goes.
  g.data.resize(1);
  EXPECT_EQ(voxelCentres(g, VoxelStatus::Marked, p), 1u);
  g.size_x = 0;
  EXPECT_EQ(voxelCentres(g, VoxelStatus::Marked, p), 0u);
  // More than 16 levels cannot be in a column: the levels above 16 are not read.
  g.size_x = 2;
  g.size_z = 40;
  g.data = {0xFFFFFFFFu, 0u};
  EXPECT_EQ(voxelCentres(g, VoxelStatus::Marked, p), 16u);
}
