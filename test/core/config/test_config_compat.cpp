// Unit tests of the costmap_2d / Nav2 compatibility step: the type alias table, the pre-Hydro
// conversion (costmap_2d's loadOldParameters), copyParentParameters, searchParam, lifting a nested
// move_base section, and the unknown-key finder. Every expected value below is written from
// costmap_2d's sources (costmap_2d_ros.cpp, footprint.cpp, plugins/obstacle_layer.cpp), not from the
// code under test.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "costmap_layers/core/config/config_compat.hpp"
#include "costmap_layers/core/costmap/costmap_config.hpp"
#include "costmap_layers/core/layers/inflation_layer.hpp"
#include "costmap_layers/core/layers/obstacle_layer.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/layers/static_layer.hpp"
#include "sensor_test_helpers.hpp"

using namespace costmap_layers;
using costmap_layers_test::B;
using costmap_layers_test::D;
using costmap_layers_test::S;

namespace
{
ParamValue point(double x, double y)
{
  return ParamValue::makeList({D(x), D(y)});
}

/// TurtleBot3's costmap_common_params_burger.yaml merged with its global_costmap_params.yaml, as
/// move_base's namespace global_costmap holds them.
ParamValue turtlebot3Global()
{
  ParamValue ns = ParamValue::makeMap();
  ns.set("obstacle_range", D(3.0));
  ns.set("raytrace_range", D(3.5));
  ns.set("footprint", ParamValue::makeList(
                          {point(-0.105, -0.105), point(-0.105, 0.105), point(0.041, 0.105), point(0.041, -0.105)}));
  ns.set("inflation_radius", D(1.0));
  ns.set("cost_scaling_factor", D(3.0));
  ns.set("map_type", S("costmap"));
  ns.set("observation_sources", S("scan"));
  ParamValue scan = ParamValue::makeMap();
  scan.set("sensor_frame", S("base_scan"));
  scan.set("data_type", S("LaserScan"));
  scan.set("topic", S("scan"));
  scan.set("marking", B(true));
  scan.set("clearing", B(true));
  ns.set("scan", scan);
  ns.set("global_frame", S("map"));
  ns.set("robot_base_frame", S("base_footprint"));
  ns.set("update_frequency", D(10.0));
  ns.set("publish_frequency", D(10.0));
  ns.set("transform_tolerance", D(0.5));
  ns.set("static_map", B(true));
  return ns;
}

std::vector<std::pair<std::string, std::string>> pluginsOf(const ParamValue& ns)
{
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& s : parsePluginLists(ns).plugins)
    out.emplace_back(s.name, s.type);
  return out;
}

double numberAt(const ParamValue& ns, const std::string& path)
{
  const ParamValue* v = ns.findPath(path);
  EXPECT_NE(v, nullptr) << path;
  return v != nullptr ? v->asDouble() : -1.0;
}

bool has(const std::vector<std::string>& v, const std::string& s)
{
  return std::find(v.begin(), v.end(), s) != v.end();
}
}  // namespace

TEST(TypeAliases, EveryForeignNameLoadsOurClass)
{
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"costmap_2d::StaticLayer", "costmap_layers/StaticLayer"},
      {"costmap_2d::ObstacleLayer", "costmap_layers/ObstacleLayer"},
      {"costmap_2d::VoxelLayer", "costmap_layers/VoxelLayer"},
      {"costmap_2d::InflationLayer", "costmap_layers/InflationLayer"},
      {"range_sensor_layer::RangeSensorLayer", "costmap_layers/RangeSensorLayer"},
      {"nav2_costmap_2d::StaticLayer", "costmap_layers/StaticLayer"},
      {"nav2_costmap_2d::ObstacleLayer", "costmap_layers/ObstacleLayer"},
      {"nav2_costmap_2d::VoxelLayer", "costmap_layers/VoxelLayer"},
      {"nav2_costmap_2d::InflationLayer", "costmap_layers/InflationLayer"},
      {"nav2_costmap_2d::LegacyInflationLayer", "costmap_layers/InflationLayer"},
      {"nav2_costmap_2d::RangeSensorLayer", "costmap_layers/RangeSensorLayer"},
      {"nav2_costmap_2d::KeepoutFilter", "costmap_layers/KeepoutFilter"},
      {"nav2_costmap_2d::SpeedFilter", "costmap_layers/SpeedFilter"},
      {"nav2_costmap_2d::ZoneParameterFilter", "costmap_layers/ZoneParameterFilter"},
      {"nav2_costmap_2d::BinaryFilter", "costmap_layers/BinaryFilter"},
      {"nav2_costmap_2d::DenoiseLayer", "costmap_layers/DenoiseLayer"},
      {"nav2_costmap_2d::AsymmetricInflationLayer", "costmap_layers/AsymmetricInflationLayer"},
      {"nav2_costmap_2d::PluginContainerLayer", "costmap_layers/PluginContainerLayer"},
  };
  for (const auto& [written, ours] : expected)
    EXPECT_EQ(resolvePluginType(written), ours) << written;
  EXPECT_EQ(pluginTypeAliases().size(), expected.size());
  // Our own names and unknown names pass through unchanged (the factory then reports the unknown one).
  EXPECT_EQ(resolvePluginType("costmap_layers/GradientLayer"), "costmap_layers/GradientLayer");
  EXPECT_EQ(resolvePluginType("costmap_2d::NoSuchLayer"), "costmap_2d::NoSuchLayer");
  EXPECT_EQ(typeDialect("costmap_2d::VoxelLayer"), TypeDialect::Costmap2D);
  EXPECT_EQ(typeDialect("range_sensor_layer::RangeSensorLayer"), TypeDialect::Costmap2D);
  EXPECT_EQ(typeDialect("nav2_costmap_2d::SpeedFilter"), TypeDialect::Nav2);
  EXPECT_EQ(typeDialect("costmap_layers/StaticLayer"), TypeDialect::Native);
  EXPECT_EQ(pluginClassName("costmap_2d::VoxelLayer"), "VoxelLayer");
  EXPECT_EQ(pluginClassName("costmap_layers/VoxelLayer"), "VoxelLayer");
}

