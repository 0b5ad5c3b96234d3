// AsymmetricInflationLayer: Nav2's asymmetric_inflation_layer_test (unit) and asymmetric_inflation_tests
// (integration) ported with their inputs and expected values, an exhaustive comparison with a brute-force
// reference on random grids and plans, and the plan input's bad values.
//
// Differences with Nav2's tests, and why:
//  - Nav2 checks its cost lookup table (cost_lut_disfavored_) at scaled distances; this layer has no
//    quantised table (exact distances), so the same costs are checked in the grid, at cells exactly that
//    many cells from an obstacle on the disfavoured side.
//  - Nav2's integration fixture sets its footprint before the layer joins, so its inscribed radius stays
//    0; here the layer reads the footprint when it initialises, so the square of half-side 0.1 m gives an
//    inscribed radius of 0.1 m and the expected costs below are worked out with it (e.g. Nav2's 56 at
//    0.5 m with factor 3 is 75 here: floor(252 exp(-3 (0.5 - 0.1)))).
//  - Nav2 takes a plan of fewer than two poses and falls back to symmetric inflation; here such a plan
//    is refused with an error naming `poses` and the previous plan stays (an empty plan is what a failed
//    planner publishes; the lanes should not flicker with it).
//  - Nav2's bucket-key and node-lifecycle tests (expired node, activate / deactivate) have no
//    counterpart: the index is checked through the sides it gives, and there is no lifecycle node.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/layers/asymmetric_inflation_layer.hpp"
#include "costmap_layers/core/rules/limits.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;

namespace
{
Footprint square(double half)
{
  return {{-half, -half}, {half, -half}, {half, half}, {-half, half}};
}

ParamValue params(double radius, double left, double right, double goal = 1.5)
{
  ParamValue p = ParamValue::makeMap();
  p.set("inflation_radius", ParamValue::makeDouble(radius));
  p.set("cost_scaling_factor_left", ParamValue::makeDouble(left));
  p.set("cost_scaling_factor_right", ParamValue::makeDouble(right));
  p.set("goal_distance_threshold", ParamValue::makeDouble(goal));
  return p;
}

PathData plan(const std::vector<PathData::Point>& poses, const std::string& frame = "map")
{
  PathData p;
  p.frame_id = frame;
  p.poses = poses;
  return p;
}

/// Nav2's straight path: y = 2.0, x = 0.5 .. 3.5 (its goal 4.03 m from the robot at the origin).
PathData straightPath(const std::string& frame = "map")
{
  return plan({{0.5, 2.0}, {1.5, 2.0}, {2.5, 2.0}, {3.5, 2.0}}, frame);
}

/// Nav2's fixture: a 40 x 40 grid of 0.1 m at the origin, the layer driven directly on the master grid.
struct Rig
{
  explicit Rig(const ParamValue& p, unsigned w = 40, unsigned h = 40, double res = 0.1, double inscribed = 0.1,
               double ox = 0.0, double oy = 0.0)
      : lc("map", false, false)
  {
    lc.resizeMap(w, h, res, ox, oy);
    lc.setFootprint(square(inscribed));
    ctx = std::make_shared<FakeContext>(p);
    layer = std::make_shared<AsymmetricInflationLayer>();
    layer->initialize(&lc, "asymmetric_inflation_layer", ctx);
    ctx->bind(*layer);
  }
  Costmap2D& grid() { return lc.getCostmap(); }
  void lethal(unsigned x, unsigned y) { grid().setCost(x, y, LETHAL_OBSTACLE); }
  /// One cycle over the whole grid with the robot at (rx, ry).
  void run(double rx = 0.0, double ry = 0.0)
  {
    double a = 0, b = 0, c = 0, d = 0;
    layer->updateBounds(rx, ry, 0.0, &a, &b, &c, &d);
    layer->updateCosts(grid(), 0, 0, static_cast<int>(grid().getSizeInCellsX()),
                       static_cast<int>(grid().getSizeInCellsY()));
  }
  int at(unsigned x, unsigned y) { return grid().getCost(x, y); }

  LayeredCostmap lc;
  std::shared_ptr<FakeContext> ctx;
  std::shared_ptr<AsymmetricInflationLayer> layer;
};

// Nav2's decay region values for factor 1, resolution 0.1 m, inscribed radius 0.3 m, at 4 .. 19 cells:
// floor(252 exp(-1 (0.1 d - 0.3))).
const int kFactorOne[] = {228, 206, 186, 168, 152, 138, 125, 113, 102, 92, 83, 75, 68, 62, 56, 50};
}  // namespace

// ---- Nav2's DisfavoredLutTest and CacheEdgeCasesTest, in the grid ----

