// PluginContainerLayer: Nav2's plugin_container_tests (nav2_costmap_2d/test/integration) with their
// inputs (costmap_2d's ten-by-ten map, 1 m cells, a square footprint of half side 1 m, inflation radius
// 1 m with cost_scaling_factor 1) and expected counts, on the same builder the node and the tool use
// (loadPlugins with a factory by type name). Nav2's tests add the plugins by hand (addPlugin); here the
// containers read their `plugins` lists, as a user's file gives them. Expected values are Nav2's; the
// inscribed counts were checked by hand: 28 cells are edge neighbours of the map's 20 walls (a cell at
// 1 m from a wall is inscribed with the inscribed radius 1 m, a diagonal one at 1.41 m is beyond the
// inflation radius).
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "costmap_layers/core/config/config_compat.hpp"
#include "costmap_layers/core/config/plugin_types.hpp"
#include "costmap_layers/core/config/unknown_keys.hpp"
#include "costmap_layers/core/costmap/costmap_builder.hpp"
#include "costmap_layers/core/costmap/costmap_clearing.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/layers/inflation_layer.hpp"
#include "costmap_layers/core/layers/obstacle_layer.hpp"
#include "costmap_layers/core/layers/plugin_container_layer.hpp"
#include "costmap_layers/core/layers/static_layer.hpp"
#include "fake_context.hpp"
#include "sensor_test_helpers.hpp"
#include "ten_by_ten.hpp"

using namespace costmap_layers;
using namespace costmap_layers_test;

namespace
{
constexpr double kSensorZ = 0.5;

/// The factory by type name, as pluginlib is for the node (the same alias table first).
std::shared_ptr<Layer> makeByType(const std::string& written)
{
  const std::string type = resolvePluginType(written);
  if (type == "costmap_layers/StaticLayer") return std::make_shared<StaticLayer>();
  if (type == "costmap_layers/ObstacleLayer") return std::make_shared<ObstacleLayer>();
  if (type == "costmap_layers/InflationLayer") return std::make_shared<InflationLayer>();
  if (type == "costmap_layers/PluginContainerLayer") return std::make_shared<PluginContainerLayer>();
  throw std::runtime_error("unknown plugin type '" + written + "'");
}

ParamValue typed(const char* type, std::initializer_list<std::pair<const char*, ParamValue>> extra = {})
{
  ParamValue p = paramMap({{"plugin", S(type)}});
  for (const auto& it : extra)
    p.set(it.first, it.second);
  return p;
}

ParamValue names(std::initializer_list<const char*> list)
{
  ParamValue l = ParamValue::makeList();
  for (const char* n : list)
    l.push(S(n));
  return l;
}

/// An obstacle layer reading one cloud source "cloud" (every range generous).
ParamValue obstacles()
{
  ParamValue p = typed("costmap_layers/ObstacleLayer", {{"observation_sources", S("cloud")}});
  p.set("cloud", paramMap({{"data_type", S("PointCloud2")},
                           {"marking", B(true)},
                           {"clearing", B(true)},
                           {"obstacle_max_range", D(100.0)},
                           {"raytrace_max_range", D(100.0)}}));
  return p;
}

/// Nav2's test inflation: radius 1 m, cost_scaling_factor 1.
ParamValue inflation(double radius = 1.0, double factor = 1.0)
{
  return typed("costmap_layers/InflationLayer", {{"inflation_radius", D(radius)}, {"cost_scaling_factor", D(factor)}});
}

ParamValue container(std::initializer_list<std::pair<const char*, ParamValue>> plugins,
                     std::initializer_list<std::pair<const char*, ParamValue>> extra = {})
{
  ParamValue p = typed("costmap_layers/PluginContainerLayer");
  ParamValue list = ParamValue::makeList();
  for (const auto& it : plugins)
  {
    list.push(S(it.first));
    p.set(it.first, it.second);
  }
  p.set("plugins", list);
  for (const auto& it : extra)
    p.set(it.first, it.second);
  return p;
}

ParamValue costmapOf(std::initializer_list<std::pair<const char*, ParamValue>> plugins)
{
  ParamValue ns = ParamValue::makeMap();
  ParamValue list = ParamValue::makeList();
  for (const auto& it : plugins)
  {
    list.push(S(it.first));
    ns.set(it.first, it.second);
  }
  ns.set("plugins", list);
  return ns;
}

Footprint square(double half)
{
  return {{-half, -half}, {half, -half}, {half, half}, {-half, half}};
}

int count(const Costmap2D& c, uint8_t v)
{
  int n = 0;
  for (std::size_t k = 0; k < c.cellCount(); ++k)
    n += c.data()[k] == v;
  return n;
}

/// A 10 x 10 costmap of 1 m cells built from a namespace, each layer (nested ones too) bound to its
/// own FakeContext; every static layer gets the ten-by-ten map.
struct Rig
{
  /// read_from: the namespace to read instead of costmap_ns (one a ParamReadLog watches).
  explicit Rig(ParamValue costmap_ns, bool track_unknown = false, const ParamValue* read_from = nullptr)
      : ns(std::move(costmap_ns)), lc("map", false, track_unknown)
  {
    const ParamValue& read = read_from != nullptr ? *read_from : ns;
    lc.resizeMap(10, 10, 1.0, 0.0, 0.0);
    loadPlugins(lc, parsePluginLists(read), makeByType,
                [this, &read](const PluginSpec& spec)
                {
                  const ParamValue* p = pluginParams(read, spec.name);
                  auto c = std::make_shared<FakeContext>(p != nullptr ? *p : ParamValue::makeMap());
                  contexts[spec.name] = c;
                  return c;
                });
    for (const auto& [name, c] : contexts)
    {
      const auto layer = lc.findLayer(name);
      if (!layer) throw std::logic_error("no layer " + name);
      c->bind(*layer);
      if (dynamic_cast<StaticLayer*>(layer.get())) c->publishGrid(GridKind::Map, tenByTen());
    }
    lc.setFootprint(square(1.0));
  }
  /// A point at (x, y) seen by the obstacle layer `name` from a sensor at the origin.
  void observe(const std::string& name, double x, double y)
  {
    ASSERT_EQ(
        contexts.at(name)->publishCloud("cloud", makeCloud({{x, y, 0.0}}, false, false, 0), poseAt(0.0, 0.0, kSensorZ)),
        1);
  }
  void update() { lc.updateMap(0, 0, 0); }
  const Costmap2D& master() const { return lc.getCostmap(); }
  template <class T>
  std::shared_ptr<T> layer(const std::string& name) const
  {
    return std::dynamic_pointer_cast<T>(lc.findLayer(name));
  }

