// Layers with a grid of their own in a rolling costmap whose master is moved by another rule than this
// package's: under move_base, costmap_2d moves its master by int() (truncation) from robot - (size -
// 0.5) * resolution / 2, and LayerBridge hands the moved master to the layers through viewMaster. A
// layer that moved its own grid by its own rule (floor, from robot - size * resolution / 2) ended one
// cell off the master after moves towards -x or -y, and merged every mark one cell off.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <set>
#include <utility>
#include <vector>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/costmap/costmap_layer.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/layers/obstacle_layer.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/layers/range_sensor_layer.hpp"
#include "costmap_layers/core/layers/voxel_layer.hpp"
#include "fake_context.hpp"
#include "sensor_test_helpers.hpp"

using namespace costmap_layers;
using namespace costmap_layers_test;

namespace
{
constexpr unsigned kCells = 40;
constexpr double kRes = 0.05;

/// costmap_2d's master, moved as costmap_2d::LayeredCostmap::updateMap and Costmap2D::updateOrigin move
/// it (written out from their source), and viewed by a core LayeredCostmap as LayerBridge views it.
struct Costmap2dHost
{
  Costmap2dHost() : lc("map", true, false), cells(kCells * kCells, FREE_SPACE)
  {
    lc.viewMaster(cells.data(), kCells, kCells, kRes, ox, oy);
  }
  void moveMaster(double robot_x, double robot_y)
  {
    const double half = (kCells - 1 + 0.5) * kRes / 2;  // costmap_2d's getSizeInMetersX() / 2
    const int cell_ox = static_cast<int>((robot_x - half - ox) / kRes);
    const int cell_oy = static_cast<int>((robot_y - half - oy) / kRes);
    ox += cell_ox * kRes;
    oy += cell_oy * kRes;
    std::fill(cells.begin(), cells.end(), FREE_SPACE);  // the test looks at this cycle's merge only
    lc.viewMaster(cells.data(), kCells, kCells, kRes, ox, oy);
  }
  /// One cycle of the bridged layer: the master moves, then the layer's bounds and costs (whole grid).
  void cycle(Layer& layer, double robot_x, double robot_y)
  {
    moveMaster(robot_x, robot_y);
    double x0 = std::numeric_limits<double>::max(), y0 = x0, x1 = std::numeric_limits<double>::lowest(), y1 = x1;
    layer.updateBounds(robot_x, robot_y, 0.0, &x0, &y0, &x1, &y1);
    layer.updateCosts(lc.getCostmap(), 0, 0, kCells, kCells);
  }
  /// The world cells (in whole cells from the world origin) of every non-free master cell.
  std::set<std::pair<long, long>> markedWorldCells() const
  {
    std::set<std::pair<long, long>> out;
    for (unsigned j = 0; j < kCells; ++j)
      for (unsigned i = 0; i < kCells; ++i)
        if (cells[j * kCells + i] != FREE_SPACE) out.emplace(std::lround(ox / kRes) + i, std::lround(oy / kRes) + j);
    return out;
  }
  bool inWindow(const std::pair<long, long>& c) const
  {
    const long i = c.first - std::lround(ox / kRes), j = c.second - std::lround(oy / kRes);
    return i >= 0 && j >= 0 && i < static_cast<long>(kCells) && j < static_cast<long>(kCells);
  }

  LayeredCostmap lc;
  std::vector<uint8_t> cells;
  double ox = 0.0, oy = 0.0;
};

/// Moves towards -x and -y by fractions of a cell, stands, then back and beyond: the marks must stay at
/// their world cells and the layer's grid on the master's origin, exactly.
void expectMarksStayInPlace(Costmap2dHost& host, CostmapLayer& layer)
{
  host.cycle(layer, 1.0, 1.0);
  const std::set<std::pair<long, long>> first = host.markedWorldCells();
  ASSERT_FALSE(first.empty());
  const double path[][2] = {{0.93, 0.97}, {0.86, 0.90}, {0.86, 0.90}, {0.83, 0.88},   {0.95, 1.01},
                            {1.30, 1.02}, {0.61, 0.66}, {0.58, 0.64}, {0.999, 0.951}, {1.0, 1.0}};
  for (const auto& p : path)
  {
    host.cycle(layer, p[0], p[1]);
    EXPECT_EQ(layer.costmap().getOriginX(), host.ox) << "robot " << p[0] << ", " << p[1];
    EXPECT_EQ(layer.costmap().getOriginY(), host.oy) << "robot " << p[0] << ", " << p[1];
    std::set<std::pair<long, long>> expected;
    for (const auto& c : first)
      if (host.inWindow(c)) expected.insert(c);
    EXPECT_EQ(host.markedWorldCells(), expected) << "robot " << p[0] << ", " << p[1];
  }
}

Observation twoPoints()
{
  Observation o;
  o.origin_x = 1.0;
  o.origin_y = 1.0;
  o.origin_z = 0.1;
  o.points = {{1.52f, 1.02f, 0.1f}, {0.52f, 1.02f, 0.1f}};
  o.obstacle_max_range = o.raytrace_max_range = 100.0;
  return o;
}
}  // namespace

TEST(RollingHost, ObstacleLayerFollowsAMasterMovedByCostmap2dsRule)
{
  Costmap2dHost host;
  ParamValue p = ParamValue::makeMap();
  p.set("observation_sources", ParamValue::makeString(""));
  auto ctx = std::make_shared<FakeContext>(p);
  auto layer = std::make_shared<ObstacleLayer>();
  layer->initialize(&host.lc, "obstacles", ctx);
  ctx->bind(*layer);
  host.lc.addPlugin(layer);
  layer->addStaticObservation(twoPoints(), true, false);
  expectMarksStayInPlace(host, *layer);
}

TEST(RollingHost, VoxelLayerFollowsAMasterMovedByCostmap2dsRule)
{
  Costmap2dHost host;
  ParamValue p = ParamValue::makeMap();
  p.set("observation_sources", ParamValue::makeString(""));
  auto ctx = std::make_shared<FakeContext>(p);
  auto layer = std::make_shared<VoxelLayer>();
  layer->initialize(&host.lc, "voxels", ctx);
  ctx->bind(*layer);
  host.lc.addPlugin(layer);
  // Marked once, then kept by the grid alone: the columns must move with the 2-D cells.
  layer->addStaticObservation(twoPoints(), true, false);
  host.cycle(*layer, 1.0, 1.0);
  layer->clearStaticObservations(true, true);
  expectMarksStayInPlace(host, *layer);
}

TEST(RollingHost, RangeSensorLayerFollowsAMasterMovedByCostmap2dsRule)
{
  Costmap2dHost host;
  ParamValue p = ParamValue::makeMap();
  p.set("topics", ParamValue::makeList({ParamValue::makeString("/sonar")}));
  auto ctx = std::make_shared<FakeContext>(p);
  auto layer = std::make_shared<RangeSensorLayer>();
  layer->initialize(&host.lc, "range", ctx);
  ctx->bind(*layer);
  host.lc.addPlugin(layer);
  RangeData r;
  r.frame_id = "base_link";
  r.radiation_type = RangeData::ULTRASOUND;
  r.field_of_view = 0.3f;
  r.min_range = 0.05f;
  r.max_range = 2.0f;
  r.range = 0.45f;
  ASSERT_EQ(ctx->publishRange("/sonar", r, poseAt(1.0, 1.0, 0.0)), 1);
  expectMarksStayInPlace(host, *layer);
}