// lut_uses_c_side_scaling_factor: left 1, right 7 -> the left side takes factor 1.
TEST(AsymmetricInflationNav2, DisfavouredSideUsesTheSmallerFactor)
{
  Rig r(params(2.0, 1.0, 7.0), 80, 50, 0.1, 0.3);
  ASSERT_TRUE(r.ctx->publishPath(plan({{0.5, 2.0}, {7.5, 2.0}})) == 1);
  r.lethal(40, 22);  // (4.05, 2.25): 0.25 m left of the path
  r.run();
  for (int d = 4; d <= 19; ++d)
    EXPECT_EQ(r.at(40, 22 + d), kFactorOne[d - 4]) << "d = " << d;
  for (int d = 1; d <= 2; ++d)  // within the inscribed radius (3 cells is 0.30000000000000004 m: not within)
    EXPECT_EQ(r.at(40, 22 + d), INSCRIBED_INFLATED_OBSTACLE) << "d = " << d;
  EXPECT_EQ(r.at(40, 22), LETHAL_OBSTACLE);
  EXPECT_TRUE(r.layer->asymmetryActive());
}

// lut_reflects_updated_c_side: swapping the factors swaps the sides, the costs stay the same.
TEST(AsymmetricInflationNav2, SwappedFactorsGiveTheSameCostsOnTheOtherSide)
{
  Rig r(params(2.0, 7.0, 1.0), 80, 50, 0.1, 0.3);
  r.ctx->publishPath(plan({{0.5, 2.5}, {7.5, 2.5}}));
  r.lethal(40, 22);  // (4.05, 2.25): 0.25 m right of the path
  r.run();
  for (int d = 4; d <= 19; ++d)
    EXPECT_EQ(r.at(40, 22 - d), kFactorOne[d - 4]) << "d = " << d;
}

// zero_cell_radius_produces_empty_lut: a radius of 0 inflates nothing.
TEST(AsymmetricInflationNav2, ZeroRadiusWritesNothing)
{
  Rig r(params(0.0, 1.0, 7.0));
  r.ctx->publishPath(straightPath());
  r.lethal(20, 24);
  r.run();
  for (unsigned y = 0; y < 40; ++y)
    for (unsigned x = 0; x < 40; ++x)
      EXPECT_EQ(r.at(x, y), x == 20 && y == 24 ? LETHAL_OBSTACLE : FREE_SPACE);
}

// equal_factors_use_that_value_in_lut: factor 5 both sides, at 4, 5, 7, 9 cells.
TEST(AsymmetricInflationNav2, EqualFactorsGiveThatFactorsCosts)
{
  Rig r(params(2.0, 5.0, 5.0), 80, 50, 0.1, 0.3);
  r.ctx->publishPath(plan({{0.5, 2.0}, {7.5, 2.0}}));
  r.lethal(40, 22);
  r.run();
  const int expected[] = {152, 92, 34, 12};  // floor(252 exp(-5 (0.1 d - 0.3)))
  const int d[] = {4, 5, 7, 9};
  for (int k = 0; k < 4; ++k)
  {
    EXPECT_EQ(r.at(40, 22 + d[k]), expected[k]) << d[k];
    EXPECT_EQ(r.at(40, 22 - d[k]), expected[k]) << d[k];
  }
  EXPECT_FALSE(r.layer->asymmetryActive());
}

// ---- Nav2's SpatialHashTest and ObstacleSideTest: the index and the side rule ----

namespace
{
PathSide indexedSide(const std::vector<PathSegment>& segs, double radius, double x, double y)
{
  PathSideIndex index;
  EXPECT_TRUE(index.build(segs, radius, 0.0, 0.0, 4.0, 4.0, 1u << 20));
  return index.side(x, y);
}
std::vector<PathSegment> chain(const std::vector<PathData::Point>& p)
{
  std::vector<PathSegment> s;
  for (std::size_t i = 1; i < p.size(); ++i)
    s.push_back({p[i - 1].x, p[i - 1].y, p[i].x, p[i].y});
  return s;
}
}  // namespace

TEST(AsymmetricInflationNav2, EmptyIndexGivesNoSide)
{
  PathSideIndex index;
  EXPECT_TRUE(index.build({}, 1.0, 0.0, 0.0, 4.0, 4.0, 100));
  EXPECT_EQ(index.entries(), 0u);
  EXPECT_EQ(index.side(2.0, 2.0), PathSide::None);
}

// The index keeps what it was built from: the caller's vector may go away (a temporary) or be
// changed after build() without changing the answers (the sanitizer build checks the first).
TEST(AsymmetricInflationNav2, IndexOutlivesTheSegmentsItWasBuiltFrom)
{
  PathSideIndex index;
  EXPECT_TRUE(index.build(std::vector<PathSegment>{{0.0, 2.0, 4.0, 2.0}}, 1.0, 0.0, 0.0, 4.0, 4.0, 100));
  EXPECT_EQ(index.side(1.0, 2.5), PathSide::Left);
  EXPECT_EQ(index.side(1.0, 1.5), PathSide::Right);

  std::vector<PathSegment> segs{{0.0, 2.0, 4.0, 2.0}};
  ASSERT_TRUE(index.build(segs, 1.0, 0.0, 0.0, 4.0, 4.0, 100));
  segs.assign(1000, PathSegment{4.0, 2.0, 0.0, 2.0});  // reversed and reallocated: the sides would swap
  EXPECT_EQ(index.side(1.0, 2.5), PathSide::Left);
  EXPECT_EQ(index.side(1.0, 1.5), PathSide::Right);
}