  ParamValue ns;
  LayeredCostmap lc;
  std::map<std::string, std::shared_ptr<FakeContext>> contexts;
};

/// The message loading `ns` fails with ("" when it loads).
std::string loadError(const ParamValue& ns)
{
  return thrownMessage(
      [&]
      {
        Rig rig(ns);
        (void)rig;
      });
}
}  // namespace

// Nav2: testObstacleLayers. One obstacle each in two containers: both reach the master.
TEST(PluginContainerLayer, ObstacleLayersInTwoContainers)
{
  Rig rig(costmapOf({{"pclayer_a", container({{"obstacles", obstacles()}})},
                     {"pclayer_b", container({{"obstacles", obstacles()}})}}));
  rig.observe("pclayer_a/obstacles", 5.0, 5.0);
  rig.observe("pclayer_b/obstacles", 3.0, 8.0);
  rig.update();
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 2);
  EXPECT_EQ(rig.master().getCost(5, 5), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.master().getCost(3, 8), LETHAL_OBSTACLE);
}

// Nav2: testObstacleAndStaticLayers. The map's 20 walls and one obstacle.
TEST(PluginContainerLayer, ObstacleAndStaticLayers)
{
  Rig rig(costmapOf({{"pclayer_a", container({{"static", typed("costmap_layers/StaticLayer")}})},
                     {"pclayer_b", container({{"obstacles", obstacles()}})}}));
  rig.observe("pclayer_b/obstacles", 3.0, 8.0);
  rig.update();
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 21);
}

