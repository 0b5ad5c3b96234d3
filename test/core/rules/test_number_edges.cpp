// Numbers at the edge of their ranges, for every numeric parameter family and message field the core
// reads: for each, the worst a sender can put there (NaN, inf, negative, 0, 1e-300, 1e300) is refused
// with an error naming the field, and the ends of the range are accepted. The ranges are written here
// as numbers, independently of the library's constants:
//   resolution [1e-4, 1e3] m/cell, |origin x/y| <= 1e7 m, |yaw| <= 1e3 rad, at most 400 million
//   cells, lengths (radii, ranges, padding, footprint vertices) <= 1e4 m, durations <= 3600 s,
//   update_frequency in [1e-3, 1e3] Hz, publish_frequency 0 (off) or in [1e-3, 1e3] Hz.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "costmap_layers/core/costmap/costmap_config.hpp"
#include "costmap_layers/core/filters/costmap_filter.hpp"
#include "costmap_layers/core/grid/footprint.hpp"
#include "costmap_layers/core/layers/inflation_layer.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/layers/obstacle_layer.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/layers/range_sensor_layer.hpp"
#include "costmap_layers/core/layers/static_layer.hpp"
#include "costmap_layers/core/layers/voxel_layer.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;

namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// The message of the exception fn throws, or "" when it throws none.
std::string errorOf(const std::function<void()>& fn)
{
  try
  {
    fn();
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& needle)
{
  return text.find(needle) != std::string::npos;
}

OccupancyGridData grid(double resolution, double ox = 0.0, double oy = 0.0, double yaw = 0.0)
{
  OccupancyGridData g;
  g.frame_id = "map";
  g.width = 3;
  g.height = 2;
  g.resolution = resolution;
  g.origin_x = ox;
  g.origin_y = oy;
  g.origin_yaw = yaw;
  g.data.assign(6, 0);
  return g;
}

ParamValue oneParam(const std::string& name, double value)
{
  ParamValue ns = ParamValue::makeMap();
  ns.set(name, ParamValue::makeDouble(value));
  return ns;
}

struct Edge
{
  std::string name;
  double value;
  bool ok;
};

/// Runs parse on {name: value} for each edge; a refusal must name the parameter.
void checkEdges(const std::string& family, const std::vector<Edge>& edges,
                const std::function<void(const ParamValue&)>& parse)
{
  for (const auto& e : edges)
  {
    const std::string err = errorOf([&] { parse(oneParam(e.name, e.value)); });
    if (e.ok)
      EXPECT_EQ(err, "") << family << ": " << e.name << " = " << e.value;
    else
      EXPECT_TRUE(contains(err, "'" + e.name + "'")) << family << ": " << e.name << " = " << e.value << ": " << err;
  }
}
}  // namespace

// ---------------------------------------------------------------------------------------------
// Incoming grids (maps and masks): validateGrid, used by StaticLayer::setMap and CostmapFilter.

TEST(NumberEdges, GridResolutionAndOriginRanges)
{
  struct Case
  {
    OccupancyGridData g;
    const char* needle;  // "" = valid
  };
  const std::vector<Case> cases = {
      {grid(1e-4), ""},
      {grid(1e3), ""},
      {grid(0.05, 1e7, -1e7, 1e3), ""},
      {grid(0.05, -1e7, 1e7, -1e3), ""},
      {grid(1e-300), "resolution"},
      {grid(1e300), "resolution"},
      {grid(9.99e-5), "resolution"},
      {grid(1000.5), "resolution"},
      {grid(std::numeric_limits<double>::denorm_min()), "resolution"},
      {grid(kInf), "resolution"},
      {grid(kNaN), "resolution"},
      {grid(-1.0), "resolution"},
      {grid(0.05, 1e300), "origin"},
      {grid(0.05, 0.0, -1e7 - 1.0), "origin"},
      {grid(0.05, 0.0, 0.0, 1e300), "origin"},
      {grid(0.05, 0.0, 0.0, -1000.5), "origin"},
      {grid(0.05, 0.0, 0.0, kNaN), "origin"},
  };
  for (const auto& c : cases)
  {
    const std::string err = validateGrid(c.g).message;
    if (*c.needle == '\0')
      EXPECT_EQ(err, "") << c.g.resolution << " " << c.g.origin_x << " " << c.g.origin_y << " " << c.g.origin_yaw;
    else
      EXPECT_TRUE(contains(err, c.needle))
          << c.g.resolution << " " << c.g.origin_x << " " << c.g.origin_y << " " << c.g.origin_yaw << ": " << err;
  }
}