// long_segment_appears_in_all_covered_buckets: every bucket along a 3 m segment finds it.
TEST(AsymmetricInflationNav2, LongSegmentIsFoundAlongItsWholeLength)
{
  const std::vector<PathSegment> segs{{0.0, 0.5, 3.0, 0.5}};
  for (double x = 0.05; x < 3.0; x += 0.1)
  {
    EXPECT_EQ(indexedSide(segs, 1.0, x, 0.9), PathSide::Left) << x;
    EXPECT_EQ(indexedSide(segs, 1.0, x, 0.1), PathSide::Right) << x;
  }
}

// zero_length_segment_is_hashed: a zero-length segment nearest to the point is found (no side).
TEST(AsymmetricInflationNav2, ZeroLengthSegmentIsIndexed)
{
  const std::vector<PathSegment> segs{{1.5, 2.0, 1.5, 2.0}, {0.0, 1.0, 4.0, 1.0}};
  EXPECT_EQ(indexedSide(segs, 1.0, 1.5, 2.1), PathSide::None);  // 0.1 from the point, 1.1 from the line
  EXPECT_EQ(indexedSide({segs[1]}, 1.0, 1.5, 1.9), PathSide::Left);
}

// computeObstacleSide_classification, at the cell centres of Nav2's 40 x 40 grid of 0.1 m.
TEST(AsymmetricInflationNav2, ObstacleSideClassification)
{
  const auto segs = chain({{0.5, 2.0}, {1.5, 2.0}, {2.5, 2.0}, {3.5, 2.0}});
  EXPECT_EQ(indexedSide(segs, 1.0, 2.05, 2.55), PathSide::Left);
  EXPECT_EQ(indexedSide(segs, 1.0, 2.05, 1.55), PathSide::Right);
  EXPECT_EQ(indexedSide(segs, 1.0, 2.05, 3.55), PathSide::None);  // 1.55 m away
}

TEST(AsymmetricInflationNav2, ClosestSegmentSelection)
{
  const auto segs = chain({{0.5, 2.0}, {1.0, 2.0}, {1.5, 2.0}, {2.0, 2.0}, {2.0, 1.5}, {2.0, 1.0}, {2.0, 0.5}});
  EXPECT_EQ(indexedSide(segs, 1.0, 2.35, 1.75), PathSide::Left);  // east of the southbound leg
}

TEST(AsymmetricInflationNav2, DoesNotBridgeGaps)
{
  const std::vector<PathSegment> segs{{0.5, 2.0, 1.0, 2.0}, {3.0, 2.0, 3.5, 2.0}};
  EXPECT_EQ(indexedSide(segs, 1.0, 2.05, 2.55), PathSide::None);
}

TEST(AsymmetricInflationNav2, SideRuleEdgeCases)
{
  const uint32_t zero = 0, both[] = {0, 1};
  const PathSegment point{2.0, 2.0, 2.0, 2.0};
  EXPECT_EQ(sideOfSegments(&point, &zero, 1, 1.0, 2.0, 2.0), PathSide::None);  // zero length
  const PathSegment far{3.0, 3.0, 3.5, 3.0};
  EXPECT_EQ(sideOfSegments(&far, &zero, 1, 0.3, 1.5, 2.0), PathSide::None);  // outside every box
  const PathSegment base{0.0, 0.0, 2.0, 0.0};
  EXPECT_EQ(sideOfSegments(&base, &zero, 1, 1.0, 3.0, 1.0), PathSide::None);  // box corner, sqrt(2) away
  const PathSegment line{0.5, 2.0, 3.5, 2.0};
  EXPECT_EQ(sideOfSegments(&line, &zero, 1, 1.0, 1.5, 2.0), PathSide::None);  // on the segment
  const PathSegment two[] = {{0.5, 1.8, 3.5, 1.8}, {0.5, 3.5, 3.5, 3.5}};
  EXPECT_EQ(sideOfSegments(two, both, 2, 2.0, 2.0, 2.0), PathSide::Left);  // the nearer one decides
  // At exactly the radius a point still has a side (Nav2 compares distance > radius).
  const PathSegment unit{0.0, 0.0, 4.0, 0.0};
  EXPECT_EQ(sideOfSegments(&unit, &zero, 1, 0.5, 2.0, 0.5), PathSide::Left);
}

// ---- Nav2's AsymmetricInflationIntegrationTest ----

namespace
{
ParamValue nav2Fixture(double left = 10.0, double right = 10.0, double goal = 1.5)
{
  return params(0.55, left, right, goal);
}
}  // namespace

TEST(AsymmetricInflationNav2, NoPathIsSymmetricAndSaidOnce)
{
  Rig r(nav2Fixture(1.0, 10.0));
  r.lethal(20, 20);
  r.run();
  r.run();
  // 5 cells = 0.5 m with the larger factor 10: floor(252 exp(-10 (0.5 - 0.1))) = 4.
  EXPECT_EQ(r.at(15, 20), 4);
  EXPECT_EQ(r.at(25, 20), 4);
  EXPECT_EQ(r.ctx->countKey("plan/none"), 1);
  EXPECT_EQ(r.layer->status().value("inflation"), "symmetric: no plan near the costmap");
}

