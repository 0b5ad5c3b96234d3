// Unit tests of the parameter tree, typed reads, the costmap's own configuration, plugin lists and
// footprints.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/config/param_value.hpp"
#include "costmap_layers/core/costmap/costmap_config.hpp"
#include "costmap_layers/core/grid/footprint.hpp"

using namespace costmap_layers;

namespace
{
ParamValue str(const std::string& s)
{
  return ParamValue::makeString(s);
}
ParamValue num(double d)
{
  return ParamValue::makeDouble(d);
}
ParamValue integer(int64_t i)
{
  return ParamValue::makeInt(i);
}
ParamValue boolean(bool b)
{
  return ParamValue::makeBool(b);
}
ParamValue list(std::vector<ParamValue> v)
{
  return ParamValue::makeList(std::move(v));
}
ParamValue point(double x, double y)
{
  return list({num(x), num(y)});
}

ParamValue one(const std::string& key, ParamValue v)
{
  ParamValue p = ParamValue::makeMap();
  p.set(key, std::move(v));
  return p;
}

/// The message of the std::invalid_argument that fn throws, or "" (and a failure) when none.
template <class Fn>
std::string errorOf(Fn&& fn)
{
  try
  {
    fn();
  }
  catch (const std::invalid_argument& e)
  {
    return e.what();
  }
  ADD_FAILURE() << "no std::invalid_argument thrown";
  return "";
}

bool contains(const std::string& text, const std::string& needle)
{
  return text.find(needle) != std::string::npos;
}

ParamValue namedType(const std::string& name, const std::string& type)
{
  ParamValue m = ParamValue::makeMap();
  m.set("name", str(name));
  m.set("type", str(type));
  return m;
}
}  // namespace

// ---------------------------------------------------------------- ParamValue

TEST(ParamValueTest, TypesAndAccessors)
{
  EXPECT_TRUE(ParamValue().isNull());
  EXPECT_EQ(ParamValue().type(), ParamValue::Type::Null);
  EXPECT_TRUE(boolean(true).asBool());
  EXPECT_EQ(integer(-42).asInt(), -42);
  EXPECT_EQ(integer(int64_t{1} << 40).asInt(), int64_t{1} << 40);
  EXPECT_DOUBLE_EQ(num(2.5).asDouble(), 2.5);
  EXPECT_DOUBLE_EQ(integer(3).asDouble(), 3.0);  // ints convert to double
  EXPECT_EQ(str("abc").asString(), "abc");
  EXPECT_EQ(list({integer(1), integer(2)}).asList().size(), 2u);
  EXPECT_TRUE(ParamValue::makeMap().isMap());
  EXPECT_TRUE(ParamValue::makeList().isList());
  EXPECT_TRUE(integer(1).isNumber());
  EXPECT_TRUE(num(1).isNumber());
  EXPECT_FALSE(str("1").isNumber());
}

TEST(ParamValueTest, WrongTypeThrows)
{
  EXPECT_THROW(str("true").asBool(), std::invalid_argument);
  EXPECT_THROW(num(1.0).asInt(), std::invalid_argument);  // no silent double -> int
  EXPECT_THROW(str("1.0").asDouble(), std::invalid_argument);
  EXPECT_THROW(integer(1).asString(), std::invalid_argument);
  EXPECT_THROW(ParamValue::makeMap().asList(), std::invalid_argument);
  EXPECT_THROW(ParamValue().asBool(), std::invalid_argument);
  const std::string msg = errorOf([] { str("x").asInt(); });
  EXPECT_TRUE(contains(msg, "integer")) << msg;
  EXPECT_TRUE(contains(msg, "\"x\"")) << msg;
}

TEST(ParamValueTest, MapSetFindAndPaths)
{
  ParamValue root;
  root.set("a", integer(1));  // Null becomes a Map
  EXPECT_TRUE(root.isMap());
  ParamValue& inner = root.set("b", ParamValue::makeMap());
  inner.set("c", str("deep"));
  ASSERT_NE(root.find("a"), nullptr);
  EXPECT_EQ(root.find("a")->asInt(), 1);
  EXPECT_EQ(root.find("zz"), nullptr);
  EXPECT_EQ(integer(3).find("a"), nullptr);  // not a map

  ASSERT_NE(root.findPath("b/c"), nullptr);
  EXPECT_EQ(root.findPath("b/c")->asString(), "deep");
  ASSERT_NE(root.findPath("/b/c/"), nullptr);  // leading and trailing slashes are ignored
  EXPECT_EQ(root.findPath("/b/c/")->asString(), "deep");
  EXPECT_EQ(root.findPath("b/x"), nullptr);
  EXPECT_EQ(root.findPath("a/c"), nullptr);
  EXPECT_EQ(root.findPath(""), &root);

  root.set("a", str("replaced"));  // replacing keeps one entry
  EXPECT_EQ(root.find("a")->asString(), "replaced");
  EXPECT_EQ(root.entries().size(), 2u);
  EXPECT_EQ(root.entries()[0].first, "a");  // insertion order kept
  EXPECT_EQ(root.entries()[1].first, "b");

  ParamValue scalar = integer(1);
  EXPECT_THROW(scalar.set("k", integer(2)), std::invalid_argument);
}