// Nav2: testDifferentInflationLayers. Only the obstacle is inflated (its container holds the
// inflation): its 4 edge neighbours, none a wall.
TEST(PluginContainerLayer, InflationInTheObstaclesContainerInflatesTheObstacleOnly)
{
  Rig rig(costmapOf({{"pclayer_a", container({{"static", typed("costmap_layers/StaticLayer")}})},
                     {"pclayer_b", container({{"obstacles", obstacles()}, {"inflation", inflation()}})}}));
  rig.observe("pclayer_b/obstacles", 5.0, 4.0);
  rig.update();
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 21);
  EXPECT_EQ(count(rig.master(), INSCRIBED_INFLATED_OBSTACLE), 4);
  for (const auto& [x, y] : std::vector<std::pair<unsigned, unsigned>>{{4, 4}, {6, 4}, {5, 3}, {5, 5}})
    EXPECT_EQ(rig.master().getCost(x, y), INSCRIBED_INFLATED_OBSTACLE) << x << "," << y;
}

// Nav2: testDifferentInflationLayers2. Only the walls are inflated: 28 cells; the obstacle at (9, 9)
// is not.
TEST(PluginContainerLayer, InflationInTheStaticContainerInflatesTheWallsOnly)
{
  Rig rig(costmapOf(
      {{"pclayer_a", container({{"static", typed("costmap_layers/StaticLayer")}, {"inflation", inflation()}})},
       {"pclayer_b", container({{"obstacles", obstacles()}})}}));
  rig.observe("pclayer_b/obstacles", 9.0, 9.0);
  rig.update();
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 21);
  EXPECT_EQ(count(rig.master(), INSCRIBED_INFLATED_OBSTACLE), 28);
  EXPECT_NE(rig.master().getCost(8, 9), INSCRIBED_INFLATED_OBSTACLE);
}

// Nav2: testResetting. A container is not current after reset() until its next update; its plugins
// are reset with it (the obstacle is gone). Nav2 also expects the static and inflation plugins to say
// "not current" after their reset: this package's keep their map and radii over a reset and stay
// current (StaticLayer::reset redraws the map it has).
TEST(PluginContainerLayer, ResetResetsThePluginsAndIsNotCurrentUntilTheNextUpdate)
{
  Rig rig(costmapOf(
      {{"pclayer_a", container({{"static", typed("costmap_layers/StaticLayer")}, {"inflation", inflation()}})},
       {"pclayer_b", container({{"obstacles", obstacles()}, {"inflation", inflation()}})}}));
  rig.observe("pclayer_b/obstacles", 9.0, 9.0);
  rig.update();
  const auto a = rig.layer<PluginContainerLayer>("pclayer_a");
  const auto b = rig.layer<PluginContainerLayer>("pclayer_b");
  ASSERT_TRUE(a && b);
  EXPECT_TRUE(a->isCurrent());
  EXPECT_TRUE(b->isCurrent());
  EXPECT_EQ(rig.master().getCost(9, 9), LETHAL_OBSTACLE);
  a->reset();
  b->reset();
  EXPECT_FALSE(a->isCurrent());
  EXPECT_FALSE(b->isCurrent());
  EXPECT_FALSE(rig.lc.isCurrent());
  EXPECT_EQ(rig.layer<ObstacleLayer>("pclayer_b/obstacles")->costmap().getCost(9, 9), FREE_SPACE);
  rig.lc.requestFullUpdate();
  rig.update();
  EXPECT_TRUE(a->isCurrent());
  EXPECT_TRUE(b->isCurrent());
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 20);
}