TEST(AsymmetricInflationNav2, EqualSidesAreSymmetric)
{
  Rig r(nav2Fixture());
  r.ctx->publishPath(straightPath());
  r.lethal(20, 20);
  r.lethal(20, 30);
  r.run();
  for (int dy = -5; dy <= 5; ++dy)
    EXPECT_EQ(r.at(15, 20 + dy), r.at(25, 20 + dy)) << dy;
}

TEST(AsymmetricInflationNav2, UnequalSidesRaiseTheDisfavouredSide)
{
  Rig r(nav2Fixture(1.0, 10.0));
  r.ctx->publishPath(straightPath());
  r.lethal(20, 24);  // (2.05, 2.45): left
  r.lethal(20, 16);  // (2.05, 1.65): right
  r.run();
  EXPECT_EQ(r.at(20, 28), 186);                            // 0.4 m, factor 1: floor(252 exp(-0.3))
  EXPECT_EQ(r.at(20, 12), 12);                             // 0.4 m, factor 10: floor(252 exp(-3))
  EXPECT_EQ(r.layer->config().cost_scaling_factor, 10.0);  // Nav2's getCostScalingFactor(): the larger
  EXPECT_EQ(r.layer->config().inflation_radius, 0.55);
}

TEST(AsymmetricInflationNav2, ShortPathIsRefusedAndThePreviousStays)
{
  Rig r(nav2Fixture(1.0, 10.0));
  EXPECT_NE(r.layer->setPlan(std::make_shared<PathData>(plan({{2.0, 2.0}}))), "");
  EXPECT_EQ(r.ctx->countKey("plan/poses"), 1);
  r.lethal(20, 20);
  r.run();
  EXPECT_EQ(r.at(15, 20), r.at(25, 20));  // still no plan: symmetric
  EXPECT_EQ(r.at(15, 20), 4);
}

TEST(AsymmetricInflationNav2, NearGoalDisablesAsymmetry)
{
  Rig r(nav2Fixture(1.0, 10.0, 5.0));  // the goal (3.5, 2.0) is 4.03 m from the robot
  r.ctx->publishPath(straightPath());
  r.lethal(20, 24);
  r.lethal(20, 16);
  r.run();
  EXPECT_EQ(r.at(20, 28), 12);
  EXPECT_EQ(r.at(20, 12), 12);
  EXPECT_EQ(r.layer->status().value("inflation"), "symmetric: within goal_distance_threshold of the goal");
  r.run(-1.0, -1.0);  // 5.4 m from the goal: asymmetric again
  EXPECT_EQ(r.at(20, 28), 186);
}

TEST(AsymmetricInflationNav2, RightSideDisfavoured)
{
  Rig r(nav2Fixture(10.0, 1.0));
  r.ctx->publishPath(straightPath());
  r.lethal(20, 16);
  r.lethal(20, 24);
  r.run();
  EXPECT_EQ(r.at(20, 12), 186);
  EXPECT_EQ(r.at(20, 28), 12);
}

TEST(AsymmetricInflationNav2, MapEdgeObstacleIsInflated)
{
  Rig r(nav2Fixture(1.0, 10.0));
  r.ctx->publishPath(straightPath());
  r.lethal(0, 20);  // (0.05, 2.05): left of the path's first segment, 0.45 m from its start
  r.run();
  EXPECT_EQ(r.at(4, 20), 186);  // Nav2: > 100 (169 with its inscribed radius 0)
}

TEST(AsymmetricInflationNav2, CostAtKnownDistanceMatchesTheFormula)
{
  Rig r(nav2Fixture(3.0, 10.0));
  r.ctx->publishPath(straightPath());
  r.lethal(20, 24);
  r.run();
  EXPECT_EQ(r.at(20, 29), 75);  // 0.5 m, factor 3: floor(252 exp(-3 (0.5 - 0.1))); Nav2: 56 +- 2 (inscribed 0)
}

TEST(AsymmetricInflationNav2, HigherCostIsNotLowered)
{
  Rig r(nav2Fixture(1.0, 10.0));
  r.ctx->publishPath(straightPath());
  r.lethal(20, 24);
  r.grid().setCost(20, 28, 200);  // the second pass would write 186
  r.run();
  EXPECT_EQ(r.at(20, 28), 200);
}

TEST(AsymmetricInflationNav2, UntransformablePlanIsSymmetricThisCycle)
{
  Rig r(nav2Fixture(1.0, 10.0));
  r.ctx->publishPath(plan({{1.0, 2.0}, {3.0, 2.0}}, "odom"));
  r.lethal(20, 24);
  r.lethal(20, 16);
  r.run();
  EXPECT_EQ(r.at(20, 28), 12);
  EXPECT_EQ(r.at(20, 12), 12);
  EXPECT_GE(r.ctx->countKey("plan/header.frame_id"), 1);
  EXPECT_EQ(r.layer->status().level, StatusLevel::Warn);
}