TEST(ParamValueTest, PushBuildsLists)
{
  ParamValue l;
  l.push(integer(1));
  l.push(str("two"));
  ASSERT_TRUE(l.isList());
  ASSERT_EQ(l.asList().size(), 2u);
  EXPECT_EQ(l.asList()[1].asString(), "two");
  ParamValue m = ParamValue::makeMap();
  EXPECT_THROW(m.push(integer(1)), std::invalid_argument);
}

TEST(ParamValueTest, ToStringAndTypeNames)
{
  EXPECT_EQ(ParamValue().toString(), "null");
  EXPECT_EQ(boolean(false).toString(), "false");
  EXPECT_EQ(integer(-7).toString(), "-7");
  EXPECT_EQ(num(0.5).toString(), "0.5");
  EXPECT_EQ(str("hi").toString(), "\"hi\"");
  EXPECT_EQ(list({integer(1), str("a")}).toString(), "[1, \"a\"]");
  ParamValue m = ParamValue::makeMap();
  m.set("k", integer(1));
  m.set("s", str("v"));
  EXPECT_EQ(m.toString(), "{k: 1, s: \"v\"}");
  std::vector<ParamValue> many;
  for (int i = 0; i < 10; ++i)
    many.push_back(integer(i));
  EXPECT_EQ(list(many).toString(), "[0, 1, 2, 3, 4, 5, 6, 7, ...]");
  EXPECT_STREQ(ParamValue::typeName(ParamValue::Type::Double), "double");
  EXPECT_STREQ(ParamValue::typeName(ParamValue::Type::Map), "map");
  EXPECT_STREQ(ParamValue::typeName(ParamValue::Type::String), "string");
}

// ---------------------------------------------------------------- ParamReader

TEST(ParamReaderTest, DefaultsWhenAbsentOrNullNamespace)
{
  const ParamValue empty = ParamValue::makeMap();
  const ParamValue null;
  for (const ParamValue* ns : {&empty, &null})
  {
    ParamReader r(*ns, "owner");
    EXPECT_FALSE(r.has("x"));
    EXPECT_EQ(r.raw("x"), nullptr);
    EXPECT_TRUE(r.getBool("x", true));
    EXPECT_EQ(r.getInt("x", 7), 7);
    EXPECT_DOUBLE_EQ(r.getDouble("x", 1.5), 1.5);
    EXPECT_EQ(r.getString("x", "d"), "d");
    EXPECT_EQ(r.getChoice("x", "b", {"a", "b"}), "b");
  }
}

TEST(ParamReaderTest, BoolAcceptsZeroAndOneOnly)
{
  ParamValue p = ParamValue::makeMap();
  p.set("t", boolean(true));
  p.set("one", integer(1));
  p.set("zero", integer(0));
  p.set("two", integer(2));
  p.set("s", str("true"));
  ParamReader r(p, "me");
  EXPECT_TRUE(r.getBool("t", false));
  EXPECT_TRUE(r.getBool("one", false));
  EXPECT_FALSE(r.getBool("zero", true));
  EXPECT_THROW(r.getBool("two", false), std::invalid_argument);
  const std::string msg = errorOf([&] { r.getBool("s", false); });
  EXPECT_EQ(msg, "me: parameter 's' must be a boolean (got \"true\")");
}

TEST(ParamReaderTest, IntRangesAndWholeDoubles)
{
  ParamValue p = ParamValue::makeMap();
  p.set("i", integer(5));
  p.set("d", num(6.0));
  p.set("frac", num(6.5));
  p.set("nan", num(std::nan("")));
  p.set("big", integer(int64_t{1} << 40));
  p.set("s", str("5"));
  ParamReader r(p, "me");
  EXPECT_EQ(r.getInt("i", 0), 5);
  EXPECT_EQ(r.getInt("d", 0), 6);
  EXPECT_EQ(r.getInt("i", 0, 5, 5), 5);  // inclusive limits
  EXPECT_THROW(r.getInt("frac", 0), std::invalid_argument);
  EXPECT_THROW(r.getInt("nan", 0), std::invalid_argument);
  EXPECT_THROW(r.getInt("big", 0), std::invalid_argument);  // outside int
  EXPECT_THROW(r.getInt("s", 0), std::invalid_argument);
  const std::string msg = errorOf([&] { r.getInt("i", 0, 6, 9); });
  EXPECT_EQ(msg, "me: parameter 'i' must be in [6, 9] (got 5)");
  EXPECT_THROW(r.getInt("i", 0, 0, 4), std::invalid_argument);
}