// Nav2: testClearing. 21 walls and obstacle, 28 + 1 inscribed ((8, 9) by the obstacles' own
// inflation). Clearing both containers clears the clearable obstacle layer's cells and leaves the
// static layer's. (Nav2's test names pclayer_b's inflation "pclayer_a.inflation", a slip that reads
// the other container's parameters; here it is pclayer_b/inflation with the same values.)
TEST(PluginContainerLayer, ClearingClearsTheClearablePluginsOnly)
{
  Rig rig(costmapOf(
      {{"pclayer_a", container({{"static", typed("costmap_layers/StaticLayer")}, {"inflation", inflation()}})},
       {"pclayer_b", container({{"obstacles", obstacles()}, {"inflation", inflation()}})}}));
  rig.observe("pclayer_b/obstacles", 9.0, 9.0);
  rig.update();
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 21);
  EXPECT_EQ(count(rig.master(), INSCRIBED_INFLATED_OBSTACLE), 29);
  const auto obstacle_layer = rig.layer<ObstacleLayer>("pclayer_b/obstacles");
  ASSERT_EQ(obstacle_layer->costmap().getCost(9, 9), LETHAL_OBSTACLE);
  for (const char* name : {"pclayer_a", "pclayer_b"})
    rig.layer<PluginContainerLayer>(name)->clearCells(0, 0, 10, 10, NO_INFORMATION);
  EXPECT_EQ(rig.layer<StaticLayer>("pclayer_a/static")->costmap().getCost(9, 0), LETHAL_OBSTACLE);
  EXPECT_EQ(obstacle_layer->costmap().getCost(9, 9), NO_INFORMATION);
}

// Nav2: testOverwriteCombinationMethods. pclayer_b overwrites: its grid is known everywhere (the
// obstacle layer draws free space), so only its obstacle and that one's 2 inscribed cells remain.
TEST(PluginContainerLayer, OverwriteCombination)
{
  Rig rig(costmapOf(
      {{"pclayer_a", container({{"static", typed("costmap_layers/StaticLayer")}, {"inflation", inflation()}})},
       {"pclayer_b",
        container({{"obstacles", obstacles()}, {"inflation", inflation()}}, {{"combination_method", I(0)}})}}));
  rig.observe("pclayer_b/obstacles", 9.0, 9.0);
  rig.update();
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 1);
  EXPECT_EQ(count(rig.master(), INSCRIBED_INFLATED_OBSTACLE), 2);
}

// Nav2: testWithoutUnknownOverwriteCombinationMethods. A master that tracks unknown space stays unknown
// under two containers merging with 2.
TEST(PluginContainerLayer, MaxWithoutUnknownOverwriteCombination)
{
  Rig rig(
      costmapOf({{"pclayer_a", container({{"static", typed("costmap_layers/StaticLayer")}, {"inflation", inflation()}},
                                         {{"combination_method", I(2)}})},
                 {"pclayer_b", container({{"obstacles", obstacles()}, {"inflation", inflation()}},
                                         {{"combination_method", I(2)}})}}),
      true);
  rig.observe("pclayer_b/obstacles", 9.0, 9.0);
  rig.update();
  EXPECT_EQ(count(rig.master(), NO_INFORMATION), 100);
}

// Nav2: testClearable. Clearable when any plugin is.
TEST(PluginContainerLayer, ClearableWhenAnyPluginIs)
{
  Rig rig(costmapOf(
      {{"pclayer_a", container({{"static", typed("costmap_layers/StaticLayer")}, {"obstacles", obstacles()}})},
       {"pclayer_b", container({{"obstacles", typed("costmap_layers/StaticLayer")}})}}));
  EXPECT_TRUE(rig.layer<PluginContainerLayer>("pclayer_a")->isClearable());
  EXPECT_FALSE(rig.layer<PluginContainerLayer>("pclayer_b")->isClearable());
  // The costmap's clear resets the clearable container only.
  EXPECT_EQ(resetClearableLayers(rig.lc), 1);
}

