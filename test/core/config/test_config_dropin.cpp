// Drop-in configurations as other robots write them, where costmap_2d or Nav2 read a value in a way
// this package must translate or at least name: frames written with tf's leading '/', costmap_2d's
// combination_method 99 ("Do nothing") and Nav2's out-of-range values, Nav2's LaserScan default,
// pre-Hydro values costmap_2d skips, plugin names with '/', ROS 2's ros__parameters level, topic names
// roscpp would refuse, and the parameter lines costmap_node and costmap_tool share. Expected values
// are written from costmap_2d's sources (costmap_2d_ros.cpp, plugins/obstacle_layer.cpp,
// cfg/ObstaclePlugin.cfg) and Nav2's (nav2_costmap_2d/src/costmap_layer.cpp, plugins/obstacle_layer.cpp),
// not from the code under test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "costmap_layers/core/config/config_compat.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/grid/footprint.hpp"
#include "costmap_layers/core/layers/inflation_layer.hpp"
#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/layers/obstacle_layer.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/layers/range_sensor_layer.hpp"
#include "costmap_layers/core/layers/static_layer.hpp"
#include "fake_context.hpp"
#include "sensor_test_helpers.hpp"

using namespace costmap_layers;
using namespace costmap_layers_test;

namespace
{
bool anyContains(const std::vector<std::string>& lines, const std::vector<std::string>& parts)
{
  return std::any_of(lines.begin(), lines.end(),
                     [&](const std::string& line)
                     {
                       return std::all_of(parts.begin(), parts.end(),
                                          [&](const std::string& p) { return line.find(p) != std::string::npos; });
                     });
}

ParamValue pluginList(std::initializer_list<std::pair<const char*, const char*>> plugins)
{
  ParamValue list = ParamValue::makeList();
  for (const auto& [name, type] : plugins)
    list.push(paramMap({{"name", S(name)}, {"type", S(type)}}));
  return list;
}

std::string stringAt(const ParamValue& ns, const std::string& path)
{
  const ParamValue* v = ns.findPath(path);
  return v != nullptr && v->type() == ParamValue::Type::String ? v->asString() : "<none>";
}

}  // namespace

TEST(RosNames, RoscppsGrammar)
{
  for (const char* good : {"scan", "/scan", "~scan", "a/b_c/d9", "/a//b"})
    EXPECT_EQ(rosNameProblem(good), "") << good;
  EXPECT_NE(rosNameProblem("~scan", false), "");
  EXPECT_NE(rosNameProblem(""), "");
  const std::string comma = rosNameProblem("scan,");
  EXPECT_NE(comma.find("','"), std::string::npos) << comma;
  EXPECT_NE(comma.find("position 4"), std::string::npos) << comma;
  for (const char* bad : {"1scan", "my map", "a-b", "a.b", "_a"})
    EXPECT_NE(rosNameProblem(bad), "") << bad;
  const std::string control = rosNameProblem(std::string("a\x01", 2));
  EXPECT_NE(control.find("character code 1"), std::string::npos) << control;
  // A megabyte name is quoted clipped.
  EXPECT_LT(rosNameProblem(std::string(1 << 20, 'a') + "-").size(), 600u);
}

TEST(DropIn, FramesWithTfsLeadingSlashAreStrippedAndNamed)
{
  // TurtleBot2's and PR2's Indigo-era files: tf took "/map", tf2 does not (costmap_2d on tf2 waits
  // for "/map" for ever).
  ParamValue ns = paramMap({{"global_frame", S("/map")}, {"robot_base_frame", S("/base_footprint")}});
  ns.set("plugins", pluginList({{"obstacles", "costmap_2d::ObstacleLayer"}}));
  ns.set("obstacles", paramMap({{"observation_sources", S("scan")},
                                {"scan", paramMap({{"data_type", S("LaserScan")}, {"sensor_frame", S("/laser")}})}}));
  const CompatResult r = prepareCostmapNamespace(ns, "");
  EXPECT_EQ(stringAt(r.params, "global_frame"), "map");
  EXPECT_EQ(stringAt(r.params, "robot_base_frame"), "base_footprint");
  EXPECT_EQ(stringAt(r.params, "obstacles/scan/sensor_frame"), "laser");
  EXPECT_TRUE(anyContains(r.warnings, {"global_frame '/map'", "using 'map'"}));
  EXPECT_TRUE(anyContains(r.warnings, {"robot_base_frame '/base_footprint'"}));
  EXPECT_TRUE(anyContains(r.warnings, {"obstacles/scan/sensor_frame '/laser'"}));
  // A frame without it is left alone and says nothing.
  const CompatResult plain = prepareCostmapNamespace(paramMap({{"global_frame", S("odom")}}), "");
  EXPECT_EQ(stringAt(plain.params, "global_frame"), "odom");
  EXPECT_FALSE(anyContains(plain.warnings, {"global_frame"}));
}