TEST(TypeAliases, Nav2ListFormWithForeignTypes)
{
  ParamValue ns = ParamValue::makeMap();
  ns.set("plugins", ParamValue::makeList({S("static_layer"), S("inflation_layer")}));
  ParamValue s = ParamValue::makeMap();
  s.set("plugin", S("nav2_costmap_2d::StaticLayer"));
  ns.set("static_layer", s);
  ParamValue i = ParamValue::makeMap();
  i.set("plugin", S("nav2_costmap_2d::InflationLayer"));
  ns.set("inflation_layer", i);
  const auto plugins = pluginsOf(applyCostmap2dRules(ns).params);
  ASSERT_EQ(plugins.size(), 2u);
  EXPECT_EQ(plugins[0].second, "nav2_costmap_2d::StaticLayer");
  EXPECT_EQ(resolvePluginType(plugins[1].second), "costmap_layers/InflationLayer");
}

TEST(PreHydro, TurtleBot3GlobalCostmap)
{
  const CompatResult r = applyCostmap2dRules(turtlebot3Global());
  EXPECT_TRUE(r.converted_pre_hydro);
  const std::vector<std::pair<std::string, std::string>> expected = {{"static_layer", "costmap_2d::StaticLayer"},
                                                                     {"obstacle_layer", "costmap_2d::ObstacleLayer"},
                                                                     {"inflation_layer", "costmap_2d::InflationLayer"}};
  EXPECT_EQ(pluginsOf(r.params), expected);
  // Moved keys leave the costmap's namespace ...
  for (const char* key :
       {"obstacle_range", "raytrace_range", "inflation_radius", "cost_scaling_factor", "observation_sources", "scan"})
    EXPECT_EQ(r.params.find(key), nullptr) << key;
  // ... and arrive in the layers'.
  EXPECT_DOUBLE_EQ(numberAt(r.params, "obstacle_layer/obstacle_range"), 3.0);
  EXPECT_DOUBLE_EQ(numberAt(r.params, "obstacle_layer/raytrace_range"), 3.5);
  EXPECT_EQ(r.params.findPath("obstacle_layer/observation_sources")->asString(), "scan");
  EXPECT_EQ(r.params.findPath("obstacle_layer/scan/sensor_frame")->asString(), "base_scan");
  EXPECT_EQ(r.params.findPath("obstacle_layer/scan/data_type")->asString(), "LaserScan");
  EXPECT_DOUBLE_EQ(numberAt(r.params, "inflation_layer/inflation_radius"), 1.0);
  EXPECT_DOUBLE_EQ(numberAt(r.params, "inflation_layer/cost_scaling_factor"), 3.0);
  // The source finds obstacle_range / raytrace_range in the layer's namespace (searchParam).
  EXPECT_DOUBLE_EQ(numberAt(r.params, "obstacle_layer/scan/obstacle_range"), 3.0);
  EXPECT_DOUBLE_EQ(numberAt(r.params, "obstacle_layer/scan/raytrace_range"), 3.5);
  // costmap_2d's StaticLayer tracks unknown space unless told otherwise.
  ASSERT_NE(r.params.findPath("static_layer/track_unknown_space"), nullptr);
  EXPECT_TRUE(r.params.findPath("static_layer/track_unknown_space")->asBool());
  // The costmap's own keys stay.
  EXPECT_EQ(r.params.find("robot_base_frame")->asString(), "base_footprint");
  EXPECT_NE(r.params.find("footprint"), nullptr);
  EXPECT_TRUE(has(r.consumed, "static_map"));
  EXPECT_TRUE(has(r.consumed, "map_type"));
  EXPECT_TRUE(has(r.consumed, "scan"));
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings[0].find("\"plugins\" not provided"), std::string::npos);
  // The equivalent list, for the host to print (io::paramToYaml; test/io checks the text).
  ASSERT_TRUE(r.plugin_list.isMap());
  ASSERT_FALSE(r.plugin_list.entries().empty());
  EXPECT_EQ(r.plugin_list.entries().front().first, "plugins");
  const ParamValue* list = r.plugin_list.find("plugins");
  ASSERT_NE(list, nullptr);
  ASSERT_TRUE(list->isList());
  ASSERT_EQ(list->asList().size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k)
  {
    const ParamValue& entry = list->asList()[k];
    ASSERT_EQ(entry.entries().size(), 2u);
    EXPECT_EQ(entry.entries()[0].first, "name");
    EXPECT_EQ(entry.entries()[0].second.asString(), expected[k].first);
    EXPECT_EQ(entry.entries()[1].first, "type");
    EXPECT_EQ(entry.entries()[1].second.asString(), expected[k].second);
  }
  const ParamValue* inflation = r.plugin_list.find("inflation_layer");
  ASSERT_NE(inflation, nullptr);
  ASSERT_EQ(inflation->entries().size(), 2u);
  EXPECT_EQ(inflation->entries()[0].first, "cost_scaling_factor");
  EXPECT_EQ(inflation->entries()[0].second.type(), ParamValue::Type::Double);
  EXPECT_DOUBLE_EQ(inflation->entries()[0].second.asDouble(), 3.0);
  EXPECT_EQ(inflation->entries()[1].first, "inflation_radius");
  EXPECT_DOUBLE_EQ(inflation->entries()[1].second.asDouble(), 1.0);

  // What the layers then read: the values of TurtleBot3's files.
  const StaticConfig st = parseStaticConfig(ParamReader(*r.params.find("static_layer"), "s"), false);
  EXPECT_TRUE(st.track_unknown_space);
  const ObstacleConfig ob = parseObstacleConfig(ParamReader(*r.params.find("obstacle_layer"), "o"), false);
  ASSERT_EQ(ob.sources.size(), 1u);
  EXPECT_EQ(ob.sources[0].topic, "scan");
  EXPECT_EQ(ob.sources[0].sensor_frame, "base_scan");
  EXPECT_DOUBLE_EQ(ob.sources[0].obstacle_max_range, 3.0);
  EXPECT_DOUBLE_EQ(ob.sources[0].raytrace_max_range, 3.5);
  EXPECT_TRUE(ob.sources[0].clearing);
  const InflationConfig in = parseInflationConfig(ParamReader(*r.params.find("inflation_layer"), "i"));
  EXPECT_DOUBLE_EQ(in.inflation_radius, 1.0);
  EXPECT_DOUBLE_EQ(in.cost_scaling_factor, 3.0);
}

