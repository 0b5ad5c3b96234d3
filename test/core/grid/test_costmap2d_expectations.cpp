// costmap_2d's own inflation, obstacle, footprint and coordinates test scenarios (navigation noetic, costmap_2d/test/
// inflation_tests.cpp, obstacle_tests.cpp, footprint_tests.cpp with footprint_tests.launch, BSD), rebuilt on this
// package's layers: the same maps, footprints, parameters (its inflation_tests.launch sets cost_scaling_factor 1) and
// observations, and the numbers costmap_2d's tests expect. The expected values are costmap_2d's, not this package's;
// the cost formula used for the "at least" checks is written out here from costmap_2d's InflationLayer::computeCost.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "costmap_layers/core/config/config_compat.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/costmap/costmap_config.hpp"
#include "costmap_layers/core/layers/inflation_layer.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/layers/obstacle_layer.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/layers/static_layer.hpp"
#include "fake_context.hpp"
#include "sensor_test_helpers.hpp"
#include "ten_by_ten.hpp"

using namespace costmap_layers;
using namespace costmap_layers_test;

namespace
{
constexpr double kMaxZ = 1.0;  // costmap_2d's testing_helper.h MAX_Z

/// costmap_2d's setRadii: a rectangle of half-length `length` along y and half-width `width` along x.
Footprint rectangle(double length, double width)
{
  return {{width, length}, {width, -length}, {-width, -length}, {-width, length}};
}

/// costmap_2d's InflationLayer::computeCost for a distance in cells, written out from its source.
unsigned char costmap2dCost(double distance_cells, double resolution, double inscribed, double factor)
{
  if (distance_cells == 0) return LETHAL_OBSTACLE;
  if (distance_cells * resolution <= inscribed) return INSCRIBED_INFLATED_OBSTACLE;
  const double f = std::exp(-1.0 * factor * (distance_cells * resolution - inscribed));
  return static_cast<unsigned char>((INSCRIBED_INFLATED_OBSTACLE - 1) * f);
}

unsigned countValues(const Costmap2D& c, unsigned char value, bool equal = true)
{
  unsigned n = 0;
  for (std::size_t k = 0; k < c.cellCount(); ++k)
    n += (c.data()[k] == value) == equal;
  return n;
}

/// costmap_2d's test set-up: an optional static layer fed TenByTen, an obstacle layer whose
/// observations are added with addStaticObservation (100 m ranges, sensor at (ox, oy, oz)), and an
/// inflation layer with cost_scaling_factor 1.
struct Stack
{
  Stack(bool with_static, double inflation_radius, bool resize_10x10, unsigned size = 10) : lc("map", false, false)
  {
    if (resize_10x10) lc.resizeMap(size, size, 1.0, 0.0, 0.0);
    if (with_static)
    {
      static_ctx = std::make_shared<FakeContext>(ParamValue::makeMap());
      static_layer = std::make_shared<StaticLayer>();
      static_layer->initialize(&lc, "static", static_ctx);
      static_ctx->bind(*static_layer);
      lc.addPlugin(static_layer);
      static_ctx->publishGrid(GridKind::Map, tenByTen());
    }
    ParamValue obstacle_params = ParamValue::makeMap();
    obstacle_params.set("observation_sources", ParamValue::makeString(""));
    obstacle_ctx = std::make_shared<FakeContext>(obstacle_params);
    obstacles = std::make_shared<ObstacleLayer>();
    obstacles->initialize(&lc, "obstacles", obstacle_ctx);
    obstacle_ctx->bind(*obstacles);
    lc.addPlugin(obstacles);
    ParamValue inflation_params = ParamValue::makeMap();
    inflation_params.set("inflation_radius", ParamValue::makeDouble(inflation_radius));
    inflation_params.set("cost_scaling_factor", ParamValue::makeDouble(1.0));
    inflation_ctx = std::make_shared<FakeContext>(inflation_params);
    inflation = std::make_shared<InflationLayer>();
    inflation->initialize(&lc, "inflation", inflation_ctx);
    inflation_ctx->bind(*inflation);
    lc.addPlugin(inflation);
  }
  /// costmap_2d's addObservation(olayer, x, y, z, ox, oy, oz).
  void addObservation(double x, double y, double z = 0.0, double ox = 0.0, double oy = 0.0, double oz = kMaxZ)
  {
    Observation o;
    o.origin_x = ox;
    o.origin_y = oy;
    o.origin_z = oz;
    o.points = {{static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)}};
    o.obstacle_max_range = o.raytrace_max_range = 100.0;
    obstacles->addStaticObservation(o, true, true);
  }
  void update() { lc.updateMap(0, 0, 0); }
  const Costmap2D& costmap() const { return lc.getCostmap(); }
  unsigned char at(unsigned x, unsigned y) const { return costmap().getCost(x, y); }