TEST(DropIn, CombinationMethodAsEachStackReadsIt)
{
  // costmap_2d: ObstaclePlugin.cfg's enum is 0 Overwrite, 1 Maximum, 99 Nothing; updateCosts writes
  // nothing for any value but 0 and 1. Nav2: 0, 1, 2, any other value warns and uses 1.
  auto rules = [](const char* type, int64_t value)
  {
    ParamValue ns = ParamValue::makeMap();
    ns.set("plugins", pluginList({{"obstacles", type}}));
    ns.set("obstacles", paramMap({{"combination_method", I(value)}}));
    return prepareCostmapNamespace(ns, "");
  };
  auto valueOf = [](const CompatResult& r) { return r.params.findPath("obstacles/combination_method")->asInt(); };
  EXPECT_EQ(valueOf(rules("costmap_2d::ObstacleLayer", 99)), 99);
  EXPECT_EQ(valueOf(rules("costmap_2d::ObstacleLayer", 0)), 0);
  const CompatResult two = rules("costmap_2d::VoxelLayer", 2);
  EXPECT_EQ(valueOf(two), 99);
  EXPECT_TRUE(anyContains(two.warnings, {"obstacles/combination_method 2", "writes nothing", "taken as 99"}));
  const CompatResult nav2 = rules("nav2_costmap_2d::ObstacleLayer", 5);
  EXPECT_EQ(valueOf(nav2), 1);
  EXPECT_TRUE(anyContains(nav2.warnings, {"obstacles/combination_method 5", "uses 1"}));
  EXPECT_EQ(valueOf(rules("nav2_costmap_2d::ObstacleLayer", 2)), 2);
  // This package's own type: 0, 1, 2 and 99; anything else is refused naming the parameter.
  EXPECT_EQ(parseObstacleConfig(ParamReader(paramMap({{"combination_method", I(99)}}), "o"), false).combination_method,
            99);
  const std::string refused = thrownMessage(
      [] {
        parseObstacleConfig(ParamReader(paramMap({{"combination_method", I(3)}}), "o"), false);
      });
  EXPECT_NE(refused.find("'combination_method'"), std::string::npos) << refused;
  EXPECT_NE(refused.find("(got 3)"), std::string::npos) << refused;
}

TEST(DropIn, CombinationMethod99WritesNothingIntoTheMaster)
{
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(10, 10, 1.0, 0.0, 0.0);
  ParamValue src =
      paramMap({{"data_type", S("PointCloud2")}, {"obstacle_max_range", D(100.0)}, {"raytrace_max_range", D(100.0)}});
  ParamValue p = paramMap({{"observation_sources", S("cloud")}, {"combination_method", I(99)}});
  p.set("cloud", src);
  auto ctx = std::make_shared<FakeContext>(p);
  auto layer = std::make_shared<ObstacleLayer>();
  layer->initialize(&lc, "obstacles", ctx);
  ctx->bind(*layer);
  lc.addPlugin(layer);
  PointCloud2Data cloud = makeCloud({{3.0, 3.0, 0.5}});
  ASSERT_EQ(ctx->publishCloud("cloud", cloud, poseAt(0.0, 0.0, 0.5)), 1);
  lc.updateMap(0.0, 0.0, 0.0);
  // The layer marked the point in its own grid, and left the master as it was.
  EXPECT_EQ(layer->costmap().getCost(3, 3), LETHAL_OBSTACLE);
  for (unsigned y = 0; y < 10; ++y)
    for (unsigned x = 0; x < 10; ++x)
      EXPECT_EQ(lc.getCostmap().getCost(x, y), FREE_SPACE) << x << "," << y;
}