TEST(PreHydro, LocalCostmapWithoutStaticMapAndVoxel)
{
  ParamValue ns = ParamValue::makeMap();
  ns.set("static_map", B(false));
  ns.set("map_type", S("voxel"));
  ns.set("z_voxels", ParamValue::makeInt(4));
  ns.set("origin_z", D(0.1));
  ns.set("max_obstacle_height", D(0.6));
  ns.set("track_unknown_space", B(true));
  ns.set("map_topic", S("/other_map"));  // no static layer: stays, unused
  const CompatResult r = applyCostmap2dRules(ns);
  const std::vector<std::pair<std::string, std::string>> expected = {{"obstacle_layer", "costmap_2d::VoxelLayer"},
                                                                     {"inflation_layer", "costmap_2d::InflationLayer"}};
  EXPECT_EQ(pluginsOf(r.params), expected);
  EXPECT_EQ(r.params.findPath("obstacle_layer/z_voxels")->asInt(), 4);
  EXPECT_DOUBLE_EQ(numberAt(r.params, "obstacle_layer/origin_z"), 0.1);
  EXPECT_DOUBLE_EQ(numberAt(r.params, "obstacle_layer/max_obstacle_height"), 0.6);
  EXPECT_TRUE(r.params.findPath("obstacle_layer/track_unknown_space")->asBool());
  // The costmap reads its own track_unknown_space before costmap_2d moves it: it stays.
  EXPECT_TRUE(r.params.find("track_unknown_space")->asBool());
  EXPECT_EQ(r.params.find("z_voxels"), nullptr);
  EXPECT_EQ(r.params.find("static_layer"), nullptr);
  EXPECT_NE(r.params.find("map_topic"), nullptr);
}