TEST(ParamReaderTest, DoubleRejectsNonFiniteAndOutOfRange)
{
  ParamValue p = ParamValue::makeMap();
  p.set("d", num(0.25));
  p.set("i", integer(3));
  p.set("nan", num(std::nan("")));
  p.set("inf", num(std::numeric_limits<double>::infinity()));
  p.set("ninf", num(-std::numeric_limits<double>::infinity()));
  p.set("s", str("0.25"));
  ParamReader r(p, "me");
  EXPECT_DOUBLE_EQ(r.getDouble("d", 0), 0.25);
  EXPECT_DOUBLE_EQ(r.getDouble("i", 0), 3.0);
  EXPECT_DOUBLE_EQ(r.getDouble("d", 0, 0.25, 0.25), 0.25);
  EXPECT_TRUE(contains(errorOf([&] { r.getDouble("nan", 0); }), "must be finite"));
  EXPECT_TRUE(contains(errorOf([&] { r.getDouble("inf", 0); }), "must be finite"));
  EXPECT_THROW(r.getDouble("ninf", 0), std::invalid_argument);
  EXPECT_TRUE(contains(errorOf([&] { r.getDouble("s", 0); }), "must be a number"));
  const std::string msg = errorOf([&] { r.getDouble("d", 0, 1.0, 2.0); });
  EXPECT_TRUE(contains(msg, "me: parameter 'd' must be in [1, 2]")) << msg;
  EXPECT_TRUE(contains(msg, "0.25")) << msg;
}

TEST(ParamReaderTest, StringsAndChoices)
{
  ParamValue p = ParamValue::makeMap();
  p.set("s", str("b"));
  p.set("bad", str("z"));
  p.set("n", integer(1));
  ParamReader r(p, "me");
  EXPECT_EQ(r.getString("s", ""), "b");
  EXPECT_THROW(r.getString("n", ""), std::invalid_argument);
  EXPECT_EQ(r.getChoice("s", "a", {"a", "b"}), "b");
  const std::string msg = errorOf([&] { r.getChoice("bad", "a", {"a", "b"}); });
  EXPECT_TRUE(contains(msg, "must be one of: a, b")) << msg;
  EXPECT_TRUE(contains(msg, "\"z\"")) << msg;
  // fail() on an absent name names it without a value.
  EXPECT_EQ(errorOf([&] { r.fail("missing", "is required"); }), "me: parameter 'missing' is required");
  EXPECT_EQ(r.owner(), "me");
}

// ---------------------------------------------------------------- parseCostmapConfig

TEST(CostmapConfigTest, Defaults)
{
  const CostmapConfig c = parseCostmapConfig(ParamValue::makeMap());
  EXPECT_EQ(c.global_frame, "map");
  EXPECT_EQ(c.robot_base_frame, "base_link");
  EXPECT_DOUBLE_EQ(c.transform_tolerance, 0.3);
  EXPECT_DOUBLE_EQ(c.update_frequency, 5.0);
  EXPECT_DOUBLE_EQ(c.publish_frequency, 0.0);
  EXPECT_DOUBLE_EQ(c.width, 10.0);
  EXPECT_DOUBLE_EQ(c.height, 10.0);
  EXPECT_DOUBLE_EQ(c.resolution, 0.05);
  EXPECT_DOUBLE_EQ(c.origin_x, 0.0);
  EXPECT_DOUBLE_EQ(c.origin_y, 0.0);
  EXPECT_FALSE(c.rolling_window);
  EXPECT_FALSE(c.track_unknown_space);
  EXPECT_FALSE(c.always_send_full_costmap);
  EXPECT_EQ(c.sizeInCellsX(), 200u);
  EXPECT_EQ(c.sizeInCellsY(), 200u);
  EXPECT_TRUE(c.footprint.footprint.empty());
  EXPECT_DOUBLE_EQ(c.footprint.robot_radius, 0.46);
  EXPECT_DOUBLE_EQ(c.footprint.footprint_padding, 0.01);
  // Also a Null namespace (nothing set at all).
  EXPECT_EQ(parseCostmapConfig(ParamValue()).global_frame, "map");
}

TEST(CostmapConfigTest, ValuesAreRead)
{
  ParamValue p = ParamValue::makeMap();
  p.set("global_frame", str("odom"));
  p.set("robot_base_frame", str("base_footprint"));
  p.set("transform_tolerance", num(0.5));
  p.set("update_frequency", integer(10));
  p.set("publish_frequency", num(2.0));
  p.set("width", integer(6));
  p.set("height", num(3.3));
  p.set("resolution", num(0.1));
  p.set("origin_x", num(-3.0));
  p.set("origin_y", num(-1.5));
  p.set("rolling_window", boolean(true));
  p.set("track_unknown_space", integer(1));
  p.set("always_send_full_costmap", boolean(true));
  const CostmapConfig c = parseCostmapConfig(p);
  EXPECT_EQ(c.global_frame, "odom");
  EXPECT_EQ(c.robot_base_frame, "base_footprint");
  EXPECT_DOUBLE_EQ(c.transform_tolerance, 0.5);
  EXPECT_DOUBLE_EQ(c.update_frequency, 10.0);
  EXPECT_DOUBLE_EQ(c.publish_frequency, 2.0);
  EXPECT_DOUBLE_EQ(c.width, 6.0);
  EXPECT_DOUBLE_EQ(c.height, 3.3);
  EXPECT_DOUBLE_EQ(c.resolution, 0.1);
  EXPECT_DOUBLE_EQ(c.origin_x, -3.0);
  EXPECT_DOUBLE_EQ(c.origin_y, -1.5);
  EXPECT_TRUE(c.rolling_window);
  EXPECT_TRUE(c.track_unknown_space);
  EXPECT_TRUE(c.always_send_full_costmap);
  EXPECT_EQ(c.sizeInCellsX(), 60u);
  EXPECT_EQ(c.sizeInCellsY(), 33u);
}