TEST(DropIn, SourcesReadTheirStacksDataTypeByDefault)
{
  // nav2_costmap_2d/plugins/obstacle_layer.cpp: declare_or_get_parameter(source + ".data_type", "LaserScan").
  ParamValue ns = ParamValue::makeMap();
  ns.set("plugins",
         pluginList({{"obstacles", "nav2_costmap_2d::ObstacleLayer"}, {"voxels", "costmap_2d::VoxelLayer"}}));
  ns.set("obstacles", paramMap({{"observation_sources", S("scan")}, {"scan", paramMap({{"topic", S("/scan")}})}}));
  ns.set("voxels", paramMap({{"observation_sources", S("cam")}, {"cam", paramMap({{"topic", S("/cam")}})}}));
  const CompatResult r = prepareCostmapNamespace(ns, "");
  EXPECT_EQ(stringAt(r.params, "obstacles/scan/data_type"), "LaserScan");
  EXPECT_TRUE(anyContains(r.notes, {"obstacles/scan", "data_type", "LaserScan", "Nav2"}));
  // Nav2's per-source max_obstacle_height default (0.0) is not taken, but said.
  EXPECT_TRUE(anyContains(r.notes, {"obstacles/scan: max_obstacle_height not set: 2.0 m", "Nav2's is 0.0"}));
  // costmap_2d's types read costmap_2d's default, sensor_msgs/PointCloud (obstacle_layer.cpp:
  // source_node.param("data_type", data_type, std::string("PointCloud"))).
  EXPECT_EQ(stringAt(r.params, "voxels/cam/data_type"), "PointCloud");
  EXPECT_TRUE(anyContains(r.notes, {"voxels/cam", "data_type not set: PointCloud", "costmap_2d's default"}));
  // This package's own type names keep its default (the layer names it at start-up).
  ParamValue native = ns;
  native.set("plugins", pluginList({{"voxels", "costmap_layers/VoxelLayer"}}));
  EXPECT_EQ(stringAt(prepareCostmapNamespace(native, "").params, "voxels/cam/data_type"), "<none>");
}

// nav2_costmap_2d/plugins/obstacle_layer.cpp (and voxel_layer.cpp): declare_or_get_parameter(name_ +
// ".min_obstacle_height", 0.0), and a hit with z below it is not marked. costmap_2d has no such limit.
TEST(DropIn, Nav2LayersDropHitsBelowTheirMinObstacleHeight)
{
  ParamValue ns = ParamValue::makeMap();
  ns.set("plugins", pluginList({{"obstacles", "nav2_costmap_2d::ObstacleLayer"},
                                {"voxels", "nav2_costmap_2d::VoxelLayer"},
                                {"set", "nav2_costmap_2d::ObstacleLayer"},
                                {"ros1", "costmap_2d::ObstacleLayer"}}));
  ns.set("obstacles", paramMap({{"observation_sources", S("")}}));
  ns.set("voxels", paramMap({{"observation_sources", S("")}}));
  ns.set("set", paramMap({{"observation_sources", S("")}, {"min_obstacle_height", D(-0.5)}}));
  ns.set("ros1", paramMap({{"observation_sources", S("")}}));
  const CompatResult r = prepareCostmapNamespace(ns, "");
  EXPECT_EQ(r.params.findPath("obstacles/min_obstacle_height")->asDouble(), 0.0);
  EXPECT_EQ(r.params.findPath("voxels/min_obstacle_height")->asDouble(), 0.0);
  EXPECT_EQ(r.params.findPath("set/min_obstacle_height")->asDouble(), -0.5);  // as written
  EXPECT_EQ(r.params.findPath("ros1/min_obstacle_height"), nullptr);
  EXPECT_TRUE(anyContains(r.notes, {"obstacles: min_obstacle_height not set: 0.0 m, Nav2's default"}));
  EXPECT_TRUE(anyContains(r.notes, {"voxels: min_obstacle_height not set"}));
  EXPECT_FALSE(anyContains(r.notes, {"set: min_obstacle_height"}));
  EXPECT_FALSE(anyContains(r.notes, {"ros1: min_obstacle_height"}));
}