TEST(AsymmetricInflationNav2, RotatedTransform)
{
  Rig r(nav2Fixture(1.0, 10.0));
  const double yaw = 0.6, tx = 0.3, ty = -0.2;
  r.ctx->transforms[{"map", "odom"}] = Transform2D{tx, ty, yaw};
  std::vector<PathData::Point> poses;
  for (double x : {0.5, 1.5, 2.5, 3.5})  // y = 2.0 in the map frame, expressed in odom
  {
    const double dx = x - tx, dy = 2.0 - ty;
    poses.push_back({std::cos(yaw) * dx + std::sin(yaw) * dy, -std::sin(yaw) * dx + std::cos(yaw) * dy});
  }
  r.ctx->publishPath(plan(poses, "odom"));
  r.lethal(20, 24);
  r.run();
  EXPECT_EQ(r.at(20, 28), 186);
  EXPECT_EQ(r.at(20, 12), 0);
}

TEST(AsymmetricInflationNav2, LiveTransformTracksDrift)
{
  Rig r(nav2Fixture(1.0, 10.0, 0.0));
  r.ctx->publishPath(straightPath("odom"));
  r.ctx->transforms[{"map", "odom"}] = Transform2D{0.0, 0.0, 0.0};
  r.lethal(20, 24);
  r.lethal(20, 16);
  r.run();
  EXPECT_EQ(r.at(20, 28), 186);
  EXPECT_EQ(r.at(20, 12), 12);
  // map -> odom drifts 0.9 m north: the path is at y = 2.9, the north obstacle on its right (favoured),
  // the south one 1.25 m away (no side).
  r.grid().resetMap(0, 0, 40, 40);
  r.lethal(20, 24);
  r.lethal(20, 16);
  r.ctx->transforms[{"map", "odom"}] = Transform2D{0.0, 0.9, 0.0};
  r.run();
  EXPECT_EQ(r.at(20, 28), 12);
  EXPECT_EQ(r.at(20, 12), 12);
}

TEST(AsymmetricInflationNav2, RecoversOnceTheTransformArrives)
{
  Rig r(nav2Fixture(1.0, 10.0, 0.0));
  r.ctx->publishPath(straightPath("odom"));
  r.lethal(20, 24);
  r.lethal(20, 16);
  r.run();
  EXPECT_EQ(r.at(20, 28), r.at(20, 12));
  r.ctx->transforms[{"map", "odom"}] = Transform2D{};
  r.grid().resetMap(0, 0, 40, 40);
  r.lethal(20, 24);
  r.lethal(20, 16);
  r.run();
  EXPECT_EQ(r.at(20, 28), 186);
  EXPECT_EQ(r.at(20, 12), 12);
}

TEST(AsymmetricInflationNav2, InteriorObstacleCellsAreNoSeedsButTheBlockIsInflated)
{
  Rig r(nav2Fixture(1.0, 10.0));
  r.ctx->publishPath(straightPath());
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      r.lethal(20 + dx, 20 + dy);
  r.run();
  EXPECT_EQ(r.at(20, 26), 168);  // 5 cells above the block's top row (left): floor(252 exp(-0.4))
}

TEST(AsymmetricInflationNav2, ObstacleFarFromThePathStaysLethal)
{
  Rig r(nav2Fixture(1.0, 10.0));
  r.ctx->publishPath(straightPath());
  r.lethal(0, 0);
  r.run();
  EXPECT_EQ(r.at(0, 0), LETHAL_OBSTACLE);
  EXPECT_EQ(r.at(4, 0), 12);  // no side: the larger factor
}

