// The rules behind costmap_node's Nav2 services (~get_cost, ~clear_entirely, ~clear_except_region,
// ~clear_around_pose) and costmap_tool --cost. Expected values are worked out by hand in the comments.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "costmap_layers/core/costmap/cost_query.hpp"
#include "costmap_layers/core/costmap/costmap_clearing.hpp"
#include "costmap_layers/core/costmap/costmap_layer.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;

namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// A sensor-like layer that marks cells on request; clearable or not.
class MarkLayer : public CostmapLayer
{
public:
  explicit MarkLayer(bool clearable) : clearable_(clearable) {}
  void mark(unsigned x, unsigned y)
  {
    costmap_.setCost(x, y, LETHAL_OBSTACLE);
    double wx, wy;
    costmap_.mapToWorld(x, y, wx, wy);
    addExtraBounds(wx, wy, wx, wy);
  }
  void updateBounds(double, double, double, double* x0, double* y0, double* x1, double* y1) override
  {
    useExtraBounds(x0, y0, x1, y1);
  }
  void updateCosts(Costmap2D& master, int i0, int j0, int i1, int j1) override
  {
    updateWithMax(master, i0, j0, i1, j1);
  }
  void reset() override { costmap_.resetMaps(); }
  bool isClearable() override { return clearable_; }
  uint8_t own(unsigned x, unsigned y) const { return costmap_.getCost(x, y); }

private:
  bool clearable_;
};

const std::pair<unsigned, unsigned> kMarked[] = {{1, 1}, {10, 10}, {12, 10}, {13, 13}};

/// 20 x 20 cells of 1 m from (0, 0); "sensor" (clearable) marks (1,1), (10,10), (12,10), (13,13);
/// "fixed" (not clearable) marks (18,18). Unmarked own cells hold FREE_SPACE (0).
struct Rig
{
  LayeredCostmap lc{"map", false, false};
  std::shared_ptr<MarkLayer> sensor = std::make_shared<MarkLayer>(true);
  std::shared_ptr<MarkLayer> fixed = std::make_shared<MarkLayer>(false);
  Rig()
  {
    lc.resizeMap(20, 20, 1.0, 0.0, 0.0);
    for (auto& l : {sensor, fixed})
    {
      l->initialize(&lc, l == sensor ? "sensor" : "fixed", std::make_shared<FakeContext>());
      lc.addPlugin(l);
      l->matchSize();
    }
    for (const auto& [x, y] : kMarked)
      sensor->mark(x, y);
    fixed->mark(18, 18);
    lc.updateMap(10.5, 10.5, 0.0);
  }
  uint8_t master(unsigned x, unsigned y) const { return lc.getCostmap().getCost(x, y); }
};
}  // namespace

TEST(CostmapServices, ClearAroundPoseClearsOnlyTheSquare)
{
  Rig r;
  std::string error;
  // Side 4 around (10.5, 10.5): [8.5, 12.5] in x and y, so cells 8..12 (floor(8.5) .. floor(12.5)).
  EXPECT_EQ(clearSquare(r.lc, 10.5, 10.5, 4.0, SquareClear::ClearSquare, {}, error), 1) << error;
  EXPECT_EQ(r.sensor->own(10, 10), NO_INFORMATION);
  EXPECT_EQ(r.sensor->own(12, 10), NO_INFORMATION);
  EXPECT_EQ(r.sensor->own(8, 8), NO_INFORMATION);  // unmarked, inside: forgotten too
  EXPECT_EQ(r.sensor->own(12, 12), NO_INFORMATION);
  EXPECT_EQ(r.sensor->own(7, 8), FREE_SPACE);  // just outside
  EXPECT_EQ(r.sensor->own(13, 12), FREE_SPACE);
  EXPECT_EQ(r.sensor->own(13, 13), LETHAL_OBSTACLE);
  EXPECT_EQ(r.sensor->own(1, 1), LETHAL_OBSTACLE);
  r.lc.updateMap(10.5, 10.5, 0.0);
  EXPECT_EQ(r.master(10, 10), FREE_SPACE);
  EXPECT_EQ(r.master(12, 10), FREE_SPACE);
  EXPECT_EQ(r.master(13, 13), LETHAL_OBSTACLE);
  EXPECT_EQ(r.master(1, 1), LETHAL_OBSTACLE);
  EXPECT_EQ(r.master(18, 18), LETHAL_OBSTACLE);
}