// nav2_costmap_2d/src/costmap_2d_ros.cpp: publish_frequency 1.0, width and height 5, resolution 0.1,
// robot_radius 0.1, where costmap_2d (and this package) default to 0.0 (never publish), 10, 0.05 and 0.46. A
// Nav2 file (its ros__parameters level) gets Nav2's, each said; a value written stays; a ROS 1 file keeps
// costmap_2d's.
TEST(DropIn, ANav2FileGetsNav2sCostmapDefaults)
{
  ParamValue ros2 = ParamValue::makeMap();
  ros2.set("ros__parameters", paramMap({{"width", D(3.0)}}));
  const CompatResult r = prepareCostmapNamespace(ros2, "");
  EXPECT_EQ(r.params.find("publish_frequency")->asDouble(), 1.0);
  EXPECT_EQ(r.params.find("width")->asDouble(), 3.0);  // as written
  EXPECT_EQ(r.params.find("height")->asDouble(), 5.0);
  EXPECT_EQ(r.params.find("resolution")->asDouble(), 0.1);
  EXPECT_EQ(r.params.find("robot_radius")->asDouble(), 0.1);
  EXPECT_TRUE(anyContains(r.notes, {"publish_frequency not set: 1, Nav2's default (costmap_2d's is 0: never)"}));
  EXPECT_TRUE(anyContains(r.notes, {"robot_radius not set: 0.1, Nav2's default (costmap_2d's is 0.46)"}));
  EXPECT_FALSE(anyContains(r.notes, {"width not set"}));
  const CostmapConfig c = parseCostmapConfig(r.params);
  EXPECT_EQ(c.publish_frequency, 1.0);
  EXPECT_EQ(c.height, 5.0);
  EXPECT_EQ(c.footprint.robot_radius, 0.1);

  // The namespace named may be that level itself (costmap_tool --namespace .../ros__parameters).
  const CompatResult level = prepareCostmapNamespace(paramMap({{"width", D(3.0)}}), "ros__parameters");
  EXPECT_EQ(level.params.find("resolution")->asDouble(), 0.1);
  EXPECT_FALSE(anyContains(level.warnings, {"remove that level"}));

  // A footprint polygon makes robot_radius moot: not set then.
  ParamValue with_footprint = ParamValue::makeMap();
  with_footprint.set("ros__parameters", paramMap({{"footprint", S("[[0.3, 0.2], [0.3, -0.2], [-0.3, -0.2]]")}}));
  EXPECT_EQ(prepareCostmapNamespace(with_footprint, "").params.find("robot_radius"), nullptr);

  // A ROS 1 file: costmap_2d's defaults, nothing added.
  const CompatResult ros1 = prepareCostmapNamespace(paramMap({{"width", D(3.0)}}), "");
  EXPECT_EQ(ros1.params.find("publish_frequency"), nullptr);
  EXPECT_EQ(ros1.params.find("robot_radius"), nullptr);
  EXPECT_EQ(parseCostmapConfig(ros1.params).publish_frequency, 0.0);
}

TEST(DropIn, PreHydroValuesCostmap2dSkipsAreNamed)
{
  // costmap_2d_ros.cpp loadOldParameters: getParam("static_map", bool) fails on a string or an int
  // (no static layer); map_type other than "voxel" gives an ObstacleLayer.
  ParamValue ns = paramMap({{"static_map", S("true")}, {"map_type", S("voxels")}});
  const CompatResult r = prepareCostmapNamespace(ns, "");
  const auto lists = parsePluginLists(r.params);
  ASSERT_EQ(lists.plugins.size(), 2u);
  EXPECT_EQ(lists.plugins[0].type, "costmap_2d::ObstacleLayer");
  EXPECT_TRUE(anyContains(r.warnings, {"\"static_map\" is \"true\"", "no static layer"}));
  EXPECT_TRUE(anyContains(r.warnings, {"\"map_type\" is \"voxels\"", "ObstacleLayer"}));
  const CompatResult one = prepareCostmapNamespace(paramMap({{"static_map", I(1)}, {"map_type", S("costmap")}}), "");
  EXPECT_TRUE(anyContains(one.warnings, {"\"static_map\" is 1"}));
  EXPECT_FALSE(anyContains(one.warnings, {"\"map_type\" is"}));
}