TEST(AsymmetricInflationNav2, NegativeParametersAreRefusedByName)
{
  for (const char* name :
       {"inflation_radius", "cost_scaling_factor_left", "cost_scaling_factor_right", "goal_distance_threshold"})
  {
    ParamValue p = nav2Fixture();
    p.set(name, ParamValue::makeDouble(-0.1));
    try
    {
      Rig r(p);
      ADD_FAILURE() << name << " accepted";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
  ParamValue p = nav2Fixture();
  p.set("num_threads", ParamValue::makeInt(-2));
  EXPECT_THROW(Rig{p}, std::invalid_argument);
}

TEST(AsymmetricInflationNav2, ReconfigureChangesTheFactorsNotTheTopic)
{
  Rig r(nav2Fixture());
  r.ctx->publishPath(straightPath());
  r.lethal(20, 24);
  ParamValue p = nav2Fixture(1.0, 10.0);
  r.layer->reconfigure(p);
  r.run();
  EXPECT_EQ(r.at(20, 28), 186);
  p.set("plan_topic", ParamValue::makeString("other_plan"));
  EXPECT_THROW(r.layer->reconfigure(p), std::invalid_argument);
  EXPECT_EQ(r.layer->asymmetricConfig().plan_topic, "plan");
  // plan_topic is not offered for run-time change.
  for (const ParamSpec& s : r.layer->tunableParameters(p))
    EXPECT_NE(s.name, "plan_topic");
}

// ---- Exactness against a brute-force reference ----

namespace
{
/// The side of (x, y): every segment, the nearest first-found, within radius, cross-product sign.
int bruteSide(const std::vector<PathData::Point>& g, double radius, double x, double y)
{
  double best = std::numeric_limits<double>::infinity(), best_cross = 0.0;
  for (std::size_t i = 1; i < g.size(); ++i)
  {
    const double ax = g[i - 1].x, ay = g[i - 1].y, ux = g[i].x - ax, uy = g[i].y - ay;
    const double l2 = ux * ux + uy * uy;
    double d2 = 0.0, cross = 0.0;
    if (l2 < 1e-6)
      d2 = (x - ax) * (x - ax) + (y - ay) * (y - ay);
    else
    {
      // Nav2's arithmetic (the offset from the segment's start, minus t times the segment), so that ties
      // between segments meeting at a pose break the same way.
      const double cx = x - ax, cy = y - ay;
      double t = (cx * ux + cy * uy) / l2;
      t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
      const double px = cx - t * ux, py = cy - t * uy;
      d2 = px * px + py * py;
      cross = ux * (y - ay) - uy * (x - ax);
    }
    if (d2 < best) best = d2, best_cross = cross;
  }
  if (best > radius * radius) return 0;
  return best_cross > 0 ? 1 : best_cross < 0 ? -1 : 0;
}

int costAt(double d2_cells, int cap, double res, double inscribed, double factor)
{
  if (d2_cells > static_cast<double>(cap) * cap) return 0;
  const double d = std::sqrt(d2_cells);
  if (d == 0.0) return LETHAL_OBSTACLE;
  if (d * res <= inscribed) return INSCRIBED_INFLATED_OBSTACLE;
  return static_cast<int>(252.0 * std::exp(-factor * (d * res - inscribed)));
}

int merge(int old, int c, int threshold)
{
  if (old == NO_INFORMATION) return c >= threshold ? c : NO_INFORMATION;
  return std::max(old, c);
}
}  // namespace

TEST(AsymmetricInflationExact, RandomGridsAndPlansEqualBruteForce)
{
  std::mt19937 rng(37);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int cases = 0, asymmetric = 0;
  for (int trial = 0; trial < 60; ++trial)
  {
    const unsigned w = 20 + rng() % 40, h = 20 + rng() % 40;
    const double res = trial % 3 == 0 ? 0.05 : 0.1;
    const double ox = -1.0 + 2.0 * u(rng), oy = -1.0 + 2.0 * u(rng);
    const double radius = res * (1 + rng() % 12) + 0.3 * res * u(rng);
    double left = 0.5 + 12.0 * u(rng), right = 0.5 + 12.0 * u(rng);
    if (trial % 10 == 9) right = left;
    const bool around = trial % 4 == 1, inflate_unknown = trial % 5 == 2;
    ParamValue p = params(radius, left, right, 0.2);
    p.set("inflate_around_unknown", ParamValue::makeBool(around));
    p.set("inflate_unknown", ParamValue::makeBool(inflate_unknown));
    Rig r(p, w, h, res, res * 2.0 * u(rng), ox, oy);
    const double inscribed = r.layer->inscribedRadius();  // the footprint's, as the costmap computed it
    const bool odom = trial % 2 == 1;
    const Transform2D t{0.3 * u(rng), -0.4 * u(rng), 3.0 * u(rng) - 1.5};
    if (odom) r.ctx->transforms[{"map", "odom"}] = t;
    // A random walk through the map (in odom: placed by the inverse so that it still crosses the map).
    std::vector<PathData::Point> global, sent;
    double x = ox + w * res * u(rng), y = oy + h * res * u(rng), heading = 6.3 * u(rng);
    const int n = 2 + static_cast<int>(rng() % 30);
    for (int k = 0; k < n; ++k)
    {
      global.push_back({x, y});
      if (k % 7 == 3) global.push_back({x, y});  // a zero-length segment now and then
      heading += u(rng) - 0.5;
      const double step = res * (0.5 + 8.0 * u(rng));
      x += step * std::cos(heading);
      y += step * std::sin(heading);
    }
    for (const auto& g : global)
    {
      PathData::Point s = g;
      if (odom) t.inverse().apply(g.x, g.y, s.x, s.y);
      sent.push_back(s);
    }
    ASSERT_EQ(r.layer->setPlan(std::make_shared<PathData>(plan(sent, odom ? "odom" : "map"))), "");
    // The reference's own copy of the plan in the map frame, as the layer places it.
    std::vector<PathData::Point> placed;
    for (const auto& s : sent)
    {
      PathData::Point g = s;
      if (odom) t.apply(s.x, s.y, g.x, g.y);
      placed.push_back(g);
    }

    const double density = 0.02 + 0.2 * u(rng);
    for (unsigned j = 0; j < h; ++j)
      for (unsigned i = 0; i < w; ++i)
      {
        const double v = u(rng);
        r.grid().setCost(i, j,
                         v < density          ? LETHAL_OBSTACLE
                         : v < density + 0.05 ? NO_INFORMATION
                         : v < density + 0.1  ? uint8_t(rng() % 253)
                                              : FREE_SPACE);
      }
    if (trial % 6 == 0)  // solid blocks: interior cells
      for (unsigned j = h / 4; j < h / 2; ++j)
        for (unsigned i = w / 4; i < w / 2; ++i)
          r.grid().setCost(i, j, LETHAL_OBSTACLE);
    std::vector<uint8_t> before(r.grid().data(), r.grid().data() + w * h);
    // The robot far from the goal (asymmetric) except now and then (symmetric).
    const bool near = trial % 8 == 5;
    const double rx = near ? placed.back().x : placed.back().x + 100.0, ry = placed.back().y;
    // A window: the whole grid, or a part of it.
    int x0 = 0, y0 = 0, x1 = static_cast<int>(w), y1 = static_cast<int>(h);
    if (trial % 3 == 2)
    {
      x0 = static_cast<int>(rng() % (w / 2));
      y0 = static_cast<int>(rng() % (h / 2));
      x1 = x0 + 1 + static_cast<int>(rng() % (w - x0));
      y1 = y0 + 1 + static_cast<int>(rng() % (h - y0));
    }
    double a = 0, b = 0, c = 0, d = 0;
    r.layer->updateBounds(rx, ry, 0.0, &a, &b, &c, &d);
    r.layer->updateCosts(r.grid(), x0, y0, x1, y1);

    const int cap = static_cast<int>(std::ceil(radius / res));
    const double cmax = std::max(left, right), cside = std::min(left, right);
    const int disfavoured = left < right ? 1 : -1;
    const bool active = left != right && !near;
    auto source = [&](int i, int j)
    {
      const uint8_t v = before[j * w + i];
      return v == LETHAL_OBSTACLE || (around && v == NO_INFORMATION);
    };
    std::vector<std::pair<int, int>> all, seeds;
    for (int j = 0; j < static_cast<int>(h); ++j)
      for (int i = 0; i < static_cast<int>(w); ++i)
      {
        if (!source(i, j)) continue;
        all.push_back({i, j});
        const bool boundary = i == 0 || j == 0 || i == static_cast<int>(w) - 1 || j == static_cast<int>(h) - 1 ||
                              !source(i - 1, j) || !source(i + 1, j) || !source(i, j - 1) || !source(i, j + 1);
        if (active && boundary && bruteSide(placed, radius, ox + (i + 0.5) * res, oy + (j + 0.5) * res) == disfavoured)
          seeds.push_back({i, j});
      }
    asymmetric += !seeds.empty();
    const int threshold = inflate_unknown ? 1 : INSCRIBED_INFLATED_OBSTACLE;
    for (int j = 0; j < static_cast<int>(h); ++j)
      for (int i = 0; i < static_cast<int>(w); ++i)
      {
        int expected = before[j * w + i];
        if (i >= x0 && i < x1 && j >= y0 && j < y1)
        {
          auto nearest = [&](const std::vector<std::pair<int, int>>& set)
          {
            double best = std::numeric_limits<double>::infinity();
            for (const auto& [si, sj] : set)
              best = std::min(best, double((si - i) * (si - i) + (sj - j) * (sj - j)));
            return best;
          };
          const double d_all = nearest(all), d_side = nearest(seeds);
          if (std::isfinite(d_all)) expected = merge(expected, costAt(d_all, cap, res, inscribed, cmax), threshold);
          if (std::isfinite(d_side)) expected = merge(expected, costAt(d_side, cap, res, inscribed, cside), threshold);
        }
        ASSERT_EQ(static_cast<int>(r.at(i, j)), expected)
            << "trial " << trial << " cell " << i << "," << j << " left " << left << " right " << right;
        ++cases;
      }
  }
  EXPECT_GT(asymmetric, 30);  // most trials have seeds on the disfavoured side
  EXPECT_GT(cases, 50000);
}

// ---- The plan input's bad values: refused by field, the last good plan stays ----

namespace
{
/// A rig with left disfavoured and a good plan in force: (20, 28) costs 186.
struct GoodPlan : Rig
{
  GoodPlan() : Rig(nav2Fixture(1.0, 10.0))
  {
    EXPECT_EQ(layer->setPlan(std::make_shared<PathData>(straightPath())), "");
    lethal(20, 24);
  }
  void expectStillGood()
  {
    run();
    EXPECT_EQ(at(20, 28), 186);
    EXPECT_EQ(at(20, 12), 0);
  }
};
}  // namespace

TEST(AsymmetricInflationInput, BadPosesAreRefusedNamingTheField)
{
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const double too_far = limits::kMaxCoordinate * (1 + 1e-12);
  for (const PathData::Point bad : {PathData::Point{nan, 2.0}, PathData::Point{1.0, -inf},
                                    PathData::Point{too_far, 0.0}, PathData::Point{0.0, -too_far}})
  {
    GoodPlan r;
    PathData p = straightPath();
    p.poses[2] = bad;
    const std::string error = r.layer->setPlan(std::make_shared<PathData>(p));
    EXPECT_NE(error.find("poses[2].pose.position"), std::string::npos) << error;
    EXPECT_EQ(r.ctx->countKey("plan/poses[i].pose.position"), 1);
    r.expectStillGood();
  }
  // At the edge: coordinates of exactly the limit are taken.
  GoodPlan r;
  EXPECT_EQ(
      r.layer->setPlan(std::make_shared<PathData>(plan(
          {{0.5, 2.0}, {3.5, 2.0}, {limits::kMaxCoordinate, 2.0}, {limits::kMaxCoordinate, -limits::kMaxCoordinate}}))),
      "");
  r.expectStillGood();  // the same line through the costmap, left of it still disfavoured
}

TEST(AsymmetricInflationInput, EmptyAndOnePosePlansAreRefused)
{
  for (std::size_t n : {0u, 1u})
  {
    GoodPlan r;
    PathData p = straightPath();
    p.poses.resize(n);
    const std::string error = r.layer->setPlan(std::make_shared<PathData>(p));
    EXPECT_NE(error.find("poses has " + std::to_string(n) + " entries"), std::string::npos) << error;
    EXPECT_EQ(r.ctx->countKey("plan/poses"), 1);
    r.expectStillGood();
  }
  GoodPlan r;
  EXPECT_NE(r.layer->setPlan(nullptr), "");
  r.expectStillGood();
}

TEST(AsymmetricInflationInput, HugePlansAreRefusedAtTheLimit)
{
  {
    GoodPlan r;
    PathData p = straightPath();
    p.poses.assign(10'000'000, PathData::Point{1.0, 2.0});
    const std::string error = r.layer->setPlan(std::make_shared<PathData>(std::move(p)));
    EXPECT_NE(error.find("poses has 10000000 entries"), std::string::npos) << error;
    r.expectStillGood();
  }
  {
    GoodPlan r;
    PathData p = straightPath();
    p.poses.assign(limits::kMaxPathPoses + 1, PathData::Point{1.0, 2.0});
    EXPECT_NE(r.layer->setPlan(std::make_shared<PathData>(std::move(p))), "");
    r.expectStillGood();
  }
  // Exactly the limit is taken: the straight path's line, 1 cm a segment (Nav2 gives no direction to a
  // segment under 1 mm), 2 km long.
  GoodPlan r;
  PathData p;
  p.frame_id = "map";
  for (std::size_t k = 0; k < limits::kMaxPathPoses; ++k)
    p.poses.push_back({0.5 + 0.01 * static_cast<double>(k), 2.0});
  EXPECT_EQ(r.layer->setPlan(std::make_shared<PathData>(std::move(p))), "");
  r.expectStillGood();
}

TEST(AsymmetricInflationInput, MissingOrUnknownFrame)
{
  GoodPlan r;
  const std::string error = r.layer->setPlan(std::make_shared<PathData>(straightPath("")));
  EXPECT_NE(error.find("header.frame_id"), std::string::npos) << error;
  r.expectStillGood();
  // A frame tf does not know: taken (tf may know it later), symmetric while it cannot be placed.
  EXPECT_EQ(r.layer->setPlan(std::make_shared<PathData>(straightPath("nowhere"))), "");
  r.grid().resetMap(0, 0, 40, 40);  // no layer below redraws the grid here
  r.lethal(20, 24);
  r.run();
  EXPECT_EQ(r.at(20, 28), 12);
  EXPECT_GE(r.ctx->countKey("plan/header.frame_id"), 1);
}

TEST(AsymmetricInflationInput, PlanCrossingTheCostmapTooOftenIsSymmetricWithAnError)
{
  // A 100 m map of 0.5 m cells with a 0.5 m radius: 201 x 201 buckets; a diagonal crossing lists its
  // segment in about 1000 of them, so 10000 crossings need far more than 4 M entries.
  ParamValue p = params(0.5, 1.0, 10.0, 0.0);
  Rig r(p, 200, 200, 0.5, 0.1);
  std::vector<PathData::Point> zigzag;
  for (int k = 0; k < 10000; ++k)
    zigzag.push_back(k % 2 == 0 ? PathData::Point{0.0, 0.0} : PathData::Point{100.0, 100.0});
  EXPECT_EQ(r.layer->setPlan(std::make_shared<PathData>(plan(zigzag))), "");
  r.lethal(100, 102);
  r.run(-50.0, -50.0);
  EXPECT_FALSE(r.layer->asymmetryActive());
  EXPECT_GE(r.ctx->countKey("plan/poses"), 1);
  // One crossing is fine.
  zigzag.resize(2);
  EXPECT_EQ(r.layer->setPlan(std::make_shared<PathData>(plan(zigzag))), "");
  r.run(-50.0, -50.0);
  EXPECT_TRUE(r.layer->asymmetryActive());
}

// ---- Through a LayeredCostmap: bounds grow as far as the disfavoured side's costs reach ----

TEST(AsymmetricInflationLayered, PartialUpdatesReachAsFarAsTheSmallerFactor)
{
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(80, 50, 0.1, 0.0, 0.0);
  lc.setFootprint(square(0.3));
  auto ctx = std::make_shared<FakeContext>(params(2.0, 1.0, 7.0));
  auto layer = std::make_shared<AsymmetricInflationLayer>();
  layer->initialize(&lc, "asym", ctx);
  ctx->bind(*layer);
  lc.addPlugin(layer);
  ctx->publishPath(plan({{0.5, 2.0}, {7.5, 2.0}}));
  lc.updateMap(0.0, 0.0, 0.0);                  // the whole map once
  double a = 0.0, b = 0.0, c = -1.0, d = -1.0;  // then: a change at (4.05, 2.25) from below
  a = c = 4.05;
  b = d = 2.25;
  layer->updateBounds(0.0, 0.0, 0.0, &a, &b, &c, &d);
  // Factor 1 reaches the radius (20 cells); factor 7 alone would stop at 0.3 + ln(252) / 7 = 1.09 m.
  EXPECT_LE(a, 4.05 - 2.0 + 1e-9);
  EXPECT_GE(d, 2.25 + 2.0 - 1e-9);
}