  LayeredCostmap lc;
  std::shared_ptr<FakeContext> static_ctx, obstacle_ctx, inflation_ctx;
  std::shared_ptr<StaticLayer> static_layer;
  std::shared_ptr<ObstacleLayer> obstacles;
  std::shared_ptr<InflationLayer> inflation;
};
}  // namespace

TEST(Costmap2dInflationTests, AdjacentToObstacleCanStillMove)
{
  Stack s(false, 4.1, true);
  s.lc.setFootprint(rectangle(2.1, 2.3));  // inscribed 2.1, circumscribed 3.1
  s.addObservation(0, 0, kMaxZ);
  s.update();
  EXPECT_EQ(s.at(0, 0), LETHAL_OBSTACLE);
  EXPECT_EQ(s.at(1, 0), INSCRIBED_INFLATED_OBSTACLE);
  EXPECT_EQ(s.at(2, 0), INSCRIBED_INFLATED_OBSTACLE);
  EXPECT_GT(INSCRIBED_INFLATED_OBSTACLE, s.at(3, 0));
  EXPECT_GT(INSCRIBED_INFLATED_OBSTACLE, s.at(2, 1));
  EXPECT_EQ(s.at(1, 1), INSCRIBED_INFLATED_OBSTACLE);
}

TEST(Costmap2dInflationTests, InflationShouldNotCreateUnknowns)
{
  Stack s(false, 4.1, true);
  s.lc.setFootprint(rectangle(2.1, 2.3));
  s.addObservation(0, 0, kMaxZ);
  s.update();
  EXPECT_EQ(countValues(s.costmap(), NO_INFORMATION), 0u);
}

TEST(Costmap2dInflationTests, CostFunctionCorrectness)
{
  Stack s(false, 10.5, true, 100);
  s.lc.setFootprint(rectangle(5.0, 6.25));  // inscribed 5.0, circumscribed 8.0
  s.addObservation(50, 50, kMaxZ);
  s.update();
  for (unsigned i = 0; i <= 5; ++i)
  {
    EXPECT_GE(s.at(50 + i, 50), INSCRIBED_INFLATED_OBSTACLE) << i;
    EXPECT_GE(s.at(50 - i, 50), INSCRIBED_INFLATED_OBSTACLE) << i;
    EXPECT_GE(s.at(50, 50 + i), INSCRIBED_INFLATED_OBSTACLE) << i;
    EXPECT_GE(s.at(50, 50 - i), INSCRIBED_INFLATED_OBSTACLE) << i;
  }
  // The attenuation: 252 * exp(-(i - 5)) truncated, by hand: 92, 34, 12, 4, 1, 0.
  const unsigned char by_hand[] = {92, 34, 12, 4, 1, 0};
  for (unsigned i = 6; i <= 11; ++i)
  {
    EXPECT_EQ(costmap2dCost(i, 1.0, 5.0, 1.0), by_hand[i - 6]) << i;
    EXPECT_EQ(s.at(50 + i, 50), by_hand[i - 6]) << i;
  }
}

TEST(Costmap2dInflationTests, InflationOrderCorrectness)
{
  // Two diagonal neighbours: every cell within costmap_2d's reach of either (ceil(4.1) = 5 cells) costs
  // at least what that obstacle alone gives it.
  Stack s(false, 4.1, true);
  s.lc.setFootprint(rectangle(2.1, 2.3));
  s.addObservation(4, 4, kMaxZ);
  s.addObservation(5, 5, kMaxZ);
  s.update();
  for (const auto& [ox, oy] : {std::pair<int, int>{4, 4}, {5, 5}})
    for (int y = 0; y < 10; ++y)
      for (int x = 0; x < 10; ++x)
      {
        const double d = std::hypot(x - ox, y - oy);
        if (d > 5.0) continue;
        EXPECT_GE(s.at(x, y), costmap2dCost(d, 1.0, 2.1, 1.0)) << x << "," << y << " from " << ox << "," << oy;
      }
}