TEST(DropIn, NestedPluginNamesAndRos2LevelAndNoPlugins)
{
  // costmap_2d reads the plugin "layers/static" from <costmap>/layers/static.
  ParamValue ns = ParamValue::makeMap();
  ns.set("plugins", pluginList({{"layers/static", "costmap_2d::StaticLayer"}}));
  ns.set("layers", paramMap({{"static", paramMap({{"map_topic", S("/mymap")}})}}));
  const CompatResult nested = prepareCostmapNamespace(ns, "");
  ASSERT_NE(nested.params.find("layers/static"), nullptr);  // the key every look-up by plugin name uses
  EXPECT_EQ(stringAt(*nested.params.find("layers/static"), "map_topic"), "/mymap");
  EXPECT_EQ(nested.params.find("layers"), nullptr);  // left empty, gone: no "unused namespace" warning
  ParamReadLog log;
  const ParamValue* layer_params = nested.params.find("layers/static");
  EXPECT_EQ(parseStaticConfig(ParamReader(*layer_params, "layers/static"), true).map_topic, "/mymap");
  EXPECT_TRUE(unusedParameterLines(nested, log,
                                   {{PluginSpec{"layers/static", "costmap_2d::StaticLayer"}, layer_params}},
                                   "/move_base/global_costmap")
                  .size() <= 1);  // at most the costmap's own keys nobody read here (plugins)

  // A Nav2 file loaded with its ros__parameters level.
  ParamValue ros2 = ParamValue::makeMap();
  ros2.set("ros__parameters", paramMap({{"global_frame", S("odom")}, {"resolution", D(0.1)}}));
  const CompatResult lifted = prepareCostmapNamespace(ros2, "");
  EXPECT_EQ(stringAt(lifted.params, "global_frame"), "odom");
  EXPECT_EQ(lifted.params.find("ros__parameters"), nullptr);
  EXPECT_TRUE(anyContains(lifted.warnings, {"ros__parameters", "remove that level"}));

  // plugins: [] builds a costmap with no layer: said.
  ParamValue empty = ParamValue::makeMap();
  empty.set("plugins", ParamValue::makeList());
  EXPECT_TRUE(anyContains(prepareCostmapNamespace(empty, "").warnings, {"no plugins and no filters"}));
  // The move_base section lift is a note, as the node logged it.
  ParamValue mb = ParamValue::makeMap();
  mb.set("global_costmap", paramMap({{"resolution", D(0.1)}}));
  const CompatResult from_mb = prepareCostmapNamespace(mb, "global_costmap");
  EXPECT_TRUE(anyContains(from_mb.notes, {"holds a move_base file's `global_costmap:` section"}));
}

TEST(DropIn, TransformToleranceZeroIsSaid)
{
  EXPECT_TRUE(anyContains(prepareCostmapNamespace(paramMap({{"transform_tolerance", D(0.0)}}), "").warnings,
                          {"transform_tolerance 0: the robot's transform is used however old it is"}));
  EXPECT_TRUE(anyContains(prepareCostmapNamespace(paramMap({{"transform_tolerance", I(0)}}), "").warnings,
                          {"transform_tolerance 0"}));
  EXPECT_FALSE(anyContains(prepareCostmapNamespace(paramMap({{"transform_tolerance", D(0.3)}}), "").warnings,
                           {"transform_tolerance"}));
}

TEST(DropIn, FootprintWinsOverRobotRadiusSaid)
{
  ParamValue ns = paramMap({{"footprint", S("[[0.1, 0.1], [0.1, -0.1], [-0.1, -0.1]]")}, {"robot_radius", D(0.3)}});
  EXPECT_TRUE(anyContains(prepareCostmapNamespace(ns, "").notes, {"robot_radius 0.3 is not used"}));
  ParamValue empty_fp = paramMap({{"footprint", S("[]")}, {"robot_radius", D(0.3)}});
  EXPECT_FALSE(anyContains(prepareCostmapNamespace(empty_fp, "").notes, {"robot_radius"}));
}

TEST(DropIn, ParentsInATreeNearestFirst)
{
  ParamValue root = ParamValue::makeMap();
  root.set("robot_radius", D(0.4));
  root.set("move_base", paramMap({{"footprint", S("[[1, 1], [1, -1], [-1, 0]]")},
                                  {"global_costmap", paramMap({{"resolution", D(0.05)}})}}));
  const auto parents = parentsInTree(root, "move_base/global_costmap");
  ASSERT_EQ(parents.size(), 2u);
  EXPECT_EQ(parents[0].name, "/move_base");
  EXPECT_NE(parents[0].values.find("footprint"), nullptr);
  EXPECT_EQ(parents[1].name, "/");
  ASSERT_NE(parents[1].values.find("robot_radius"), nullptr);
  EXPECT_DOUBLE_EQ(parents[1].values.find("robot_radius")->asDouble(), 0.4);
  EXPECT_TRUE(parentsInTree(root, "").empty());
}