TEST(PreHydro, MapTypeOtherThanVoxelIsAnObstacleLayerAndVoxelKeysStay)
{
  ParamValue ns = ParamValue::makeMap();
  ns.set("z_voxels", ParamValue::makeInt(4));
  const CompatResult r = applyCostmap2dRules(ns);
  EXPECT_EQ(pluginsOf(r.params)[0].second, "costmap_2d::ObstacleLayer");
  EXPECT_NE(r.params.find("z_voxels"), nullptr);
}

TEST(PluginList, OldKeysAreReportedUnused)
{
  ParamValue ns = ParamValue::makeMap();
  ns.set("plugins", ParamValue::makeList());
  ns.set("static_map", B(true));
  const CompatResult r = applyCostmap2dRules(ns);
  EXPECT_FALSE(r.converted_pre_hydro);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("\"static_map\" unused"), std::string::npos);
  EXPECT_TRUE(pluginsOf(r.params).empty());
}

TEST(PluginList, CopyParentParametersOnlyForCostmap2dTypes)
{
  for (const std::string type : {"costmap_2d::InflationLayer", "costmap_layers/InflationLayer"})
  {
    ParamValue ns = ParamValue::makeMap();
    ParamValue entry = ParamValue::makeMap();
    entry.set("name", S("inflation"));
    entry.set("type", S(type));
    ns.set("plugins", ParamValue::makeList({entry}));
    ns.set("inflation_radius", D(0.3));
    ParamValue layer = ParamValue::makeMap();
    layer.set("inflation_radius", D(1.0));
    ns.set("inflation", layer);
    const CompatResult r = applyCostmap2dRules(ns);
    if (type == "costmap_2d::InflationLayer")
    {
      // costmap_2d's move_parameter(..., false) overwrites the layer's value with the costmap's.
      EXPECT_DOUBLE_EQ(numberAt(r.params, "inflation/inflation_radius"), 0.3);
      ASSERT_EQ(r.warnings.size(), 1u);
      EXPECT_NE(r.warnings[0].find("replaces 'inflation/inflation_radius' 1"), std::string::npos) << r.warnings[0];
      EXPECT_TRUE(has(r.consumed, "inflation_radius"));
    }
    else
    {
      EXPECT_DOUBLE_EQ(numberAt(r.params, "inflation/inflation_radius"), 1.0);
      EXPECT_TRUE(r.warnings.empty());
      EXPECT_FALSE(has(r.consumed, "inflation_radius"));
    }
  }
}

TEST(PluginList, StaticLayerDefaultsFollowTheDialect)
{
  for (const std::string type :
       {"costmap_2d::StaticLayer", "nav2_costmap_2d::StaticLayer", "costmap_layers/StaticLayer"})
  {
    ParamValue ns = ParamValue::makeMap();
    ParamValue entry = ParamValue::makeMap();
    entry.set("name", S("map"));
    entry.set("type", S(type));
    ns.set("plugins", ParamValue::makeList({entry}));
    const CompatResult r = applyCostmap2dRules(ns);
    const ParamValue* t = r.params.findPath("map/track_unknown_space");
    if (type == "costmap_2d::StaticLayer")
    {
      ASSERT_NE(t, nullptr);
      EXPECT_TRUE(t->asBool());
    }
    else
    {
      EXPECT_EQ(t, nullptr) << type;  // follows the costmap's track_unknown_space, as Nav2's does
    }
  }
}

TEST(SearchParam, NearestNamespaceFirst)
{
  ParamValue a = ParamValue::makeMap(), b = ParamValue::makeMap(), c = ParamValue::makeMap();
  b.set("k", D(2.0));
  c.set("k", D(3.0));
  std::size_t at = 99;
  EXPECT_DOUBLE_EQ(searchParam({&a, &b, &c}, "k", &at)->asDouble(), 2.0);
  EXPECT_EQ(at, 1u);
  EXPECT_EQ(searchParam({&a}, "k"), nullptr);
  EXPECT_EQ(searchedKeys(),
            (std::vector<std::string>{"footprint", "robot_radius", "obstacle_range", "raytrace_range"}));
}