TEST(Costmap2dInflationTests, InflationOfStaticAndDynamicObstacles)
{
  Stack s(true, 1.0, false);
  s.lc.setFootprint(rectangle(1, 1));
  s.update();
  ASSERT_EQ(s.costmap().getSizeInCellsX(), 10u);
  EXPECT_EQ(countValues(s.costmap(), LETHAL_OBSTACLE), 20u);
  EXPECT_EQ(countValues(s.costmap(), INSCRIBED_INFLATED_OBSTACLE), 28u);

  s.addObservation(0, 0, 0.4);
  s.update();
  EXPECT_EQ(countValues(s.costmap(), LETHAL_OBSTACLE) + countValues(s.costmap(), INSCRIBED_INFLATED_OBSTACLE), 51u);

  s.addObservation(2, 0);
  s.update();
  EXPECT_EQ(countValues(s.costmap(), LETHAL_OBSTACLE) + countValues(s.costmap(), INSCRIBED_INFLATED_OBSTACLE), 54u);

  s.addObservation(1, 9);
  s.update();
  EXPECT_EQ(s.at(1, 9), LETHAL_OBSTACLE);
  EXPECT_EQ(s.at(0, 9), INSCRIBED_INFLATED_OBSTACLE);
  EXPECT_EQ(s.at(2, 9), INSCRIBED_INFLATED_OBSTACLE);

  s.addObservation(0, 9);
  s.update();
  EXPECT_EQ(s.at(0, 9), LETHAL_OBSTACLE);
}

TEST(Costmap2dInflationTests, InflatedCellsAreNotMadeObstacles)
{
  Stack s(true, 1.0, false);
  s.lc.setFootprint(rectangle(1, 1));
  s.addObservation(1, 1, kMaxZ);
  s.addObservation(2, 1, kMaxZ);
  s.addObservation(2, 2, kMaxZ);
  s.update();
  EXPECT_EQ(s.at(2, 3), INSCRIBED_INFLATED_OBSTACLE);
  EXPECT_EQ(s.at(3, 3), INSCRIBED_INFLATED_OBSTACLE);
}

TEST(Costmap2dInflationTests, InflationStartingFromAnEmptyMap)
{
  Stack s(false, 3.0, true);
  s.lc.setFootprint(rectangle(1, 1.75));  // inscribed 1
  EXPECT_EQ(countValues(s.costmap(), LETHAL_OBSTACLE), 0u);
  EXPECT_EQ(countValues(s.costmap(), INSCRIBED_INFLATED_OBSTACLE), 0u);
  s.addObservation(5, 5, kMaxZ);
  for (int round = 0; round < 2; ++round)  // the second update must change nothing
  {
    s.update();
    EXPECT_EQ(countValues(s.costmap(), FREE_SPACE, false), 29u) << round;
    EXPECT_EQ(countValues(s.costmap(), LETHAL_OBSTACLE), 1u) << round;
    EXPECT_EQ(countValues(s.costmap(), INSCRIBED_INFLATED_OBSTACLE), 4u) << round;
  }
}

TEST(Costmap2dObstacleTests, DynamicObstaclesInsertOnce)
{
  Stack s(true, 0.0, false);
  s.addObservation(0.0, 0.0);
  s.addObservation(0.0, 0.0);
  s.addObservation(0.0, 0.0);
  s.update();
  EXPECT_EQ(countValues(s.costmap(), LETHAL_OBSTACLE), 21u);
  s.update();
  EXPECT_EQ(countValues(s.costmap(), LETHAL_OBSTACLE), 21u);
}

TEST(Costmap2dObstacleTests, AnObservationInsideAnObstacleAddsNothing)
{
  Stack s(true, 0.0, false);
  s.addObservation(9.5, 0.0);
  s.update();
  EXPECT_EQ(countValues(s.costmap(), LETHAL_OBSTACLE), 20u);
}

TEST(Costmap2dObstacleTests, ZThreshold)
{
  // costmap_2d's testZThreshold runs with track_unknown on; one point below max_obstacle_height (2.0
  // by default), one above it.
  LayeredCostmap lc("map", false, true);
  lc.resizeMap(10, 10, 1.0, 0.0, 0.0);
  ParamValue p = ParamValue::makeMap();
  p.set("observation_sources", ParamValue::makeString(""));
  auto ctx = std::make_shared<FakeContext>(p);
  auto layer = std::make_shared<ObstacleLayer>();
  layer->initialize(&lc, "obstacles", ctx);
  ctx->bind(*layer);
  lc.addPlugin(layer);
  for (const auto& [x, y, z] : {std::tuple<float, float, float>{0.0f, 5.0f, 0.4f}, {1.0f, 5.0f, 2.2f}})
  {
    Observation o;
    o.origin_z = kMaxZ;
    o.points = {{x, y, z}};
    o.obstacle_max_range = o.raytrace_max_range = 100.0;
    layer->addStaticObservation(o, true, true);
  }
  lc.updateMap(0, 0, 0);
  EXPECT_EQ(countValues(lc.getCostmap(), LETHAL_OBSTACLE), 1u);
}