TEST(DropIn, TopicNamesRoscppWouldRefuseAreNamedAtStartUp)
{
  // "scan, bump": costmap_2d splits on blanks, so the source is "scan," (and its default topic too).
  const std::string comma = thrownMessage(
      [] {
        parseObstacleConfig(ParamReader(paramMap({{"observation_sources", S("scan, bump")}}), "o"), false);
      });
  EXPECT_NE(comma.find("'observation_sources'"), std::string::npos) << comma;
  EXPECT_NE(comma.find("not commas"), std::string::npos) << comma;
  ParamValue spaced = paramMap({{"observation_sources", S("scan")}});
  spaced.set("scan", paramMap({{"topic", S("scan topic")}}));
  const std::string topic = thrownMessage([&] { parseObstacleConfig(ParamReader(spaced, "o"), false); });
  EXPECT_NE(topic.find("o/scan: parameter 'topic'"), std::string::npos) << topic;
  const std::string map_topic = thrownMessage(
      [] {
        parseStaticConfig(ParamReader(paramMap({{"map_topic", S("my map")}}), "static"), true);
      });
  EXPECT_NE(map_topic.find("'map_topic'"), std::string::npos) << map_topic;
  const std::string range = thrownMessage(
      [] {
        parseRangeSensorConfig(ParamReader(paramMap({{"topics", ParamValue::makeList({S("/sonar-1")})}}), "r"));
      });
  EXPECT_NE(range.find("'topics'"), std::string::npos) << range;
  EXPECT_NE(range.find("/sonar-1"), std::string::npos) << range;
  // Private and absolute names are names.
  ParamValue fine = paramMap({{"observation_sources", S("a b")}});
  fine.set("a", paramMap({{"topic", S("~scan")}}));
  fine.set("b", paramMap({{"topic", S("/robot/scan")}}));
  EXPECT_EQ(thrownMessage([&] { parseObstacleConfig(ParamReader(fine, "o"), false); }), "");
}

TEST(DropIn, ASourceWithoutItsNamespaceAndAMisspeltOneAreNamed)
{
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(10, 10, 1.0, 0.0, 0.0);
  ParamValue p = paramMap({{"observation_sources", S("laser_scan_sensor")}});
  p.set("laser_scan_senser", paramMap({{"data_type", S("LaserScan")}, {"topic", S("/scan")}}));
  auto ctx = std::make_shared<FakeContext>(p);
  auto layer = std::make_shared<ObstacleLayer>();
  ParamReadLog log;
  layer->initialize(&lc, "obstacles", ctx);
  bool named = false;
  for (const auto& r : ctx->reports)
    named = named || (r.severity == Severity::Warn &&
                      r.message.find("'laser_scan_sensor' has no namespace of that name") != std::string::npos);
  EXPECT_TRUE(named) << "no warning about the source without its namespace";
  // The unused namespace is described as the layer's, with the nearest source name.
  CompatResult compat;
  compat.params = ParamValue::makeMap();
  const auto lines =
      unusedParameterLines(compat, log, {{PluginSpec{"obstacles", "costmap_2d::ObstacleLayer"}, &ctx->params()}},
                           "/move_base/local_costmap");
  EXPECT_TRUE(anyContains(lines, {"namespace 'laser_scan_senser' in /move_base/local_costmap/obstacles",
                                  "not read by this ObstacleLayer", "`laser_scan_sensor`"}))
      << (lines.empty() ? std::string("no line") : lines.front());
  EXPECT_FALSE(anyContains(lines, {"names no plugin"}));
}

TEST(DropIn, LethalCostThresholdClampIsSaid)
{
  // costmap_2d's static_layer.cpp clamps it to [0, 100] silently.
  LayeredCostmap lc("map", false, false);
  auto ctx = std::make_shared<FakeContext>(paramMap({{"lethal_cost_threshold", I(254)}}));
  auto layer = std::make_shared<StaticLayer>();
  layer->initialize(&lc, "static", ctx);
  EXPECT_EQ(layer->config().lethal_cost_threshold, 100);
  bool said = false;
  for (const auto& r : ctx->reports)
    said = said || (r.key == "lethal_cost_threshold" && r.message.find("254") != std::string::npos &&
                    r.message.find("100 used") != std::string::npos);
  EXPECT_TRUE(said);
}