// Nav2: testDynParamsSetPluginContainerLayer, as this package's run-time reconfiguration: combination_method
// and enabled change; a value Nav2 would replace by 1 is refused and the last good one kept. Nav2's
// own type names load the container and its plugins.
TEST(PluginContainerLayer, ReconfiguresCombinationMethodAndEnabled)
{
  ParamValue a = container({{"obstacle_layer", obstacles()}, {"inflation_layer", inflation()}});
  a.set("plugin", S("nav2_costmap_2d::PluginContainerLayer"));
  a.findMutable("obstacle_layer")->set("plugin", S("nav2_costmap_2d::ObstacleLayer"));
  a.findMutable("inflation_layer")->set("plugin", S("nav2_costmap_2d::InflationLayer"));
  ParamValue b = container({{"static_layer", typed("nav2_costmap_2d::StaticLayer")}, {"inflation_layer", inflation()}});
  b.set("plugin", S("nav2_costmap_2d::PluginContainerLayer"));
  Rig rig(costmapOf({{"plugin_container_layer_a", a}, {"plugin_container_layer_b", b}}));
  const auto la = rig.layer<PluginContainerLayer>("plugin_container_layer_a");
  const auto lb = rig.layer<PluginContainerLayer>("plugin_container_layer_b");
  ASSERT_TRUE(la && lb);
  EXPECT_EQ(la->config().combination_method, ContainerCombination::Max);  // Nav2's default, 1
  ParamValue pa = a, pb = b;
  pa.set("combination_method", I(2));
  pa.set("enabled", B(false));
  pb.set("combination_method", I(1));
  pb.set("enabled", B(true));
  la->reconfigure(pa);
  lb->reconfigure(pb);
  EXPECT_EQ(la->config().combination_method, ContainerCombination::MaxWithoutUnknownOverwrite);
  EXPECT_EQ(lb->config().combination_method, ContainerCombination::Max);
  EXPECT_FALSE(la->enabled());
  EXPECT_TRUE(lb->enabled());
  std::vector<std::string> tunable;
  for (const auto& spec : la->tunableParameters(pa))
    tunable.push_back(spec.name);
  EXPECT_EQ(tunable, (std::vector<std::string>{"enabled", "combination_method"}));
  for (const int64_t bad : {3, -1})
  {
    pa.set("combination_method", I(bad));
    const std::string what = thrownMessage([&] { la->reconfigure(pa); });
    EXPECT_NE(what.find("combination_method"), std::string::npos) << what;
    EXPECT_NE(what.find(std::to_string(bad)), std::string::npos) << what;
    EXPECT_EQ(la->config().combination_method, ContainerCombination::MaxWithoutUnknownOverwrite);
  }
}

// The use: a container of [static, inflation] gives the same master as the same two layers in
// the costmap's own list (inflation radius 3 m, so that the costs fall off over several cells).
TEST(PluginContainerLayer, StaticAndInflationInAContainerGiveTheSameMasterAsAtTheTop)
{
  const ParamValue wide = inflation(3.0, 2.0);
  Rig top(costmapOf({{"static", typed("costmap_layers/StaticLayer")}, {"inflation", wide}}));
  Rig held(costmapOf({{"group", container({{"static", typed("costmap_layers/StaticLayer")}, {"inflation", wide}})}}));
  top.update();
  held.update();
  int ramp = 0;
  for (unsigned y = 0; y < 10; ++y)
    for (unsigned x = 0; x < 10; ++x)
    {
      EXPECT_EQ(held.master().getCost(x, y), top.master().getCost(x, y)) << x << "," << y;
      const uint8_t c = top.master().getCost(x, y);
      ramp += c > FREE_SPACE && c < INSCRIBED_INFLATED_OBSTACLE;
    }
  EXPECT_GT(ramp, 10);  // the comparison covers falling costs, not only walls
  EXPECT_EQ(count(held.master(), LETHAL_OBSTACLE), 20);
}

// The container draws its plugins on a clean window each cycle: an obstacle the obstacle layer clears
// leaves the master (Nav2 keeps its container's grid between cycles, where the obstacle layer's maximum
// would keep the old 254).
TEST(PluginContainerLayer, AnObstacleClearedByALaterRayLeavesTheMaster)
{
  Rig rig(costmapOf({{"group", container({{"obstacles", obstacles()}})}}));
  rig.observe("group/obstacles", 5.0, 5.0);
  rig.update();
  ASSERT_EQ(rig.master().getCost(5, 5), LETHAL_OBSTACLE);
  rig.observe("group/obstacles", 8.0, 8.0);  // the ray to (8, 8) crosses (5, 5)
  rig.update();
  EXPECT_EQ(rig.master().getCost(8, 8), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.master().getCost(5, 5), FREE_SPACE);
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 1);
}