TEST(SearchParam, FootprintAndRadiusFromParents)
{
  ParamValue ns = ParamValue::makeMap();
  ns.set("plugins", ParamValue::makeList());
  std::vector<ParentNamespace> parents(2);
  parents[0].name = "/move_base";
  parents[0].values = ParamValue::makeMap();
  parents[0].values.set("robot_radius", D(0.2));
  parents[1].name = "/";
  parents[1].values = ParamValue::makeMap();
  parents[1].values.set("robot_radius", D(0.9));
  parents[1].values.set("footprint", S("[[1, 1], [-1, 1], [-1, -1]]"));
  const CompatResult r = applyCostmap2dRules(ns, parents);
  EXPECT_DOUBLE_EQ(numberAt(r.params, "robot_radius"), 0.2);
  EXPECT_EQ(r.params.find("footprint")->asString(), "[[1, 1], [-1, 1], [-1, -1]]");
  const CostmapConfig cfg = parseCostmapConfig(r.params);
  EXPECT_EQ(cfg.footprint.footprint.size(), 3u);
  EXPECT_DOUBLE_EQ(cfg.footprint.robot_radius, 0.2);

  // A value in the costmap's own namespace wins over the parents'.
  ns.set("robot_radius", D(0.5));
  EXPECT_DOUBLE_EQ(numberAt(applyCostmap2dRules(ns, parents).params, "robot_radius"), 0.5);
}

TEST(SearchParam, ObstacleRangeFromLayerCostmapOrParents)
{
  ParamValue ns = ParamValue::makeMap();
  ParamValue entry = ParamValue::makeMap();
  entry.set("name", S("obstacles"));
  entry.set("type", S("costmap_2d::VoxelLayer"));  // VoxelLayer has no copyParentParameters for these
  ns.set("plugins", ParamValue::makeList({entry}));
  ns.set("raytrace_range", D(4.0));
  ParamValue layer = ParamValue::makeMap();
  layer.set("observation_sources", S("a b c"));
  layer.set("obstacle_range", D(1.5));
  ParamValue b = ParamValue::makeMap();
  b.set("obstacle_range", D(0.7));
  layer.set("b", b);
  ParamValue c = ParamValue::makeMap();
  c.set("obstacle_max_range", D(0.4));  // Nav2's name in the source: searchParam is not needed
  layer.set("c", c);
  ns.set("obstacles", layer);
  std::vector<ParentNamespace> parents(1);
  parents[0].name = "/move_base";
  parents[0].values = ParamValue::makeMap();
  parents[0].values.set("obstacle_range", D(9.0));
  const CompatResult r = applyCostmap2dRules(ns, parents);
  EXPECT_DOUBLE_EQ(numberAt(r.params, "obstacles/a/obstacle_range"), 1.5);  // the layer's
  EXPECT_DOUBLE_EQ(numberAt(r.params, "obstacles/a/raytrace_range"), 4.0);  // the costmap's
  EXPECT_DOUBLE_EQ(numberAt(r.params, "obstacles/b/obstacle_range"), 0.7);  // its own
  EXPECT_EQ(r.params.findPath("obstacles/c/obstacle_range"), nullptr);
  const ObstacleConfig ob = parseObstacleConfig(ParamReader(*r.params.find("obstacles"), "o"), false);
  ASSERT_EQ(ob.sources.size(), 3u);
  EXPECT_DOUBLE_EQ(ob.sources[0].obstacle_max_range, 1.5);
  EXPECT_DOUBLE_EQ(ob.sources[0].raytrace_max_range, 4.0);
  EXPECT_DOUBLE_EQ(ob.sources[2].obstacle_max_range, 0.4);
  EXPECT_TRUE(has(r.consumed, "raytrace_range"));
  EXPECT_TRUE(has(r.layer_consumed.at("obstacles"), "obstacle_range"));

  // Without any value up the chain but a parent's, the parent's applies.
  ns.erase("raytrace_range");
  ns.findMutable("obstacles")->erase("obstacle_range");
  const CompatResult r2 = applyCostmap2dRules(ns, parents);
  EXPECT_DOUBLE_EQ(numberAt(r2.params, "obstacles/a/obstacle_range"), 9.0);
  EXPECT_EQ(r2.params.findPath("obstacles/a/raytrace_range"), nullptr);
}

TEST(LiftOwnNamespace, MergesTheNestedSectionOverTheCommonKeys)
{
  ParamValue ns = ParamValue::makeMap();
  ns.set("inflation_radius", D(1.0));
  ns.set("global_frame", S("odom"));
  ParamValue nested = ParamValue::makeMap();
  nested.set("global_frame", S("map"));
  nested.set("static_map", B(true));
  ns.set("global_costmap", nested);
  EXPECT_TRUE(liftOwnNamespace(ns, "global_costmap"));
  EXPECT_EQ(ns.find("global_costmap"), nullptr);
  EXPECT_EQ(ns.find("global_frame")->asString(), "map");
  EXPECT_TRUE(ns.find("static_map")->asBool());
  EXPECT_DOUBLE_EQ(ns.find("inflation_radius")->asDouble(), 1.0);
  EXPECT_FALSE(liftOwnNamespace(ns, "global_costmap"));

  // A plugin of that name is a plugin, not a section to lift.
  ParamValue p = ParamValue::makeMap();
  p.set("plugins", ParamValue::makeList({S("local_costmap")}));
  p.set("local_costmap", ParamValue::makeMap());
  EXPECT_FALSE(liftOwnNamespace(p, "local_costmap"));
}