TEST(CostmapConfigTest, InvalidValuesNameTheParameter)
{
  const std::vector<std::pair<std::string, ParamValue>> bad = {
      {"resolution", num(0.0)},
      {"resolution", num(-0.05)},
      {"resolution", num(std::nan(""))},
      {"width", num(0.01)},  // smaller than one cell
      {"height", num(-1.0)},
      {"width", num(1e9)},
      {"global_frame", str("")},
      {"robot_base_frame", str("")},
      {"global_frame", integer(3)},
      // Frame ids tf2 would never find (issue 34: "map\nodom" came back as "map odom" from a file).
      {"global_frame", str("map\nodom")},
      {"global_frame", str("map odom")},
      {"robot_base_frame", str("base_link\t")},
      {"robot_base_frame", str(std::string(257, 'b'))},
      {"rolling_window", str("yes")},
      {"update_frequency", num(-1.0)},
      {"transform_tolerance", num(std::numeric_limits<double>::infinity())},
      {"origin_x", num(1e8)},
      {"track_unknown_space", integer(2)},
  };
  for (const auto& b : bad)
  {
    const std::string msg = errorOf([&] { parseCostmapConfig(one(b.first, b.second)); });
    EXPECT_TRUE(contains(msg, "'" + b.first + "'")) << b.first << ": " << msg;
    EXPECT_TRUE(contains(msg, "costmap")) << msg;
  }
}

// ---------------------------------------------------------------- parsePluginLists

TEST(PluginListsTest, EmptyWhenNothingConfigured)
{
  const PluginLists l = parsePluginLists(ParamValue::makeMap());
  EXPECT_TRUE(l.plugins.empty());
  EXPECT_TRUE(l.filters.empty());
  ParamValue p = ParamValue::makeMap();
  p.set("plugins", ParamValue());  // "plugins:" with nothing after it
  EXPECT_TRUE(parsePluginLists(p).plugins.empty());
  EXPECT_TRUE(parsePluginLists(one("plugins", list({}))).plugins.empty());
}

TEST(PluginListsTest, Ros1FormWithNameAndTypeMaps)
{
  ParamValue p = ParamValue::makeMap();
  p.set("plugins", list({namedType("static", "costmap_layers/StaticLayer"),
                         namedType("gradient", "costmap_layers/GradientLayer")}));
  p.set("filters", list({namedType("keepout", "costmap_layers/KeepoutFilter")}));
  const PluginLists l = parsePluginLists(p);
  ASSERT_EQ(l.plugins.size(), 2u);
  EXPECT_EQ(l.plugins[0].name, "static");
  EXPECT_EQ(l.plugins[0].type, "costmap_layers/StaticLayer");
  EXPECT_EQ(l.plugins[1].name, "gradient");
  EXPECT_EQ(l.plugins[1].type, "costmap_layers/GradientLayer");
  ASSERT_EQ(l.filters.size(), 1u);
  EXPECT_EQ(l.filters[0].name, "keepout");
  EXPECT_EQ(l.filters[0].type, "costmap_layers/KeepoutFilter");

  // "plugin" is accepted instead of "type" inside a map entry.
  ParamValue entry = ParamValue::makeMap();
  entry.set("name", str("g"));
  entry.set("plugin", str("costmap_layers/GradientLayer"));
  const PluginLists l2 = parsePluginLists(one("plugins", list({entry})));
  ASSERT_EQ(l2.plugins.size(), 1u);
  EXPECT_EQ(l2.plugins[0].type, "costmap_layers/GradientLayer");
}

TEST(PluginListsTest, FoxyFormWithNamesAndTypes)
{
  ParamValue p = ParamValue::makeMap();
  p.set("plugin_names", list({str("a"), str("b")}));
  p.set("plugin_types", list({str("costmap_layers/StaticLayer"), str("costmap_layers/InflationLayer")}));
  p.set("filter_names", list({str("speed")}));
  p.set("filter_types", list({str("costmap_layers/SpeedFilter")}));
  const PluginLists l = parsePluginLists(p);
  ASSERT_EQ(l.plugins.size(), 2u);
  EXPECT_EQ(l.plugins[0].name, "a");
  EXPECT_EQ(l.plugins[0].type, "costmap_layers/StaticLayer");
  EXPECT_EQ(l.plugins[1].name, "b");
  EXPECT_EQ(l.plugins[1].type, "costmap_layers/InflationLayer");
  ASSERT_EQ(l.filters.size(), 1u);
  EXPECT_EQ(l.filters[0].name, "speed");
  EXPECT_EQ(l.filters[0].type, "costmap_layers/SpeedFilter");
}