TEST(NumberEdges, StaticLayerRefusesAMapOfTinyResolution)
{
  // A map of resolution 1e-300 used to be taken: the master grid took its resolution, every
  // distance became astronomically many cells and the inflation made every cell inscribed.
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(4, 4, 1.0, 0.0, 0.0);
  auto layer = std::make_shared<StaticLayer>();
  layer->initialize(&lc, "static_layer", std::make_shared<FakeContext>());
  lc.addPlugin(layer);
  for (const double res : {1e-300, 1e300})
  {
    const std::string err = layer->setMap(std::make_shared<const OccupancyGridData>(grid(res)));
    EXPECT_TRUE(contains(err, "resolution")) << res << ": " << err;
  }
  EXPECT_EQ(layer->setMap(std::make_shared<const OccupancyGridData>(grid(1e-4))), "");
}

// ---------------------------------------------------------------------------------------------
// The costmap's own parameters.

TEST(NumberEdges, CostmapParameters)
{
  const auto parse = [](const ParamValue& ns) { parseCostmapConfig(ns); };
  checkEdges("costmap",
             {
                 {"update_frequency", 1e-3, true},
                 {"update_frequency", 1e3, true},
                 {"update_frequency", 1e-10, false},  // a period of 317 years: beyond ros::Duration
                 {"update_frequency", 0.0, false},
                 {"update_frequency", 1000.5, false},
                 {"update_frequency", -1.0, false},
                 {"update_frequency", kNaN, false},
                 {"update_frequency", kInf, false},
                 {"publish_frequency", 0.0, true},  // off
                 {"publish_frequency", 1e-3, true},
                 {"publish_frequency", 1e3, true},
                 {"publish_frequency", 1e-10, false},
                 {"publish_frequency", 5e-324, false},
                 {"publish_frequency", 1e300, false},
                 {"transform_tolerance", 3600.0, true},
                 {"transform_tolerance", 3600.5, false},
                 {"transform_tolerance", 1e300, false},
                 {"resolution", 1e-300, false},
                 {"resolution", 1e300, false},
                 {"origin_x", 1e7, true},
                 {"origin_x", -1e7, true},
                 {"origin_x", 1e300, false},
                 {"origin_y", -1e300, false},
                 {"footprint_padding", 1e4, true},
                 {"footprint_padding", 1e300, false},
                 {"robot_radius", 1e4, true},
                 {"robot_radius", 1e300, false},
                 {"robot_radius", -0.1, false},
                 {"reset_distance", 1e4, true},
                 {"reset_distance", 1e300, false},
             },
             parse);

  // Both ends of resolution, with sizes that fit them: 1 m at 1e-4 m/cell is 10000 cells a side;
  // 2000 m at 1e3 m/cell is 2 cells. (The default 10 m would be 1e10 cells at 1e-4: refused below.)
  for (const auto& [res, size] : {std::pair<double, double>{1e-4, 1.0}, {1e3, 2000.0}})
  {
    ParamValue ends = ParamValue::makeMap();
    ends.set("resolution", ParamValue::makeDouble(res));
    ends.set("width", ParamValue::makeDouble(size));
    ends.set("height", ParamValue::makeDouble(size));
    const std::string err = errorOf([&] { parseCostmapConfig(ends); });
    EXPECT_EQ(err, "") << res;
  }
  ParamValue fine = ParamValue::makeMap();
  fine.set("resolution", ParamValue::makeDouble(1e-4));
  EXPECT_TRUE(contains(errorOf([&] { parseCostmapConfig(fine); }), "400000000"));

  // width x height: 20000 x 20000 cells is the limit; 20000 x 20001 is over it (the default
  // resolution 0.05 m: 1000 m = 20000 cells).
  ParamValue ns = ParamValue::makeMap();
  ns.set("resolution", ParamValue::makeDouble(0.05));
  ns.set("width", ParamValue::makeDouble(1000.0));
  ns.set("height", ParamValue::makeDouble(1000.0));
  const CostmapConfig at_limit = parseCostmapConfig(ns);
  EXPECT_EQ(uint64_t{at_limit.sizeInCellsX()} * at_limit.sizeInCellsY(), 400000000u);
  ns.set("height", ParamValue::makeDouble(1000.05));
  const std::string over = errorOf([&] { parseCostmapConfig(ns); });
  EXPECT_TRUE(contains(over, "'height'") && contains(over, "400000000")) << over;
  // 100000 x 100000 cells (each side within its own limit) is 25 times the limit.
  ns.set("width", ParamValue::makeDouble(5000.0));
  ns.set("height", ParamValue::makeDouble(5000.0));
  EXPECT_TRUE(contains(errorOf([&] { parseCostmapConfig(ns); }), "400000000"));
}