TEST(UnknownKeys, EditDistanceAndNearestName)
{
  EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(editDistance("", "abc"), 3u);
  EXPECT_EQ(editDistance("same", "same"), 0u);
  EXPECT_EQ(nearestName("inflaton_radius", {"cost_scaling_factor", "inflation_radius", "enabled"}), "inflation_radius");
  EXPECT_EQ(nearestName("robot_raduis", {"robot_radius", "footprint"}), "robot_radius");
  EXPECT_EQ(nearestName("completely_else", {"robot_radius", "footprint"}), "");
}

TEST(UnknownKeys, FoundWithTheirNearestName)
{
  ParamValue ns = ParamValue::makeMap();
  ns.set("inflaton_radius", D(0.3));
  ns.set("cost_scaling_factor", D(2.0));
  ns.set("plugin", S("costmap_2d::InflationLayer"));
  ParamReadLog log;
  parseInflationConfig(ParamReader(ns, "inflation"));
  const auto unknown = unknownKeys(ns, log, "InflationLayer", {"plugin"});
  ASSERT_EQ(unknown.size(), 1u);
  EXPECT_EQ(unknown[0].path, "inflaton_radius");
  EXPECT_EQ(unknown[0].suggestion, "inflation_radius");
  EXPECT_EQ(describeUnknownKey(unknown[0], "/move_base/global_costmap/inflation"),
            "parameter 'inflaton_radius' in /move_base/global_costmap/inflation is not a parameter of "
            "costmap_layers and is ignored (did you mean `inflation_radius`?)");
}

namespace
{
/// The unknown keys of an obstacle layer with one source "scan": layer_extra in the layer's namespace,
/// source_extra in the source's, read by parseObstacleConfig and walked in scope.
std::vector<UnknownKey> obstacleUnknownKeys(const std::vector<std::pair<std::string, ParamValue>>& layer_extra,
                                            const std::vector<std::pair<std::string, ParamValue>>& source_extra,
                                            const std::string& scope)
{
  ParamValue layer = ParamValue::makeMap();
  layer.set("observation_sources", S("scan"));
  for (const auto& [k, v] : layer_extra)
    layer.set(k, v);
  ParamValue scan = ParamValue::makeMap();
  for (const auto& [k, v] : source_extra)
    scan.set(k, v);
  layer.set("scan", scan);
  ParamReadLog log;
  parseObstacleConfig(ParamReader(layer, "obstacles"), false);
  return unknownKeys(layer, log, scope);
}
}  // namespace

TEST(UnknownKeys, SourceNamespacesAreWalkedAndKnownForeignKeysExplained)
{
  const auto unknown = obstacleUnknownKeys({{"transform_tolerance", D(0.2)}},
                                           {{"data_type", S("LaserScan")}, {"topc", S("scan")}}, "ObstacleLayer");
  ASSERT_EQ(unknown.size(), 2u);
  EXPECT_EQ(unknown[0].path, "transform_tolerance");
  EXPECT_NE(unknown[0].known_elsewhere.find("0.2 s"), std::string::npos);
  EXPECT_EQ(unknown[1].path, "scan/topc");
  EXPECT_EQ(unknown[1].suggestion, "topic");
}

// Keys of Nav2's own params file (nav2_bringup/params/nav2_params.yaml and Nav2's layers) that only mean
// something in ROS 2: each is said to be ignored, with the reason, not taken for a misspelling.
TEST(UnknownKeys, Nav2sRos2OnlyKeysAreExplained)
{
  const auto unknown =
      obstacleUnknownKeys({{"tf_filter_tolerance", D(0.35)}, {"allow_parameter_qos_overrides", B(true)}},
                          {{"data_type", S("PointCloud2")}, {"transport_type", S("raw")}}, "VoxelLayer");
  ASSERT_EQ(unknown.size(), 3u);
  for (const auto& u : unknown)
  {
    EXPECT_FALSE(u.known_elsewhere.empty()) << u.path;
    EXPECT_TRUE(u.suggestion.empty()) << u.path;
  }
  EXPECT_EQ(describeUnknownKey(unknown[0], "/c/voxel_layer"),
            "parameter 'tf_filter_tolerance' in /c/voxel_layer is ignored: Nav2's tf message filter tolerance; here "
            "readings wait for tf in a bounded queue and the costmap's transform_tolerance applies to the robot pose");
  EXPECT_EQ(unknown[2].path, "scan/transport_type");

  ParamValue ns = ParamValue::makeMap();
  ns.set("introspection_mode", S("disabled"));
  ns.set("plugins", ParamValue::makeList());
  ParamReadLog costmap_log;
  parseCostmapConfig(ns);
  parsePluginLists(ns);
  const auto costmap_unknown = unknownKeys(ns, costmap_log, "costmap");
  ASSERT_EQ(costmap_unknown.size(), 1u);
  EXPECT_NE(costmap_unknown[0].known_elsewhere.find("introspection"), std::string::npos);
}