TEST(PluginListsTest, GalacticFormWithNamesAndPluginKeys)
{
  ParamValue p = ParamValue::makeMap();
  p.set("plugins", list({str("static_layer"), str("inflation_layer")}));
  p.set("static_layer", one("plugin", str("costmap_layers/StaticLayer")));
  ParamValue infl = ParamValue::makeMap();
  infl.set("plugin", str("costmap_layers/InflationLayer"));
  infl.set("inflation_radius", num(0.5));
  p.set("inflation_layer", infl);
  p.set("filters", list({str("keepout")}));
  p.set("keepout", one("type", str("costmap_layers/KeepoutFilter")));  // "type" accepted too
  const PluginLists l = parsePluginLists(p);
  ASSERT_EQ(l.plugins.size(), 2u);
  EXPECT_EQ(l.plugins[0].name, "static_layer");
  EXPECT_EQ(l.plugins[0].type, "costmap_layers/StaticLayer");
  EXPECT_EQ(l.plugins[1].name, "inflation_layer");
  EXPECT_EQ(l.plugins[1].type, "costmap_layers/InflationLayer");
  ASSERT_EQ(l.filters.size(), 1u);
  EXPECT_EQ(l.filters[0].type, "costmap_layers/KeepoutFilter");
}

TEST(PluginListsTest, MixedFormsPerList)
{
  // plugins in the Galactic form, filters in the Foxy form.
  ParamValue p = ParamValue::makeMap();
  p.set("plugins", list({str("g")}));
  p.set("g", one("plugin", str("costmap_layers/GradientLayer")));
  p.set("filter_names", list({str("k")}));
  p.set("filter_types", list({str("costmap_layers/KeepoutFilter")}));
  const PluginLists l = parsePluginLists(p);
  ASSERT_EQ(l.plugins.size(), 1u);
  ASSERT_EQ(l.filters.size(), 1u);
  EXPECT_EQ(l.filters[0].name, "k");
}

TEST(PluginListsTest, SixtyFourPluginsAreAccepted)
{
  std::vector<ParamValue> layers, filters;
  for (int k = 0; k < 32; ++k)
  {
    layers.push_back(namedType("layer" + std::to_string(k), "x/Y"));
    filters.push_back(namedType("filter" + std::to_string(k), "x/F"));
  }
  ParamValue p = ParamValue::makeMap();
  p.set("plugins", list(layers));
  p.set("filters", list(filters));
  const PluginLists lists = parsePluginLists(p);
  EXPECT_EQ(lists.plugins.size(), 32u);
  EXPECT_EQ(lists.filters.size(), 32u);
}