TEST(NumberEdges, FootprintVerticesAreLengths)
{
  for (const std::string fp : {"[[1e300, 0], [0, 1], [1, 1]]", "[[0, 0], [0, -10000.5], [1, 1]]"})
  {
    ParamValue ns = ParamValue::makeMap();
    ns.set("footprint", ParamValue::makeString(fp));
    const std::string err = errorOf([&] { parseCostmapConfig(ns); });
    EXPECT_TRUE(contains(err, "'footprint'") && contains(err, "vertex")) << fp << ": " << err;
  }
  ParamValue ns = ParamValue::makeMap();
  ParamValue list = ParamValue::makeList();
  for (const auto& [x, y] : {std::pair<double, double>{1e300, 0.0}, {0.0, 1.0}, {1.0, 1.0}})
    list.push(ParamValue::makeList({ParamValue::makeDouble(x), ParamValue::makeDouble(y)}));
  ns.set("footprint", list);
  EXPECT_TRUE(contains(errorOf([&] { parseCostmapConfig(ns); }), "vertex"));
  ns.set("footprint", ParamValue::makeString("[[1e4, -1e4], [-1e4, -1e4], [0, 1e4]]"));
  EXPECT_EQ(errorOf([&] { parseCostmapConfig(ns); }), "");
}

// ---------------------------------------------------------------------------------------------
// Layer parameters whose derived quantities (cells = length / resolution, ns = s * 1e9) must stay
// representable.

TEST(NumberEdges, LayerParameters)
{
  checkEdges("inflation",
             {{"inflation_radius", 1e4, true}, {"inflation_radius", 1e300, false}, {"inflation_radius", 1e5, false}},
             [](const ParamValue& ns) { parseInflationConfig(ParamReader(ns, "inflation")); });
  checkEdges("observation source",
             {
                 {"raytrace_max_range", 1e4, true},
                 {"raytrace_max_range", 1e300, false},
                 {"raytrace_range", 1e300, false},  // the old name
                 {"obstacle_max_range", 1e300, false},
                 {"obstacle_min_range", 1e300, false},
                 {"raytrace_min_range", 1e300, false},
                 {"observation_keep_distance", 1e300, false},
                 {"observation_persistence", 3600.0, true},
                 {"observation_persistence", 1e300, false},
                 {"expected_update_rate", 1e300, false},
             },
             [](const ParamValue& ns) { parseObservationSourceConfig(ParamReader(ns, "scan"), "scan"); });
  checkEdges("range sensor", {{"no_readings_timeout", 3600.0, true}, {"no_readings_timeout", 1e300, false}},
             [](const ParamValue& ns) { parseRangeSensorConfig(ParamReader(ns, "range")); });
  checkEdges("voxel",
             {{"origin_z", -1e7, true},
              {"origin_z", 1e300, false},
              {"z_resolution", 1e3, true},
              {"z_resolution", 1e300, false}},
             [](const ParamValue& ns) { parseVoxelConfig(ParamReader(ns, "voxel")); });
}

// The one footprint rule, also what the move_base bridge applies to the footprint costmap_2d hands on
// (its footprint topic is float32: NaN and +-inf arrive as they are).
TEST(NumberEdges, FootprintProblemNamesTheVertex)
{
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(footprintProblem(makeFootprintFromRadius(0.3)), "");
  EXPECT_EQ(footprintProblem({{1e4, -1e4}, {-1e4, -1e4}, {0, 1e4}}), "");  // at the limit
  EXPECT_TRUE(contains(footprintProblem({{0, 0}, {1, 1}}), "at least 3")) << footprintProblem({{0, 0}, {1, 1}});
  EXPECT_TRUE(contains(footprintProblem({}), "got 0"));
  const std::string all_nan = footprintProblem({{nan, nan}, {nan, nan}, {nan, nan}});
  EXPECT_TRUE(contains(all_nan, "vertex 0") && contains(all_nan, "not finite")) << all_nan;
  const std::string one_inf = footprintProblem({{0.2, 0.2}, {-0.2, 0.2}, {-0.2, inf}});
  EXPECT_TRUE(contains(one_inf, "vertex 2") && contains(one_inf, "inf")) << one_inf;
  const std::string far = footprintProblem({{0.2, 0.2}, {-10000.5, 0.2}, {-0.2, -0.2}});
  EXPECT_TRUE(contains(far, "vertex 1") && contains(far, "10000.5") && contains(far, "farther")) << far;
}