TEST(UnknownKeys, CostmapLevelWithSkipsAndNamespaces)
{
  ParamValue ns = ParamValue::makeMap();
  ns.set("robot_raduis", D(0.2));
  ns.set("footprint_topic", S("fp"));
  ns.set("static_map", B(true));
  ns.set("plugins", ParamValue::makeList());
  ns.set("leftover_layer", ParamValue::makeMap());
  ns.set("my_layer", ParamValue::makeMap());
  ParamReadLog log;
  parseCostmapConfig(ns);
  parsePluginLists(ns);
  const auto unknown = unknownKeys(ns, log, "costmap", {"static_map"}, {"my_layer"});
  ASSERT_EQ(unknown.size(), 3u);
  EXPECT_EQ(unknown[0].path, "robot_raduis");
  EXPECT_EQ(unknown[0].suggestion, "robot_radius");
  EXPECT_EQ(unknown[1].path, "footprint_topic");
  EXPECT_FALSE(unknown[1].known_elsewhere.empty());
  EXPECT_EQ(unknown[2].path, "leftover_layer");
  EXPECT_TRUE(unknown[2].is_namespace);
  EXPECT_EQ(describeUnknownKey(unknown[2], "/c", {"my_layer"}),
            "namespace 'leftover_layer' in /c names no plugin of this costmap (plugins: my_layer): its parameters "
            "are not used");
}

TEST(UnknownKeys, LogsNestAndStop)
{
  ParamValue ns = ParamValue::makeMap();
  ns.set("a", D(1.0));
  {
    ParamReadLog outer;
    {
      ParamReadLog inner;
      ns.find("a");
      EXPECT_TRUE(inner.asked(&ns, "a"));
    }
    EXPECT_FALSE(outer.asked(&ns, "a"));
    ns.find("b");
    EXPECT_TRUE(outer.asked(&ns, "b"));
    EXPECT_EQ(ParamReadLog::current(), &outer);
  }
  EXPECT_EQ(ParamReadLog::current(), nullptr);
}

// A layer hosted in move_base in the place of one of costmap_2d's: costmap_2d copies costmap-level keys
// into its own types only, so the host applies the rules of the role itself. The values expected are
// what costmap_2d's Costmap2DROS::copyParentParameters and ObstacleLayer's searchParam give its own
// layers (costmap_2d_ros.cpp, obstacle_layer.cpp).
TEST(HostedRole, EachClassTakesTheRulesOfTheCostmap2dTypeItReplaces)
{
  EXPECT_EQ(costmap2dRole("InflationLayer"), "costmap_2d::InflationLayer");
  EXPECT_EQ(costmap2dRole("StaticLayer"), "costmap_2d::StaticLayer");
  EXPECT_EQ(costmap2dRole("ObstacleLayer"), "costmap_2d::ObstacleLayer");
  EXPECT_EQ(costmap2dRole("VoxelLayer"), "costmap_2d::VoxelLayer");
  EXPECT_EQ(costmap2dRole("RangeSensorLayer"), "range_sensor_layer::RangeSensorLayer");
  for (const char* none : {"KeepoutFilter", "SpeedFilter", "GradientLayer", "LanesFilter", ""})
    EXPECT_EQ(costmap2dRole(none), "") << none;
}