TEST(PluginListsTest, MalformedListsThrow)
{
  struct Case
  {
    const char* what;
    ParamValue ns;
    const char* needle;
  };
  std::vector<Case> cases;
  cases.push_back({"plugins not a list", one("plugins", str("a")), "must be a list"});
  {
    ParamValue m = ParamValue::makeMap();
    m.set("name", str("a"));
    cases.push_back({"map entry without type", one("plugins", list({m})), "name and type"});
  }
  {
    ParamValue m = ParamValue::makeMap();
    m.set("type", str("x/Y"));
    cases.push_back({"map entry without name", one("plugins", list({m})), "name and type"});
  }
  {
    ParamValue m = ParamValue::makeMap();
    m.set("name", integer(1));
    m.set("type", str("x/Y"));
    cases.push_back({"name not a string", one("plugins", list({m})), "name and type"});
  }
  cases.push_back({"entry neither map nor string", one("plugins", list({integer(3)})), "maps or names"});
  cases.push_back({"galactic name without its namespace", one("plugins", list({str("ghost")})), "ghost/plugin"});
  {
    ParamValue p = ParamValue::makeMap();
    p.set("plugins", list({str("a")}));
    p.set("a", one("plugin", integer(5)));
    cases.push_back({"galactic plugin not a string", p, "a/plugin"});
  }
  cases.push_back({"names without types", one("plugin_names", list({str("a")})), "must both be lists"});
  cases.push_back({"types without names", one("plugin_types", list({str("x/Y")})), "must both be lists"});
  {
    ParamValue p = ParamValue::makeMap();
    p.set("plugin_names", list({str("a"), str("b")}));
    p.set("plugin_types", list({str("x/Y")}));
    cases.push_back({"size mismatch", p, "has 2 entries"});
  }
  {
    ParamValue p = ParamValue::makeMap();
    p.set("plugin_names", str("a"));
    p.set("plugin_types", str("x/Y"));
    cases.push_back({"names not lists", p, "must both be lists"});
  }
  {
    ParamValue p = ParamValue::makeMap();
    p.set("plugin_names", list({integer(1)}));
    p.set("plugin_types", list({str("x/Y")}));
    cases.push_back({"names not strings", p, "must hold strings"});
  }
  {
    ParamValue p = ParamValue::makeMap();
    p.set("filter_names", list({str("f")}));
    cases.push_back({"filter names without types", p, "filter_types"});
  }
  cases.push_back({"empty name", one("plugins", list({namedType("", "x/Y")})), "is empty, not a plugin name"});
  // What costmap_node's NodeHandles refuse, refused here too, where costmap_tool reads the list.
  cases.push_back({"name with a space", one("plugins", list({namedType("static layer", "x/Y")})),
                   "'static layer' is not a plugin name"});
  cases.push_back({"absolute name", one("plugins", list({namedType("/obstacles", "x/Y")})), "not a plugin name"});
  {
    ParamValue p = ParamValue::makeMap();
    p.set("plugin_names", list({str("in-flation")}));
    p.set("plugin_types", list({str("x/Y")}));
    cases.push_back({"Foxy form, name with a dash", p, "'in-flation' is not a plugin name"});
  }
  cases.push_back({"empty type", one("plugins", list({namedType("a", "")})), "empty type"});
  cases.push_back(
      {"duplicate plugin", one("plugins", list({namedType("a", "x/Y"), namedType("a", "x/Z")})), "used twice"});
  {
    ParamValue p = ParamValue::makeMap();
    p.set("plugins", list({namedType("same", "x/Y")}));
    p.set("filters", list({namedType("same", "x/F")}));
    cases.push_back({"duplicate across plugins and filters", p, "'same' is used twice"});
  }
  cases.push_back({"filters not a list", one("filters", integer(1)), "'filters' must be a list"});
  {
    // 65 plugins (the limit is 64), in each form, and 40 + 40 across the two lists.
    std::vector<ParamValue> many, names, types, half;
    for (int k = 0; k < 65; ++k)
    {
      many.push_back(namedType("l" + std::to_string(k), "x/Y"));
      names.push_back(str("l" + std::to_string(k)));
      types.push_back(str("x/Y"));
    }
    for (int k = 0; k < 40; ++k)
      half.push_back(namedType("f" + std::to_string(k), "x/F"));
    cases.push_back({"65 plugins", one("plugins", list(many)), "lists 65 plugins, more than 64"});
    ParamValue foxy = ParamValue::makeMap();
    foxy.set("plugin_names", list(names));
    foxy.set("plugin_types", list(types));
    cases.push_back({"65 plugins, Foxy form", foxy, "'plugin_names' lists 65 plugins"});
    ParamValue both = ParamValue::makeMap();
    std::vector<ParamValue> first40(many.begin(), many.begin() + 40);
    both.set("plugins", list(first40));
    both.set("filters", list(half));
    cases.push_back({"40 layers and 40 filters", both, "lists 80 plugins"});
  }
  for (const auto& c : cases)
  {
    const std::string msg = errorOf([&] { parsePluginLists(c.ns); });
    EXPECT_TRUE(contains(msg, c.needle)) << c.what << ": " << msg;
  }
}

// ---------------------------------------------------------------- footprints

TEST(FootprintTest, RobotRadiusGives16Gon)
{
  ParamValue p = ParamValue::makeMap();
  p.set("robot_radius", num(0.3));
  p.set("footprint_padding", num(0.0));
  const CostmapConfig c = parseCostmapConfig(p);
  EXPECT_TRUE(c.footprint.footprint.empty());
  const Footprint fp = c.footprint.padded();
  ASSERT_EQ(fp.size(), 16u);
  for (int i = 0; i < 16; ++i)
  {
    const double angle = i * 2.0 * M_PI / 16.0;
    EXPECT_NEAR(fp[i].x(), 0.3 * std::cos(angle), 1e-12) << i;
    EXPECT_NEAR(fp[i].y(), 0.3 * std::sin(angle), 1e-12) << i;
  }
  double inscribed, circumscribed;
  calculateMinAndMaxDistances(fp, inscribed, circumscribed);
  EXPECT_NEAR(circumscribed, 0.3, 1e-12);
  EXPECT_NEAR(inscribed, 0.3 * std::cos(M_PI / 16.0), 1e-12);  // distance to a chord's midpoint
  EXPECT_EQ(makeFootprintFromRadius(1.0).size(), 16u);
}

TEST(FootprintTest, SquareWithZeroPaddingHasInscribedHalfWidth)
{
  ParamValue p = ParamValue::makeMap();
  p.set("footprint", list({point(0.22, 0.22), point(0.22, -0.22), point(-0.22, -0.22), point(-0.22, 0.22)}));
  p.set("footprint_padding", integer(0));
  const CostmapConfig c = parseCostmapConfig(p);
  ASSERT_EQ(c.footprint.footprint.size(), 4u);
  const Footprint fp = c.footprint.padded();
  ASSERT_EQ(fp.size(), 4u);
  EXPECT_DOUBLE_EQ(fp[1].x(), 0.22);
  EXPECT_DOUBLE_EQ(fp[1].y(), -0.22);
  double inscribed, circumscribed;
  calculateMinAndMaxDistances(fp, inscribed, circumscribed);
  EXPECT_NEAR(inscribed, 0.22, 1e-12);
  EXPECT_NEAR(circumscribed, 0.22 * std::sqrt(2.0), 1e-12);
}