TEST(CostmapServices, ClearExceptRegionOnNamedPluginsKeepsTheSquare)
{
  Rig r;
  std::string error;
  EXPECT_EQ(clearSquare(r.lc, 10.5, 10.5, 4.0, SquareClear::KeepSquare, {"sensor"}, error), 1) << error;
  EXPECT_EQ(r.sensor->own(1, 1), NO_INFORMATION);
  EXPECT_EQ(r.sensor->own(13, 13), NO_INFORMATION);
  EXPECT_EQ(r.sensor->own(7, 8), NO_INFORMATION);
  EXPECT_EQ(r.sensor->own(10, 10), LETHAL_OBSTACLE);
  EXPECT_EQ(r.sensor->own(12, 10), LETHAL_OBSTACLE);
  EXPECT_EQ(r.sensor->own(8, 8), FREE_SPACE);
  r.lc.updateMap(10.5, 10.5, 0.0);
  EXPECT_EQ(r.master(1, 1), FREE_SPACE);
  EXPECT_EQ(r.master(10, 10), LETHAL_OBSTACLE);
  EXPECT_EQ(r.master(18, 18), LETHAL_OBSTACLE);  // the fixed layer is never cleared
}

// Nav2's clear_costmap_service_test: an empty list clears the clearable plugins, a clearable one is
// accepted, a non-clearable or unknown one (alone or with a good one) fails and clears nothing.
TEST(CostmapServices, PluginListsAreCheckedAsNav2ChecksThem)
{
  Rig r;
  std::string error;
  EXPECT_EQ(clearPluginsProblem(r.lc, {}), "");
  EXPECT_EQ(clearPluginsProblem(r.lc, {"sensor"}), "");
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"fixed"}, {"sensor", "fixed"}, {"lidar"}, {"sensor", "lidar"}})
  {
    for (auto mode : {SquareClear::KeepSquare, SquareClear::ClearSquare})
    {
      EXPECT_EQ(clearSquare(r.lc, 10.5, 10.5, 4.0, mode, bad, error), -1);
      EXPECT_NE(error.find("plugins:"), std::string::npos) << error;
    }
    EXPECT_EQ(clearEntirely(r.lc, bad, error), -1);
    EXPECT_EQ(r.sensor->own(1, 1), LETHAL_OBSTACLE);  // untouched
    EXPECT_EQ(r.sensor->own(10, 10), LETHAL_OBSTACLE);
  }
  clearSquare(r.lc, 0, 0, 1, SquareClear::KeepSquare, {"sensor", "fixed", "lidar"}, error);
  EXPECT_EQ(error,
            "plugins: 2 of the 3 name(s) are not clearable plugins of this costmap: 'fixed' (not clearable), "
            "'lidar' (not found)");
}

TEST(CostmapServices, BadCentresAndDistancesAreRefusedUntouched)
{
  Rig r;
  std::string error;
  for (auto mode : {SquareClear::KeepSquare, SquareClear::ClearSquare})
  {
    EXPECT_EQ(clearSquare(r.lc, kNaN, 10.5, 4.0, mode, {}, error), -1);
    EXPECT_NE(error.find("not finite"), std::string::npos) << error;
    EXPECT_EQ(clearSquare(r.lc, 10.5, -kInf, 4.0, mode, {}, error), -1);
    EXPECT_EQ(clearSquare(r.lc, 10.5, 10.5, kNaN, mode, {}, error), -1);
    EXPECT_NE(error.find("reset_distance nan"), std::string::npos) << error;
    EXPECT_EQ(clearSquare(r.lc, 10.5, 10.5, -0.01, mode, {}, error), -1);
    EXPECT_NE(error.find("reset_distance -0.01"), std::string::npos) << error;
    EXPECT_EQ(clearSquare(r.lc, 10.5, 10.5, -kInf, mode, {}, error), -1);
  }
  for (const auto& [x, y] : kMarked)
    EXPECT_EQ(r.sensor->own(x, y), LETHAL_OBSTACLE);
}