TEST(HostedRole, CostmapLevelKeysReachTheHostedLayer)
{
  // move_base/local_costmap as a common-params file leaves it: ranges and radius at the costmap level.
  ParamValue ns = ParamValue::makeMap();
  ns.set("inflation_radius", D(1.0));
  ns.set("cost_scaling_factor", D(3.0));
  ns.set("obstacle_range", D(5.0));
  ns.set("raytrace_range", D(6.0));
  ns.set("track_unknown_space", B(true));
  ns.set("max_obstacle_height", D(0.6));
  ParamValue obstacles = ParamValue::makeMap();
  obstacles.set("observation_sources", S("scan bump"));
  obstacles.set("obstacle_range", D(4.0));  // replaced by the costmap's 5.0 (copyParentParameters)
  ParamValue scan = ParamValue::makeMap();
  scan.set("sensor_frame", S("/base_scan"));
  obstacles.set("scan", scan);
  ParamValue bump = ParamValue::makeMap();
  bump.set("raytrace_range", D(0.5));
  obstacles.set("bump", bump);
  ns.set("obstacles", obstacles);
  ParamValue inflation = ParamValue::makeMap();
  inflation.set("inflation_radius", D(0.3));
  ns.set("inflation", inflation);

  const CompatResult inf = applyCostmap2dRulesAsRole(ns, "inflation", "costmap_2d::InflationLayer");
  EXPECT_DOUBLE_EQ(numberAt(inf.params, "inflation/inflation_radius"), 1.0);
  EXPECT_DOUBLE_EQ(numberAt(inf.params, "inflation/cost_scaling_factor"), 3.0);
  ASSERT_EQ(inf.warnings.size(), 1u);  // the layer's 0.3 replaced: said, naming both values
  EXPECT_NE(inf.warnings[0].find("'inflation_radius' 1"), std::string::npos) << inf.warnings[0];
  EXPECT_NE(inf.warnings[0].find("'inflation/inflation_radius' 0.3"), std::string::npos) << inf.warnings[0];
  EXPECT_NE(inf.warnings[0].find("costmap_2d::InflationLayer"), std::string::npos) << inf.warnings[0];
  const InflationConfig ic = parseInflationConfig(ParamReader(*inf.params.find("inflation"), "i"));
  EXPECT_DOUBLE_EQ(ic.inflation_radius, 1.0);
  EXPECT_DOUBLE_EQ(ic.cost_scaling_factor, 3.0);

  const CompatResult obs = applyCostmap2dRulesAsRole(ns, "obstacles", "costmap_2d::ObstacleLayer");
  EXPECT_DOUBLE_EQ(numberAt(obs.params, "obstacles/max_obstacle_height"), 0.6);
  EXPECT_TRUE(obs.params.findPath("obstacles/track_unknown_space")->asBool());
  EXPECT_DOUBLE_EQ(numberAt(obs.params, "obstacles/scan/obstacle_range"), 5.0);  // the layer's, after the copy
  EXPECT_DOUBLE_EQ(numberAt(obs.params, "obstacles/scan/raytrace_range"), 6.0);
  EXPECT_DOUBLE_EQ(numberAt(obs.params, "obstacles/bump/raytrace_range"), 0.5);  // its own
  EXPECT_EQ(obs.params.findPath("obstacles/scan/sensor_frame")->asString(), "base_scan");
  EXPECT_TRUE(has(obs.layer_consumed.at("obstacles"), "obstacle_range"));
  const ObstacleConfig oc = parseObstacleConfig(ParamReader(*obs.params.find("obstacles"), "o"), false);
  ASSERT_EQ(oc.sources.size(), 2u);
  EXPECT_DOUBLE_EQ(oc.sources[0].obstacle_max_range, 5.0);
  EXPECT_DOUBLE_EQ(oc.sources[0].raytrace_max_range, 6.0);
  EXPECT_DOUBLE_EQ(oc.sources[1].obstacle_max_range, 5.0);
  EXPECT_DOUBLE_EQ(oc.sources[1].raytrace_max_range, 0.5);

  // costmap_2d's VoxelLayer rule moves the voxel keys only: the ranges come by searchParam, the
  // layer's 4.0 first.
  const CompatResult vox = applyCostmap2dRulesAsRole(ns, "obstacles", "costmap_2d::VoxelLayer");
  EXPECT_DOUBLE_EQ(numberAt(vox.params, "obstacles/scan/obstacle_range"), 4.0);
  EXPECT_DOUBLE_EQ(numberAt(vox.params, "obstacles/scan/raytrace_range"), 6.0);
  EXPECT_EQ(vox.params.findPath("obstacles/max_obstacle_height"), nullptr);

  // The static layer: costmap_2d's default track_unknown_space true, unless the costmap sets it.
  ParamValue plain = ParamValue::makeMap();
  const CompatResult st = applyCostmap2dRulesAsRole(plain, "map", "costmap_2d::StaticLayer");
  EXPECT_TRUE(st.params.findPath("map/track_unknown_space")->asBool());
  plain.set("track_unknown_space", B(false));
  EXPECT_FALSE(applyCostmap2dRulesAsRole(plain, "map", "costmap_2d::StaticLayer")
                   .params.findPath("map/track_unknown_space")
                   ->asBool());

  // No role (a filter): the namespace as written, nothing said.
  const CompatResult none = applyCostmap2dRulesAsRole(ns, "inflation", "");
  EXPECT_DOUBLE_EQ(numberAt(none.params, "inflation/inflation_radius"), 0.3);
  EXPECT_TRUE(none.warnings.empty());
  EXPECT_TRUE(none.notes.empty());
}