namespace
{
ParamValue footprintList(const std::vector<std::vector<double>>& points)
{
  ParamValue list = ParamValue::makeList();
  for (const auto& p : points)
  {
    ParamValue point = ParamValue::makeList();
    for (double v : p)
      point.push(ParamValue::makeDouble(v));
    list.push(point);
  }
  return list;
}

/// The padded footprint costmap_2d's Costmap2DROS makes for a costmap namespace ns, whose parent
/// namespace holds parent (footprint_tests.launch: "padded/string" finds "padded/footprint").
Footprint footprintOf(const ParamValue& ns, const ParamValue& parent = ParamValue::makeMap())
{
  const CompatResult r = applyCostmap2dRules(ns, {ParentNamespace{"/parent", parent}});
  return parseCostmapConfig(r.params).footprint.padded();
}

ParamValue namespaceOf(std::initializer_list<std::pair<const char*, ParamValue>> keys)
{
  ParamValue ns = ParamValue::makeMap();
  for (const auto& [k, v] : keys)
    ns.set(k, v);
  return ns;
}
}  // namespace

// footprint_tests: unpadded_footprint_from_string_param and padded_footprint_from_string_param (the
// footprint found in the parent namespace, the padding in the costmap's).
TEST(Costmap2dFootprintTests, FootprintFromStringParam)
{
  const ParamValue parent = namespaceOf({{"footprint", ParamValue::makeString("[[1, 1], [-1, 1], [-1, -1]]")}});
  for (const auto& [padding, reach] : {std::pair<double, double>{0.0, 1.0}, {0.5, 1.5}})
  {
    const Footprint f = footprintOf(namespaceOf({{"footprint_padding", ParamValue::makeDouble(padding)}}), parent);
    ASSERT_EQ(f.size(), 3u) << padding;
    EXPECT_EQ(f[0].x(), reach);
    EXPECT_EQ(f[0].y(), reach);
    EXPECT_EQ(f[1].x(), -reach);
    EXPECT_EQ(f[1].y(), reach);
    EXPECT_EQ(f[2].x(), -reach);
    EXPECT_EQ(f[2].y(), -reach);
  }
}

// radius_param: robot_radius 10 from the parent, padding 0: 16 points, (10, 0) first, (0, 10) fifth.
TEST(Costmap2dFootprintTests, RadiusParam)
{
  const Footprint f = footprintOf(namespaceOf({{"footprint_padding", ParamValue::makeDouble(0.0)}}),
                                  namespaceOf({{"robot_radius", ParamValue::makeDouble(10.0)}}));
  ASSERT_EQ(f.size(), 16u);
  EXPECT_EQ(f[0].x(), 10.0);
  EXPECT_EQ(f[0].y(), 0.0);
  EXPECT_NEAR(f[4].x(), 0.0, 1e-4);
  EXPECT_NEAR(f[4].y(), 10.0, 1e-4);
}

// footprint_from_xmlrpc_param and footprint_from_same_level_param (a list and a string in the
// costmap's own namespace).
TEST(Costmap2dFootprintTests, FootprintFromXmlRpcAndSameLevelParam)
{
  const Footprint square =
      footprintOf(namespaceOf({{"footprint_padding", ParamValue::makeDouble(0.0)},
                               {"footprint", footprintList({{0.1, 0.1}, {-0.1, 0.1}, {-0.1, -0.1}, {0.1, -0.1}})}}));
  ASSERT_EQ(square.size(), 4u);
  const double expected[4][2] = {{0.1, 0.1}, {-0.1, 0.1}, {-0.1, -0.1}, {0.1, -0.1}};
  for (int k = 0; k < 4; ++k)
  {
    EXPECT_EQ(static_cast<float>(square[k].x()), static_cast<float>(expected[k][0])) << k;
    EXPECT_EQ(static_cast<float>(square[k].y()), static_cast<float>(expected[k][1])) << k;
  }
  const Footprint same = footprintOf(namespaceOf({{"footprint_padding", ParamValue::makeDouble(0.0)},
                                                  {"footprint", ParamValue::makeString("[[1, 2], [3, 4], [5, 6]]")}}));
  ASSERT_EQ(same.size(), 3u);
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_EQ(same[k].x(), 1.0 + 2 * k) << k;
    EXPECT_EQ(same[k].y(), 2.0 + 2 * k) << k;
  }
}