TEST(CostmapServices, HugeZeroAndFarSquares)
{
  {
    Rig r;  // an infinite square around a pose clears the whole grid of the clearable layer
    std::string error;
    EXPECT_EQ(clearSquare(r.lc, 10.5, 10.5, kInf, SquareClear::ClearSquare, {}, error), 1);
    EXPECT_EQ(r.sensor->own(0, 0), NO_INFORMATION);
    EXPECT_EQ(r.sensor->own(1, 1), NO_INFORMATION);
    EXPECT_EQ(r.sensor->own(19, 19), NO_INFORMATION);
  }
  {
    Rig r;  // side 0 at (12.5, 10.5): the one cell (12, 10)
    std::string error;
    EXPECT_EQ(clearSquare(r.lc, 12.5, 10.5, 0.0, SquareClear::ClearSquare, {}, error), 1);
    EXPECT_EQ(r.sensor->own(12, 10), NO_INFORMATION);
    EXPECT_EQ(r.sensor->own(11, 10), FREE_SPACE);
    EXPECT_EQ(r.sensor->own(10, 10), LETHAL_OBSTACLE);
  }
  {
    Rig r;  // a pose a thousand km away: its square misses the grid, nothing is cleared
    std::string error;
    EXPECT_EQ(clearSquare(r.lc, 1e6, -1e6, 4.0, SquareClear::ClearSquare, {}, error), 1);
    EXPECT_EQ(r.sensor->own(1, 1), LETHAL_OBSTACLE);
    EXPECT_EQ(r.sensor->own(0, 19), FREE_SPACE);
  }
}

TEST(CostmapServices, ClearEntirelyResetsEveryLayerOrTheNamedOnes)
{
  {
    Rig r;
    std::string error;
    EXPECT_EQ(clearEntirely(r.lc, {}, error), 2) << error;  // the non-clearable layer too, as Nav2
    EXPECT_EQ(r.sensor->own(10, 10), FREE_SPACE);
    EXPECT_EQ(r.fixed->own(18, 18), FREE_SPACE);
    r.lc.updateMap(10.5, 10.5, 0.0);  // nothing newly marked: only the full redraw clears the master
    EXPECT_EQ(r.master(10, 10), FREE_SPACE);
    EXPECT_EQ(r.master(18, 18), FREE_SPACE);
  }
  {
    Rig r;
    std::string error;
    EXPECT_EQ(clearEntirely(r.lc, {"sensor"}, error), 1) << error;
    EXPECT_EQ(r.sensor->own(1, 1), FREE_SPACE);  // the grid's default value (Nav2's resetMap)
    EXPECT_EQ(r.fixed->own(18, 18), LETHAL_OBSTACLE);
    r.lc.updateMap(10.5, 10.5, 0.0);
    EXPECT_EQ(r.master(1, 1), FREE_SPACE);
    EXPECT_EQ(r.master(13, 13), FREE_SPACE);
    EXPECT_EQ(r.master(18, 18), LETHAL_OBSTACLE);
  }
}

namespace
{
/// 10 x 10 cells of 0.5 m from (-1, -2).
Costmap2D smallGrid()
{
  Costmap2D g(10, 10, 0.5, -1.0, -2.0, FREE_SPACE);
  g.setCost(2, 2, 100);
  g.setCost(9, 9, 7);
  return g;
}

/// 10 x 10 cells of 1 m from (0, 0).
Costmap2D unitGrid()
{
  return Costmap2D(10, 10, 1.0, 0.0, 0.0, FREE_SPACE);
}

Footprint square(double h)
{
  return {Eigen::Vector2d(h, h), Eigen::Vector2d(-h, h), Eigen::Vector2d(-h, -h), Eigen::Vector2d(h, -h)};
}
}  // namespace

TEST(CostQuery, PointCostIsTheCellsCostAndOffTheGridIsLethalAndNotOk)
{
  const Costmap2D g = smallGrid();
  // (0.2, -0.6): (0.2 + 1) / 0.5 = 2.4 -> 2, (-0.6 + 2) / 0.5 = 2.8 -> 2.
  auto a = pointCost(g, 0.2, -0.6);
  EXPECT_EQ(a.cost, 100.0);
  EXPECT_TRUE(a.ok);
  a = pointCost(g, 3.99, 2.99);  // cell (9, 9), the last one
  EXPECT_EQ(a.cost, 7.0);
  EXPECT_TRUE(a.ok);
  const std::pair<double, double> off[] = {{4.0, 0.0}, {0.0, 3.0}, {-1.01, 0.0}, {0.0, -2.01}, {1e300, 0.0}};
  for (const auto& [x, y] : off)
  {
    a = pointCost(g, x, y);
    EXPECT_EQ(a.cost, 254.0) << x << ", " << y;
    EXPECT_FALSE(a.ok);
  }
  const std::pair<double, double> bad[] = {{kNaN, 0.0}, {0.0, kInf}, {-kInf, kNaN}};
  for (const auto& [x, y] : bad)
  {
    a = pointCost(g, x, y);
    EXPECT_EQ(a.cost, 255.0);
    EXPECT_FALSE(a.ok);
  }
}