TEST(DropIn, ANumberRosparamReadsAsAStringSaysHowToWriteIt)
{
  const std::string hint = thrownMessage(
      [] {
        ParamReader(paramMap({{"inflation_radius", S("5e-1")}}), "inflation").getDouble("inflation_radius", 0.55);
      });
  EXPECT_NE(hint.find("'inflation_radius'"), std::string::npos) << hint;
  EXPECT_NE(hint.find("5.0e-2"), std::string::npos) << hint;
  const std::string plain = thrownMessage(
      [] {
        ParamReader(paramMap({{"inflation_radius", S("wide")}}), "inflation").getDouble("inflation_radius", 0.55);
      });
  EXPECT_NE(plain.find("must be a number"), std::string::npos) << plain;
  EXPECT_EQ(plain.find("rosparam"), std::string::npos) << plain;
}

TEST(DropIn, Nav2StaticLayerKeysAtTheCostmapLevelApply)
{
  // nav2_costmap_2d/plugins/static_layer.cpp: node->get_parameter("lethal_cost_threshold", ...) and
  // the same for unknown_cost_value, trinary_costmap, use_maximum, track_unknown_space.
  ParamValue ns = paramMap({{"lethal_cost_threshold", I(65)}, {"trinary_costmap", B(false)}, {"use_maximum", B(true)}});
  ns.set("plugins", pluginList({{"static_layer", "nav2_costmap_2d::StaticLayer"}}));
  ns.set("static_layer", paramMap({{"use_maximum", B(false)}}));
  const CompatResult r = prepareCostmapNamespace(ns, "");
  const StaticConfig c = parseStaticConfig(ParamReader(*r.params.find("static_layer"), "static_layer"), true);
  EXPECT_EQ(c.lethal_cost_threshold, 65);
  EXPECT_FALSE(c.trinary_costmap);
  EXPECT_TRUE(c.use_maximum);
  EXPECT_TRUE(anyContains(r.warnings, {"'static_layer/use_maximum' false", "costmap level only"}));
  EXPECT_TRUE(anyContains(r.notes, {"lethal_cost_threshold 65"}));
  // Used up: not reported as unknown keys of the costmap.
  EXPECT_NE(std::find(r.consumed.begin(), r.consumed.end(), "lethal_cost_threshold"), r.consumed.end());
  // A costmap_2d::StaticLayer is not read that way (it has copyParentParameters for its own keys).
  ParamValue c2d = paramMap({{"trinary_costmap", B(false)}});
  c2d.set("plugins", pluginList({{"static_layer", "costmap_2d::StaticLayer"}}));
  EXPECT_EQ(prepareCostmapNamespace(c2d, "").params.findPath("static_layer/trinary_costmap"), nullptr);
}

TEST(DropIn, Nav2InflationNumThreadsMinusOneIsAuto)
{
  // nav2_costmap_2d/plugins/inflation_layer.cpp: num_threads default -1; <= 0 means half the cores,
  // at least one (getOptimalThreadCount).
  for (int64_t v : {-1, 0})
  {
    const int n = parseInflationConfig(ParamReader(paramMap({{"num_threads", I(v)}}), "inflation")).num_threads;
    EXPECT_GE(n, 1) << v;
    EXPECT_LE(n, 64) << v;
  }
  EXPECT_EQ(parseInflationConfig(ParamReader(paramMap({{"num_threads", I(3)}}), "inflation")).num_threads, 3);
  for (int64_t bad : {65, -2})
    EXPECT_NE(thrownMessage(
                  [&] {
                    parseInflationConfig(ParamReader(paramMap({{"num_threads", I(bad)}}), "inflation"));
                  }),
              "")
        << bad;
}

TEST(DropIn, NegativeFootprintPaddingShrinksAsInCostmap2d)
{
  // costmap_2d's Costmap2D.cfg gives footprint_padding no bounds; padFootprint moves each coordinate
  // by the padding away from (or, negative, towards) the axis.
  const FootprintConfig c = parseFootprintConfig(
      ParamReader(paramMap({{"footprint", S("[[0.3, 0.2], [0.3, -0.2], [-0.3, -0.2], [-0.3, 0.2]]")},
                            {"footprint_padding", D(-0.05)}}),
                  "costmap"));
  const Footprint fp = c.padded();
  ASSERT_EQ(fp.size(), 4u);
  EXPECT_DOUBLE_EQ(fp[0].x(), 0.25);
  EXPECT_DOUBLE_EQ(fp[0].y(), 0.15);
  EXPECT_DOUBLE_EQ(fp[2].x(), -0.25);
  EXPECT_DOUBLE_EQ(fp[2].y(), -0.15);
  // A shrink that would carry a vertex across an axis is refused, naming the parameter.
  const std::string refused = thrownMessage(
      []
      {
        parseFootprintConfig(ParamReader(
            paramMap({{"footprint", S("[[0.3, 0.2], [0.3, -0.2], [-0.3, -0.2]]")}, {"footprint_padding", D(-0.2)}}),
            "costmap"));
      });
  EXPECT_NE(refused.find("'footprint_padding'"), std::string::npos) << refused;
}