TEST(FootprintTest, StringFootprintAndDefaultPadding)
{
  ParamValue p = ParamValue::makeMap();
  p.set("footprint", str("[[0.22, 0.22], [0.22, -0.22], [-0.22, -0.22], [-0.22, 0.22]]"));
  const CostmapConfig c = parseCostmapConfig(p);
  ASSERT_EQ(c.footprint.footprint.size(), 4u);
  EXPECT_DOUBLE_EQ(c.footprint.footprint[0].x(), 0.22);  // stored unpadded
  const Footprint fp = c.footprint.padded();             // default padding 0.01 outward
  EXPECT_NEAR(fp[0].x(), 0.23, 1e-12);
  EXPECT_NEAR(fp[0].y(), 0.23, 1e-12);
  EXPECT_NEAR(fp[2].x(), -0.23, 1e-12);
  EXPECT_NEAR(fp[2].y(), -0.23, 1e-12);
  double inscribed, circumscribed;
  calculateMinAndMaxDistances(fp, inscribed, circumscribed);
  EXPECT_NEAR(inscribed, 0.23, 1e-12);
}

TEST(FootprintTest, PaddingMovesAlongEachAxisAndKeepsZeros)
{
  Footprint fp = {{0.5, 0.0}, {0.0, -0.4}, {-0.3, 0.2}};
  padFootprint(fp, 0.1);
  EXPECT_DOUBLE_EQ(fp[0].x(), 0.6);
  EXPECT_DOUBLE_EQ(fp[0].y(), 0.0);
  EXPECT_DOUBLE_EQ(fp[1].x(), 0.0);
  EXPECT_DOUBLE_EQ(fp[1].y(), -0.5);
  EXPECT_DOUBLE_EQ(fp[2].x(), -0.4);
  EXPECT_DOUBLE_EQ(fp[2].y(), 0.30000000000000004);

  FootprintConfig cfg;
  cfg.robot_radius = 0.5;
  cfg.footprint_padding = 0.1;
  const Footprint circle = cfg.padded();
  ASSERT_EQ(circle.size(), 16u);
  EXPECT_NEAR(circle[0].x(), 0.6, 1e-12);  // (0.5, 0) -> (0.6, 0)
  EXPECT_NEAR(circle[0].y(), 0.0, 1e-12);
  EXPECT_NEAR(circle[4].y(), 0.6, 1e-12);
}

TEST(FootprintTest, EmptyStringOrListMeansRobotRadius)
{
  for (const ParamValue& v : {str("[]"), str(" [ ] "), str(""), list({})})
  {
    ParamValue p = ParamValue::makeMap();
    p.set("footprint", v);
    p.set("robot_radius", num(0.2));
    const CostmapConfig c = parseCostmapConfig(p);
    EXPECT_TRUE(c.footprint.footprint.empty()) << v.toString();
    EXPECT_EQ(c.footprint.padded().size(), 16u);
  }
}

TEST(FootprintTest, InvalidFootprintsThrowNamingFootprint)
{
  const std::vector<ParamValue> bad = {
      str("[[1, 2], [3, 4]]"),             // two points
      str("[[1, 2, 3], [3, 4], [5, 6]]"),  // three numbers in a point
      str("[[1, 2], [3, 4], [5, 6]"),      // unbalanced
      str("[[1, 2], [3, 4], [5, nan]]"),   // not finite
      str("[[1, 2], [3, x], [5, 6]]"),     // not a number
      str("[[[1, 2]], [3, 4], [5, 6]]"),   // too deep
      str("[1, 2, 3, 4, 5, 6]"),           // not in pairs
      list({point(1, 2), point(3, 4)}),    // two points
      list({point(1, 2), point(3, 4), list({num(5)})}),
      list({point(1, 2), point(3, 4), list({num(5), str("6")})}),
      list({point(1, 2), point(3, 4), num(5)}),
      list({point(1, 2), point(3, 4), point(5, std::numeric_limits<double>::infinity())}),
      integer(3),
  };
  for (const auto& v : bad)
  {
    const std::string msg = errorOf([&] { parseCostmapConfig(one("footprint", v)); });
    EXPECT_TRUE(contains(msg, "'footprint'")) << v.toString() << ": " << msg;
  }
  EXPECT_THROW(parseCostmapConfig(one("robot_radius", num(-0.1))), std::invalid_argument);
  // A negative padding shrinks, as in costmap_2d (DropIn.NegativeFootprintPaddingShrinksAsInCostmap2d);
  // one beyond the distance limit is refused.
  EXPECT_THROW(parseCostmapConfig(one("footprint_padding", num(-1e9))), std::invalid_argument);
}