TEST(CostQuery, FootprintCostIsTheMaximumOnTheOutline)
{
  Costmap2D g = unitGrid();
  // Half-side 1.5 at (5, 5): vertices at 3.5 and 6.5 -> cells 3 and 6; the outline is the ring of
  // cells 3..6 with x or y in {3, 6}; (4..5, 4..5) is inside and not looked at (as Nav2).
  g.setCost(5, 5, 200);
  auto a = footprintCostAtPose(g, 5.0, 5.0, 0.0, square(1.5));
  EXPECT_EQ(a.cost, 0.0);
  EXPECT_TRUE(a.ok);
  g.setCost(3, 5, 50);
  EXPECT_EQ(footprintCostAtPose(g, 5.0, 5.0, 0.0, square(1.5)).cost, 50.0);
  g.setCost(6, 4, 128);
  EXPECT_EQ(footprintCostAtPose(g, 5.0, 5.0, 0.0, square(1.5)).cost, 128.0);
  g.setCost(4, 6, LETHAL_OBSTACLE);
  EXPECT_EQ(footprintCostAtPose(g, 5.0, 5.0, 0.0, square(1.5)).cost, 254.0);
  // Off the outline: (2, 5) and (7, 5) do not count.
  Costmap2D h = unitGrid();
  h.setCost(2, 5, 99);
  h.setCost(7, 5, 99);
  EXPECT_EQ(footprintCostAtPose(h, 5.0, 5.0, 0.0, square(1.5)).cost, 0.0);
}

TEST(CostQuery, FootprintIsTurnedByYaw)
{
  // A bar 4 m x 0.8 m at (5.5, 5.5): at yaw 0 it spans x 3.5..7.5 in row 5; at yaw pi/2 the vertex
  // (2, 0.4) goes to (-0.4, 2) -> (5.1, 7.5), so it spans y 3.5..7.5 in column 5.
  const Footprint bar = {Eigen::Vector2d(2, 0.4), Eigen::Vector2d(-2, 0.4), Eigen::Vector2d(-2, -0.4),
                         Eigen::Vector2d(2, -0.4)};
  Costmap2D g = unitGrid();
  g.setCost(5, 7, 77);
  EXPECT_EQ(footprintCostAtPose(g, 5.5, 5.5, 0.0, bar).cost, 0.0);
  EXPECT_EQ(footprintCostAtPose(g, 5.5, 5.5, M_PI / 2, bar).cost, 77.0);
  g.setCost(7, 5, 33);
  EXPECT_EQ(footprintCostAtPose(g, 5.5, 5.5, 0.0, bar).cost, 33.0);
}

TEST(CostQuery, FootprintOffTheGridOrNotFinite)
{
  const Costmap2D g = unitGrid();
  // At (0.2, 5) the vertex x 0.2 - 1.5 = -1.3 is off the grid: lethal, and Nav2's success stays true.
  auto a = footprintCostAtPose(g, 0.2, 5.0, 0.0, square(1.5));
  EXPECT_EQ(a.cost, 254.0);
  EXPECT_TRUE(a.ok);
  a = footprintCostAtPose(g, 8.6, 5.0, 0.0, square(1.5));  // 8.6 + 1.5 = 10.1 >= 10 m
  EXPECT_EQ(a.cost, 254.0);
  const std::tuple<double, double, double> bad[] = {
      {kNaN, 5.0, 0.0}, {5.0, kInf, 0.0}, {5.0, 5.0, kNaN}, {5.0, 5.0, -kInf}};
  for (const auto& [x, y, yaw] : bad)
  {
    a = footprintCostAtPose(g, x, y, yaw, square(1.5));
    EXPECT_EQ(a.cost, 255.0);
    EXPECT_FALSE(a.ok);
  }
  // No footprint: the pose's cell, as pointCost.
  Costmap2D h = unitGrid();
  h.setCost(5, 5, 42);
  a = footprintCostAtPose(h, 5.5, 5.5, 1.0, {});
  EXPECT_EQ(a.cost, 42.0);
  EXPECT_TRUE(a.ok);
  // One vertex (1, 0) turned by 1 rad: (cos 1, sin 1) = (0.540, 0.841) + (5.5, 5.5) -> cell (6, 6).
  h.setCost(6, 6, 61);
  a = footprintCostAtPose(h, 5.5, 5.5, 1.0, {Eigen::Vector2d(1.0, 0.0)});
  EXPECT_EQ(a.cost, 61.0);
  EXPECT_TRUE(a.ok);
}