// footprint_from_xmlrpc_param_failure: a point of three values stops Costmap2DROS (it throws); here
// the configuration is refused.
TEST(Costmap2dFootprintTests, FootprintFromXmlRpcParamFailure)
{
  const ParamValue ns =
      namespaceOf({{"footprint_padding", ParamValue::makeDouble(0.0)},
                   {"footprint", footprintList({{0.1, 0.1}, {-0.1, 0.1, 77.0}, {-0.1, -0.1}, {0.1, -0.1}})}});
  std::string message;
  try
  {
    footprintOf(ns);
  }
  catch (const std::exception& e)
  {
    message = e.what();
  }
  EXPECT_NE(message.find("footprint"), std::string::npos) << message;
}

// footprint_empty: no footprint, no robot_radius: costmap_2d's robot_radius 0.46 and footprint_padding
// 0.01 give 16 points, the first at x = 0.47.
TEST(Costmap2dFootprintTests, FootprintEmpty)
{
  const Footprint f = footprintOf(ParamValue::makeMap());
  ASSERT_EQ(f.size(), 16u);
  EXPECT_NEAR(f[0].x(), 0.47, 1e-4);
}

// costmap_2d's coordinates_test.cpp (from locusrobotics' nav_grid): cell centres, the cell under a point
// at and near cell borders, and the two unbounded forms, with its numbers.
namespace
{
/// The part both of its cases check: (wx, wy), the centre of cell (1, 2), maps back to that cell by both
/// forms; at x = 2.5, off the grid, worldToMap refuses, the clamped form gives (1, 2) and the unbounded
/// one (nobounds_x, 2).
void expectCell12AndOffGrid(const Costmap2D& costmap, double wx, double wy, int nobounds_x)
{
  unsigned int umx, umy;
  int mx, my;
  EXPECT_TRUE(costmap.worldToMap(wx, wy, umx, umy));
  EXPECT_EQ(umx, 1u);
  EXPECT_EQ(umy, 2u);
  costmap.worldToMapNoBounds(wx, wy, mx, my);
  EXPECT_EQ(mx, 1);
  EXPECT_EQ(my, 2);
  EXPECT_FALSE(costmap.worldToMap(2.5, wy, umx, umy));
  costmap.worldToMapEnforceBounds(2.5, wy, mx, my);
  EXPECT_EQ(mx, 1);
  EXPECT_EQ(my, 2);
  costmap.worldToMapNoBounds(2.5, wy, mx, my);
  EXPECT_EQ(mx, nobounds_x);
  EXPECT_EQ(my, 2);
}
}  // namespace

TEST(Costmap2dCoordinatesTests, EasyCoordinates)
{
  Costmap2D costmap(2, 3, 1.0, 0, 0);
  double wx, wy;
  costmap.mapToWorld(0u, 0u, wx, wy);
  EXPECT_DOUBLE_EQ(wx, 0.5);
  EXPECT_DOUBLE_EQ(wy, 0.5);
  costmap.mapToWorld(1u, 2u, wx, wy);
  EXPECT_DOUBLE_EQ(wx, 1.5);
  EXPECT_DOUBLE_EQ(wy, 2.5);
  expectCell12AndOffGrid(costmap, wx, wy, 2);

  // Borders: a cell spans [i, i + 1).
  unsigned int umx, umy;
  for (const auto& [x, cell] : std::vector<std::pair<double, unsigned int>>{
           {0.0, 0u}, {0.25, 0u}, {0.75, 0u}, {0.9999, 0u}, {1.0, 1u}, {1.25, 1u}, {1.75, 1u}, {1.9999, 1u}})
  {
    EXPECT_TRUE(costmap.worldToMap(x, wy, umx, umy)) << x;
    EXPECT_EQ(umx, cell) << x;
  }
  EXPECT_FALSE(costmap.worldToMap(2.0, wy, umx, umy));
  int mx, my;
  costmap.worldToMapEnforceBounds(2.0, wy, mx, my);
  EXPECT_EQ(mx, 1);
}

TEST(Costmap2dCoordinatesTests, HardCoordinates)
{
  Costmap2D costmap(2, 3, 0.1, -0.2, 0.2);
  double wx, wy;
  costmap.mapToWorld(0, 0, wx, wy);
  EXPECT_DOUBLE_EQ(wx, -0.15);
  EXPECT_DOUBLE_EQ(wy, 0.25);
  costmap.mapToWorld(1, 2, wx, wy);
  EXPECT_DOUBLE_EQ(wx, -0.05);
  EXPECT_DOUBLE_EQ(wy, 0.45);
  expectCell12AndOffGrid(costmap, wx, wy, 27);  // (2.5 + 0.2) / 0.1
}