TEST(FootprintTest, ParseFootprintStringDirectly)
{
  const Footprint fp = parseFootprintString("[[0.1,-0.2],[ 1e-1 , 3 ],[-4.5,6]]");
  ASSERT_EQ(fp.size(), 3u);
  EXPECT_DOUBLE_EQ(fp[0].x(), 0.1);
  EXPECT_DOUBLE_EQ(fp[0].y(), -0.2);
  EXPECT_DOUBLE_EQ(fp[1].x(), 0.1);
  EXPECT_DOUBLE_EQ(fp[1].y(), 3.0);
  EXPECT_DOUBLE_EQ(fp[2].x(), -4.5);
  const std::string msg = errorOf([] { parseFootprintString("]["); });
  EXPECT_TRUE(contains(msg, "\"][\"")) << msg;  // the text is named
  EXPECT_THROW(parseFootprintString(""), std::invalid_argument);
  EXPECT_THROW(parseFootprintString("[[1,2],[],[3,4],[5,6]]"), std::invalid_argument);
  // costmap_2d's parseVVF reads decimal numbers only (array_parser.cpp): a hexadecimal typo is not a
  // 16 m vertex.
  const std::string hex = errorOf([] { parseFootprintString("[[0x10, 1], [-1, 1], [-1, -1]]"); });
  EXPECT_TRUE(contains(hex, "'0x10'")) << hex;
  EXPECT_TRUE(contains(hex, "not a decimal number")) << hex;
  EXPECT_THROW(parseFootprintString("[[inf, 1], [-1, 1], [-1, -1]]"), std::invalid_argument);
}

// costmap_2d's array_parser_test (parseVVF, what its footprint strings go through): basic_operation's
// number forms (.3, -4e4; a third point here, since a footprint needs three), and missing_open,
// missing_close and wrong_depth refused.
TEST(FootprintTest, Costmap2dArrayParserCases)
{
  const Footprint fp = parseFootprintString("[[1, 2.2], [.3, -4e4], [0, 0]]");
  ASSERT_EQ(fp.size(), 3u);
  EXPECT_EQ(static_cast<float>(fp[0].x()), 1.0f);
  EXPECT_EQ(static_cast<float>(fp[0].y()), 2.2f);
  EXPECT_EQ(static_cast<float>(fp[1].x()), 0.3f);
  EXPECT_EQ(static_cast<float>(fp[1].y()), -40000.0f);
  for (const char* bad :
       {"[1, 2.2], [.3, -4e4], [0, 0]]", "[[1, 2.2], [.3, -4e4], [0, 0]", "[1, 2.2], [.3, -4e4], [0, 0]"})
    EXPECT_THROW(parseFootprintString(bad), std::invalid_argument) << bad;
}

// The worst a parameter can hold: a string of megabytes. It is read in one pass (a copy of the rest
// of the text per number made 200,000 points take hours), and the error quotes it clipped.
TEST(FootprintTest, LongFootprintStringsAreReadInOnePassAndQuotedClipped)
{
  std::string text = "[";
  for (int k = 0; k < 200000; ++k)
    text += "[" + std::to_string(k % 7) + ".5, -1.25],";
  text += "[0, 0]]";
  const Footprint fp = parseFootprintString(text);
  ASSERT_EQ(fp.size(), 200001u);
  EXPECT_DOUBLE_EQ(fp[3].x(), 3.5);
  EXPECT_DOUBLE_EQ(fp[199999].y(), -1.25);
  const std::string msg = errorOf([&] { parseFootprintString(text + "x"); });
  EXPECT_LT(msg.size(), 300u) << msg.substr(0, 300);
  EXPECT_TRUE(contains(msg, "numbers must stand inside")) << msg.substr(0, 300);
}

TEST(FootprintTest, RadiiOfDegenerateFootprints)
{
  double lo = -1, hi = -1;
  calculateMinAndMaxDistances({}, lo, hi);
  EXPECT_DOUBLE_EQ(lo, 0.0);
  EXPECT_DOUBLE_EQ(hi, 0.0);
  calculateMinAndMaxDistances({{3.0, 4.0}, {0.0, 1.0}}, lo, hi);
  EXPECT_DOUBLE_EQ(lo, 0.0);
  EXPECT_DOUBLE_EQ(hi, 5.0);
  // The origin outside the polygon (a footprint ahead of the robot).
  calculateMinAndMaxDistances({{1.0, -1.0}, {3.0, -1.0}, {3.0, 1.0}, {1.0, 1.0}}, lo, hi);
  EXPECT_NEAR(lo, 1.0, 1e-12);
  EXPECT_NEAR(hi, std::hypot(3.0, 1.0), 1e-12);
}

TEST(FootprintTest, TransformFootprint)
{
  const Footprint fp = {{1.0, 0.0}, {0.0, 2.0}};
  const Footprint t = transformFootprint(10.0, -1.0, M_PI / 2, fp);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_NEAR(t[0].x(), 10.0, 1e-12);
  EXPECT_NEAR(t[0].y(), 0.0, 1e-12);
  EXPECT_NEAR(t[1].x(), 8.0, 1e-12);
  EXPECT_NEAR(t[1].y(), -1.0, 1e-12);
}