// The same rule for the circle of robot_radius, whether `footprint` is absent or costmap_2d's "[]".
// Before, an absent footprint skipped the check (r 0.46, padding -0.5 was taken: vertices mirrored,
// inscribed radius 0.04), and "[]" refused even -0.01 (the circle's vertex on the y axis has
// x = 2.8e-17, which counted as off the axis).
TEST(DropIn, NegativeFootprintPaddingOfTheRadiusCircle)
{
  for (const char* written : {"", "[]"})
  {
    auto params = [&](double padding)
    {
      ParamValue p = paramMap({{"robot_radius", D(0.46)}, {"footprint_padding", D(padding)}});
      if (*written != '\0') p.set("footprint", S(written));
      return p;
    };
    const FootprintConfig small = parseFootprintConfig(ParamReader(params(-0.01), "costmap"));
    EXPECT_TRUE(small.footprint.empty()) << written;
    // The 16-gon of 0.46 moved 0.01 towards both axes: the vertex at 0 degrees is at (0.45, ~0).
    EXPECT_NEAR(small.padded()[0].x(), 0.45, 1e-12) << written;
    // At -0.5 the vertex at 22.5 degrees (0.425, 0.176) would cross the x axis: refused, named.
    const std::string refused = thrownMessage([&] { parseFootprintConfig(ParamReader(params(-0.5), "costmap")); });
    EXPECT_NE(refused.find("'footprint_padding'"), std::string::npos) << written << ": " << refused;
    // Just under that vertex's distance from the axis (0.46 sin 22.5 = 0.17603) is taken; just over it, not.
    EXPECT_NO_THROW(parseFootprintConfig(ParamReader(params(-0.1760), "costmap"))) << written;
    EXPECT_THROW(parseFootprintConfig(ParamReader(params(-0.1761), "costmap")), std::invalid_argument) << written;
  }
}

TEST(DropIn, Nav2CustomInscribedRadiusReplacesTheFootprintsAndIsWarned)
{
  // Nav2 integration/inflation_tests.cpp testCustomInscribedRadius: with custom_inscribed_radius below
  // the footprint's inscribed radius, cells within the footprint's radius are no longer inscribed
  // (253): the cost function starts at the custom radius, 252 * exp(-factor * (d - custom)).
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(11, 11, 1.0, 0.0, 0.0);
  lc.setFootprint({{1.0, 1.0}, {1.0, -1.0}, {-1.0, -1.0}, {-1.0, 1.0}});  // inscribed radius 1.0
  auto run = [&lc](double custom)
  {
    auto ctx = std::make_shared<FakeContext>(paramMap(
        {{"inflation_radius", D(5.0)}, {"cost_scaling_factor", D(1.0)}, {"custom_inscribed_radius", D(custom)}}));
    auto layer = std::make_shared<InflationLayer>();
    layer->initialize(&lc, "inflation", ctx);
    Costmap2D& master = lc.getCostmap();
    master.resetMaps();
    master.setCost(5, 5, LETHAL_OBSTACLE);
    layer->updateCosts(master, 0, 0, 11, 11);
    bool warned = false;
    for (const auto& r : ctx->reports)
      warned = warned || (r.key == "custom_inscribed_radius" && r.severity == Severity::Warn);
    return std::make_pair(static_cast<int>(master.getCost(6, 5)), warned);
  };
  const auto footprint = run(-1.0);
  EXPECT_EQ(footprint.first, INSCRIBED_INFLATED_OBSTACLE);  // 1 m from the obstacle, within 1.0
  EXPECT_FALSE(footprint.second);
  const auto custom = run(0.0);
  EXPECT_EQ(custom.first, static_cast<int>(252.0 * std::exp(-1.0 * (1.0 - 0.0))));  // 92
  EXPECT_TRUE(custom.second);
  // Any negative number is "not set" in Nav2 (it tests >= 0), not only its default -1.
  const auto minus_two = run(-2.5);
  EXPECT_EQ(minus_two.first, INSCRIBED_INFLATED_OBSTACLE);
  EXPECT_FALSE(minus_two.second);
}