// A plugin switched off inside a container: its cells go at the next update, and come back when it is on.
TEST(PluginContainerLayer, APluginSwitchedOffLeavesAtTheNextUpdate)
{
  Rig rig(
      costmapOf({{"group", container({{"static", typed("costmap_layers/StaticLayer")}, {"inflation", inflation()}})}}));
  rig.update();
  ASSERT_EQ(count(rig.master(), INSCRIBED_INFLATED_OBSTACLE), 28);
  const auto infl = rig.lc.findLayer("group/inflation");
  infl->setEnabled(false);
  rig.update();
  EXPECT_EQ(count(rig.master(), INSCRIBED_INFLATED_OBSTACLE), 0);
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 20);
  infl->setEnabled(true);
  rig.update();
  EXPECT_EQ(count(rig.master(), INSCRIBED_INFLATED_OBSTACLE), 28);
}

// The host reaches every plugin of every container (to wire ports, reconfiguration and diagnostics),
// named <container>/<plugin>, depth first; each reads its parameters from that namespace.
TEST(PluginContainerLayer, NestedPluginsAreExposedToTheHostByPath)
{
  // The static layer first: it overwrites what comes before it.
  Rig rig(costmapOf({{"static", typed("costmap_layers/StaticLayer")},
                     {"outer", container({{"inner", container({{"obstacles", obstacles()}})},
                                          {"inflation", inflation(2.5, 1.0)}})}}));
  std::vector<std::string> nested;
  for (const auto& l : rig.lc.nestedLayers())
    nested.push_back(l->getName());
  EXPECT_EQ(nested, (std::vector<std::string>{"outer/inner", "outer/inner/obstacles", "outer/inflation"}));
  EXPECT_EQ(rig.contexts.size(), 5u);
  EXPECT_EQ(rig.layer<InflationLayer>("outer/inflation")->config().inflation_radius, 2.5);
  rig.observe("outer/inner/obstacles", 2.0, 7.0);
  rig.update();
  EXPECT_EQ(rig.master().getCost(2, 7), LETHAL_OBSTACLE);
}

// The keys nobody read are found in the plugins' namespaces, named by path, and a container's plugin
// namespaces are not taken for unknown keys of the container.
TEST(PluginContainerLayer, UnusedKeysAreNamedInTheNestedNamespace)
{
  ParamValue ns = costmapOf({{"group", container({{"inflation", inflation()}})}});
  ns.findMutable("group")->findMutable("inflation")->set("inflaton_radius", D(2.0));
  std::vector<std::string> lines;
  {
    ParamReadLog log;
    const CompatResult compat = prepareCostmapNamespace(ns, "", {});
    Rig rig(ParamValue::makeMap(), false, &compat.params);
    std::vector<std::pair<PluginSpec, const ParamValue*>> layers;
    for (const auto& [name, ctx] : rig.contexts)
      layers.push_back(
          {PluginSpec{name, name == "group" ? "costmap_layers/PluginContainerLayer" : "costmap_layers/InflationLayer"},
           &ctx->params()});
    lines = unusedParameterLines(compat, log, layers, "/costmap");
  }
  ASSERT_EQ(lines.size(), 1u) << (lines.empty() ? "" : lines[0]);
  EXPECT_NE(lines[0].find("inflaton_radius"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find("/costmap/group/inflation"), std::string::npos) << lines[0];
}

// Bad configurations: each refused in one line naming the parameter (or the plugin) and the value.
TEST(PluginContainerLayer, ConfigErrorsAreRefusedNamingTheParameterAndValue)
{
  struct Case
  {
    const char* what;
    ParamValue ns;
    std::vector<std::string> said;
  };
  ParamValue empty_list = costmapOf({{"group", container({})}});
  ParamValue no_list = costmapOf({{"group", typed("costmap_layers/PluginContainerLayer")}});
  ParamValue twice = costmapOf({{"group", container({{"a", inflation()}})}});
  twice.findMutable("group")->set("plugins", names({"a", "a"}));
  ParamValue self = costmapOf({{"group", container({{"group", container({{"a", inflation()}})}})}});
  ParamValue bad_name = costmapOf({{"group", container({{"9lives", inflation()}})}});
  ParamValue bad_name2 = costmapOf({{"group", container({{"a b", inflation()}})}});
  ParamValue no_type = costmapOf({{"group", container({{"a", paramMap({{"inflation_radius", D(1.0)}})}})}});
  const std::vector<Case> cases = {
      {"unknown type",
       costmapOf({{"group", container({{"bogus", typed("costmap_layers/NoSuchLayer")}})}}),
       {"group/bogus", "costmap_layers/NoSuchLayer"}},
      {"a name used twice", twice, {"group", "'a'", "twice"}},
      {"an empty list", empty_list, {"group", "'plugins'", "[]"}},
      {"no list", no_list, {"group", "'plugins'"}},
      {"a container inside itself", self, {"group", "'plugins'", "'group'", "itself"}},
      {"a name that is no name (digit first)", bad_name, {"group", "'plugins'", "9lives"}},
      {"a name that is no name (space)", bad_name2, {"group", "'plugins'", "a b"}},
      {"a plugin without its type", no_type, {"group", "'a/plugin'"}},
      {"combination_method 3",
       costmapOf({{"group", container({{"a", inflation()}}, {{"combination_method", I(3)}})}}),
       {"group", "'combination_method'", "3"}},
      {"combination_method -1",
       costmapOf({{"group", container({{"a", inflation()}}, {{"combination_method", I(-1)}})}}),
       {"group", "'combination_method'", "-1"}},
  };
  for (const Case& c : cases)
  {
    const std::string what = loadError(c.ns);
    ASSERT_FALSE(what.empty()) << c.what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << c.what << ": " << what;
    for (const auto& s : c.said)
      EXPECT_NE(what.find(s), std::string::npos) << c.what << ": '" << s << "' not in: " << what;
  }
}

// Nesting: kMaxNesting levels of containers load, one more is refused naming the deepest one.
TEST(PluginContainerLayer, NestingIsBounded)
{
  auto nested = [](int levels)
  {
    ParamValue inner = container({{"inflation", inflation()}});
    for (int k = levels; k > 1; --k)
      inner = container({{("c" + std::to_string(k)).c_str(), inner}});
    return costmapOf({{"c1", inner}});
  };
  static_assert(PluginContainerLayer::kMaxNesting == 4);
  EXPECT_EQ(loadError(nested(4)), "");
  const std::string what = loadError(nested(5));
  EXPECT_NE(what.find("c1/c2/c3/c4/c5: containers nested 5 deep, at most 4"), std::string::npos) << what;
}

// The whole costmap, containers' plugins included, holds at most 64 plugins (limits::kMaxPlugins), as
// its own list does: 63 in a container with the container itself loads, 64 do not.
TEST(PluginContainerLayer, PluginCountIsBoundedOverTheWholeCostmap)
{
  auto withPlugins = [](int n)
  {
    ParamValue c = typed("costmap_layers/PluginContainerLayer");
    ParamValue list = ParamValue::makeList();
    for (int k = 0; k < n; ++k)
    {
      const std::string name = "i" + std::to_string(k);
      list.push(S(name));
      c.set(name, inflation());
    }
    c.set("plugins", list);
    return costmapOf({{"group", c}});
  };
  EXPECT_EQ(loadError(withPlugins(63)), "");
  const std::string what = loadError(withPlugins(64));
  EXPECT_NE(what.find("group: parameter 'plugins' makes 65 plugins in this costmap"), std::string::npos) << what;
}

// A host that gives no factories (a layer initialised by hand) is told so, not crashed.
TEST(PluginContainerLayer, WithoutTheHostsFactoriesItRefusesToStart)
{
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(10, 10, 1.0, 0.0, 0.0);
  auto layer = std::make_shared<PluginContainerLayer>();
  const std::string what = thrownMessage(
      [&] {
        layer->initialize(&lc, "group", std::make_shared<FakeContext>(container({{"a", inflation()}})));
      });
  EXPECT_NE(what.find("group: this host cannot make the plugins"), std::string::npos) << what;
}
