// Tests of costmap_layers::io params YAML reading (structure, rosparam-like scalar typing, errors) and
// writing (paramToYaml: the layout, and a tree read back equal).
#include "costmap_layers/io/param_yaml.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "costmap_layers/core/config/costmap2d_rules.hpp"
#include "costmap_layers/io/features_file.hpp"

using costmap_layers::ParamValue;
using costmap_layers::io::featuresFileProblems;
using costmap_layers::io::loadParamsYamlFile;
using costmap_layers::io::paramToYaml;
using costmap_layers::io::parseParamsYaml;
using costmap_layers::io::speedLimitsFromParams;
using costmap_layers::io::typePlainScalar;
using Type = costmap_layers::ParamValue::Type;

namespace
{
ParamValue one(const std::string& yaml_value)
{
  const ParamValue root = parseParamsYaml("v: " + yaml_value + "\n", "test");
  const ParamValue* v = root.find("v");
  if (v == nullptr) throw std::logic_error("no key v");
  return *v;
}

std::vector<std::string> keys(const ParamValue& map)
{
  std::vector<std::string> out;
  for (const auto& kv : map.entries())
    out.push_back(kv.first);
  return out;
}

template <typename F>
std::string errorOf(F&& f)
{
  try
  {
    f();
  }
  catch (const std::runtime_error& e)
  {
    return e.what();
  }
  return "<no exception>";
}

TEST(ParamYaml, BoolsAsPyYamlTypesThem)
{
  for (const char* t : {"true", "True", "TRUE", "yes", "Yes", "YES", "on", "On", "ON"})
  {
    const ParamValue v = one(t);
    ASSERT_EQ(v.type(), Type::Bool) << t;
    EXPECT_TRUE(v.asBool()) << t;
  }
  for (const char* f : {"false", "False", "FALSE", "no", "No", "NO", "off", "Off", "OFF"})
  {
    const ParamValue v = one(f);
    ASSERT_EQ(v.type(), Type::Bool) << f;
    EXPECT_FALSE(v.asBool()) << f;
  }
  // Not booleans in YAML 1.1 as PyYAML implements it.
  for (const char* s : {"y", "n", "tRUE", "yES", "enabled"})
    EXPECT_EQ(one(s).type(), Type::String) << s;
}

TEST(ParamYaml, Integers)
{
  EXPECT_EQ(one("42").asInt(), 42);
  EXPECT_EQ(one("0").asInt(), 0);
  EXPECT_EQ(one("-7").asInt(), -7);
  EXPECT_EQ(one("+3").asInt(), 3);
  EXPECT_EQ(one("1_000").asInt(), 1000);
  EXPECT_EQ(one("0x1F").asInt(), 31);
  EXPECT_EQ(one("-0x10").asInt(), -16);
  EXPECT_EQ(one("0b101").asInt(), 5);
  EXPECT_EQ(one("010").asInt(), 8);  // YAML 1.1 octal
  EXPECT_EQ(one("9223372036854775807").asInt(), std::numeric_limits<int64_t>::max());
  EXPECT_EQ(one("-9223372036854775808").asInt(), std::numeric_limits<int64_t>::min());
  for (const char* i : {"42", "-7", "0x1F", "010"})
    EXPECT_EQ(one(i).type(), Type::Int) << i;
  // Beyond int64: a double.
  const ParamValue big = one("123456789012345678901234");
  ASSERT_EQ(big.type(), Type::Double);
  EXPECT_DOUBLE_EQ(big.asDouble(), 1.23456789012345678901234e23);
  // Not integers: strings.
  for (const char* s : {"09", "0x", "1_2_x", "12abc", "- 3", "0o17", "1:30"})
    EXPECT_EQ(one(std::string("'") + s + "'").type(), Type::String) << s;  // quoted: trivially strings
  for (const char* s : {"09", "0x", "12abc", "0o17", "1:30"})
    EXPECT_EQ(typePlainScalar(s).type(), Type::String) << s;
}

TEST(ParamYaml, Floats)
{
  const std::vector<std::pair<std::string, double>> cases = {
      {"1.0", 1.0},        {"-2.5", -2.5},   {"+0.25", 0.25},    {"1.", 1.0},       {".5", 0.5},
      {"-.5", -0.5},       {"1e3", 1000.0},  {"1.0e+3", 1000.0}, {"2.5E-2", 0.025}, {"6.02e23", 6.02e23},
      {"1_000.5", 1000.5}, {"0.196", 0.196}, {"-0.0", -0.0}};
  for (const auto& c : cases)
  {
    const ParamValue v = one(c.first);
    ASSERT_EQ(v.type(), Type::Double) << c.first;
    EXPECT_DOUBLE_EQ(v.asDouble(), c.second) << c.first;
  }
  for (const char* inf : {".inf", ".Inf", ".INF", "+.inf"})
  {
    const ParamValue v = one(inf);
    ASSERT_EQ(v.type(), Type::Double) << inf;
    EXPECT_TRUE(std::isinf(v.asDouble()) && v.asDouble() > 0) << inf;
  }
  for (const char* ninf : {"-.inf", "-.Inf", "-.INF"})
  {
    const ParamValue v = one(ninf);
    ASSERT_EQ(v.type(), Type::Double) << ninf;
    EXPECT_TRUE(std::isinf(v.asDouble()) && v.asDouble() < 0) << ninf;
  }
  for (const char* nan : {".nan", ".NaN", ".NAN"})
  {
    const ParamValue v = one(nan);
    ASSERT_EQ(v.type(), Type::Double) << nan;
    EXPECT_TRUE(std::isnan(v.asDouble())) << nan;
  }
  for (const char* s : {"1.2.3", "1e", "e3", ".", "inf", "nan", "-.nan", "1.5m", "0.5 m"})
    EXPECT_EQ(one(s).type(), Type::String) << s;
}

// What `rosparam load` puts on the parameter server: PyYAML's float resolver wants a dot, a signed
// exponent, and no sign before a leading dot (yaml.safe_load('a: 5e-2') gives the string '5e-2').
TEST(ParamYaml, FloatsAsRosparamTypesThem)
{
  auto typed = [](const std::string& text) { return parseParamsYaml("v: " + text, "t", true).find("v")->type(); };
  for (const char* f : {"1.0", "-2.5", "+0.25", "1.", ".5", "1.0e+3", "2.5E-2", "1.e+3", "6.02e+23", ".inf", "-.inf",
                        ".nan", "1_000.5"})
    EXPECT_EQ(typed(f), Type::Double) << f;
  for (const char* s : {"5e-2", "1e3", "1e+3", "1.0e1", "-.5", "+.5", "2.5E2"})
    EXPECT_EQ(typed(s), Type::String) << s;
  EXPECT_EQ(typed("42"), Type::Int);
  // The default (costmap_layers' own files) keeps reading them as numbers.
  EXPECT_EQ(parseParamsYaml("v: 5e-2", "t").find("v")->type(), Type::Double);
}

TEST(ParamYaml, NullsAndStrings)
{
  for (const char* n : {"~", "null", "Null", "NULL", ""})
    EXPECT_EQ(one(n).type(), Type::Null) << "'" << n << "'";
  EXPECT_EQ(one("map").asString(), "map");
  EXPECT_EQ(one("base_link").asString(), "base_link");
  EXPECT_EQ(one("hello world").asString(), "hello world");
  EXPECT_EQ(one("2024-01-01").asString(), "2024-01-01");
}

TEST(ParamYaml, QuotedAndBlockScalarsAreAlwaysStrings)
{
  for (const char* q : {"'true'", "\"true\"", "'42'", "\"1.5\"", "'null'", "\"~\"", "'.inf'", "''"})
  {
    const ParamValue v = one(q);
    ASSERT_EQ(v.type(), Type::String) << q;
  }
  EXPECT_EQ(one("'42'").asString(), "42");
  EXPECT_EQ(one("''").asString(), "");
  const ParamValue root = parseParamsYaml("a: |\n  42\nb: >\n  true\n", "test");
  EXPECT_EQ(root.find("a")->asString(), "42\n");
  EXPECT_EQ(root.find("b")->asString(), "true\n");
}

TEST(ParamYaml, ExplicitTags)
{
  EXPECT_EQ(one("!!str 42").asString(), "42");
  EXPECT_EQ(one("!!str true").type(), Type::String);
  const ParamValue f = one("!!float 3");
  ASSERT_EQ(f.type(), Type::Double);
  EXPECT_DOUBLE_EQ(f.asDouble(), 3.0);
  EXPECT_EQ(one("!!int 12").asInt(), 12);
  EXPECT_TRUE(one("!!bool yes").asBool());
  EXPECT_EQ(one("!!null ~").type(), Type::Null);
  // unknown local tags are ignored: typed as plain
  EXPECT_EQ(one("!degrees 90").asInt(), 90);
  EXPECT_NE(errorOf([] { one("!!int abc"); }).find("!!int"), std::string::npos);
  EXPECT_NE(errorOf([] { one("!!float abc"); }).find("!!float"), std::string::npos);
  EXPECT_NE(errorOf([] { one("!!bool maybe"); }).find("!!bool"), std::string::npos);
}

TEST(ParamYaml, StructureKeepsKeyOrderAndNests)
{
  const std::string text =
      "zeta: 1\n"
      "alpha:\n"
      "  plugins: [static_layer, inflation_layer]\n"
      "  inflation_layer:\n"
      "    inflation_radius: 0.55\n"
      "    enabled: true\n"
      "  footprint: [[0.1, 0.2], [-0.1, 0.2], [-0.1, -0.2]]\n"
      "mid: {b: 2, a: 1}\n"
      "empty_list: []\n"
      "empty_map: {}\n";
  const ParamValue root = parseParamsYaml(text, "test");
  ASSERT_TRUE(root.isMap());
  EXPECT_EQ(keys(root), (std::vector<std::string>{"zeta", "alpha", "mid", "empty_list", "empty_map"}));
  EXPECT_EQ(keys(*root.find("mid")), (std::vector<std::string>{"b", "a"}));
  const ParamValue* plugins = root.findPath("alpha/plugins");
  ASSERT_NE(plugins, nullptr);
  ASSERT_TRUE(plugins->isList());
  ASSERT_EQ(plugins->asList().size(), 2u);
  EXPECT_EQ(plugins->asList()[1].asString(), "inflation_layer");
  EXPECT_DOUBLE_EQ(root.findPath("alpha/inflation_layer/inflation_radius")->asDouble(), 0.55);
  EXPECT_TRUE(root.findPath("alpha/inflation_layer/enabled")->asBool());
  const auto& fp = root.findPath("alpha/footprint")->asList();
  ASSERT_EQ(fp.size(), 3u);
  EXPECT_DOUBLE_EQ(fp[2].asList()[1].asDouble(), -0.2);
  EXPECT_TRUE(root.find("empty_list")->isList());
  EXPECT_TRUE(root.find("empty_list")->asList().empty());
  EXPECT_TRUE(root.find("empty_map")->isMap());
  EXPECT_TRUE(root.find("empty_map")->entries().empty());
  // Empty document and a top-level list.
  EXPECT_TRUE(parseParamsYaml("", "test").isNull());
  EXPECT_TRUE(parseParamsYaml("# only a comment\n", "test").isNull());
  EXPECT_EQ(parseParamsYaml("- 1\n- two\n", "test").asList().size(), 2u);
  // A repeated key: first position, last value.
  const ParamValue dup = parseParamsYaml("a: 1\nb: 2\na: 3\n", "test");
  EXPECT_EQ(keys(dup), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(dup.find("a")->asInt(), 3);
}

TEST(ParamYaml, RepeatedKeysAreDescribedWhenAsked)
{
  std::vector<std::string> repeated;
  const ParamValue root =
      parseParamsYaml("a: 1\nb:\n  c: 2\n  d: 3\n  c: 4\na: 5\ne: {f: 1, f: 2}\n", "p.yaml", false, &repeated);
  EXPECT_EQ(root.findPath("b/c")->asInt(), 4);  // the last value, as without the list
  EXPECT_EQ(root.find("a")->asInt(), 5);
  ASSERT_EQ(repeated.size(), 3u);
  EXPECT_EQ(repeated[0],
            "p.yaml at line 5: key 'c' is written twice in one map (first at line 3); the last value is used");
  EXPECT_EQ(repeated[1],
            "p.yaml at line 6: key 'a' is written twice in one map (first at line 1); the last value is used");
  EXPECT_NE(repeated[2].find("key 'f' is written twice"), std::string::npos) << repeated[2];
  // Not repeats: the same key in two maps, a key that overrides a merged map's, the same key in list items.
  repeated.clear();
  parseParamsYaml("x: {k: 1}\ny: {k: 2}\nbase: &b {k: 1}\nz:\n  <<: *b\n  k: 2\nl: [{k: 1}, {k: 2}]\n", "q", false,
                  &repeated);
  EXPECT_TRUE(repeated.empty()) << repeated.front();
  // Many repeats: 20 lines and one that counts the rest; a long key is cut.
  std::string many;
  for (int i = 0; i < 1000; ++i)
    many += "k: " + std::to_string(i) + "\n";
  many += std::string(100, 'x') + ": 1\n" + std::string(100, 'x') + ": 2\n";
  repeated.clear();
  EXPECT_EQ(parseParamsYaml(many, "m", false, &repeated).find("k")->asInt(), 999);
  ASSERT_EQ(repeated.size(), 21u);
  EXPECT_EQ(repeated.back(), "m: 980 more keys written twice (not listed); the last value of each is used");
  repeated.clear();
  parseParamsYaml(std::string(100, 'y') + ": 1\n" + std::string(100, 'y') + ": 2\n", "long", false, &repeated);
  ASSERT_EQ(repeated.size(), 1u);
  EXPECT_NE(repeated[0].find("key '" + std::string(64, 'y') + "...' is written twice"), std::string::npos)
      << repeated[0];
}

TEST(ParamYaml, AliasesAndMergeKeys)
{
  const std::string text =
      "base: &base {radius: 0.5, enabled: true}\n"
      "other: &other {radius: 0.7, cost: 3}\n"
      "copy: *base\n"
      "derived:\n"
      "  <<: *base\n"
      "  enabled: false\n"
      "both:\n"
      "  <<: [*base, *other]\n";
  const ParamValue root = parseParamsYaml(text, "test");
  EXPECT_DOUBLE_EQ(root.findPath("copy/radius")->asDouble(), 0.5);
  EXPECT_DOUBLE_EQ(root.findPath("derived/radius")->asDouble(), 0.5);
  EXPECT_FALSE(root.findPath("derived/enabled")->asBool());
  EXPECT_EQ(root.findPath("derived/<<"), nullptr);
  EXPECT_DOUBLE_EQ(root.findPath("both/radius")->asDouble(), 0.5);  // the first merged map wins
  EXPECT_EQ(root.findPath("both/cost")->asInt(), 3);
  EXPECT_NE(errorOf([] { parseParamsYaml("a:\n  <<: 3\n", "test"); }).find("merge"), std::string::npos);
}

TEST(ParamYaml, SyntaxErrorsNameTheSourceAndLine)
{
  const std::string e1 = errorOf([] { parseParamsYaml("a: 1\nb: [1, 2\nc: 3\n", "my_params.yaml"); });
  EXPECT_NE(e1.find("my_params.yaml"), std::string::npos) << e1;
  EXPECT_NE(e1.find("syntax error at line"), std::string::npos) << e1;
  EXPECT_EQ(e1.find('\n'), std::string::npos) << e1;
  const std::string e2 = errorOf([] { parseParamsYaml("a: 1\n  b: 2\n", "inline"); });
  EXPECT_NE(e2.find("inline: YAML syntax error at line 2"), std::string::npos) << e2;
  const std::string e3 = errorOf([] { parseParamsYaml("a: b: c\n", "q"); });
  EXPECT_NE(e3.find("q: YAML syntax error"), std::string::npos) << e3;
  const std::string e4 = errorOf([] { parseParamsYaml("? [1, 2]\n: x\n", "k"); });
  EXPECT_NE(e4.find("map key"), std::string::npos) << e4;
  EXPECT_NE(e4.find("k at line 1"), std::string::npos) << e4;
}

TEST(ParamYaml, Files)
{
  char pattern[] = "/tmp/costmap_io_params_XXXXXX";
  const char* dir = mkdtemp(pattern);
  ASSERT_NE(dir, nullptr);
  const std::string path = std::string(dir) + "/params.yaml";
  {
    std::ofstream out(path);
    out << "costmap:\n  resolution: 0.05\n  plugins: [a, b]\n  track_unknown_space: yes\n";
  }
  const ParamValue root = loadParamsYamlFile(path);
  EXPECT_DOUBLE_EQ(root.findPath("costmap/resolution")->asDouble(), 0.05);
  EXPECT_TRUE(root.findPath("costmap/track_unknown_space")->asBool());
  {
    std::ofstream out(path);
    out << "a: 1\nb: {c: 2\n";
  }
  const std::string bad = errorOf([&] { loadParamsYamlFile(path); });
  EXPECT_NE(bad.find(path), std::string::npos) << bad;
  EXPECT_NE(bad.find("line"), std::string::npos) << bad;
  const std::string missing = errorOf([&] { loadParamsYamlFile(std::string(dir) + "/none.yaml"); });
  EXPECT_NE(missing.find("none.yaml"), std::string::npos) << missing;
  EXPECT_NE(missing.find("cannot open"), std::string::npos) << missing;
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
}
}  // namespace

// A features file is this package's own format: a key written twice would drop its first value (here a
// whole list of limits), so the file is refused, naming both lines; the same limits once load.
TEST(FeaturesFile, AKeyWrittenTwiceRefusesTheFile)
{
  char pattern[] = "/tmp/costmap_io_features_XXXXXX";
  const char* dir = mkdtemp(pattern);
  ASSERT_NE(dir, nullptr);
  const std::string path = std::string(dir) + "/features.yaml";
  std::ofstream(path) << "limits: [{area_id: 1, max_speed: 0.5}]\nlimits: [{area_id: 2, max_speed: 0.3}]\n";
  const std::string e = errorOf([&] { costmap_layers::io::loadFeaturesFile(path); });
  EXPECT_NE(e.find(path + "' at line 2: key 'limits' is written twice in one map (first at line 1)"), std::string::npos)
      << e;
  EXPECT_NE(e.find("refused"), std::string::npos) << e;
  std::ofstream(path) << "limits: [{area_id: 1, max_speed: 0.5}, {area_id: 2, max_speed: 0.3}]\n";
  EXPECT_EQ(costmap_layers::io::loadFeaturesFile(path).limits.size(), 2u);
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
}

// features_server says at load what every SpeedFilter will drop or remark (m/s rules, any mode):
// an area id outside the mask's 1..100, a speed that is not a finite number >= 0, a repeated id.
TEST(FeaturesFile, ProblemsEverySpeedFilterWouldReportAreListed)
{
  const ParamValue tree = parseParamsYaml(
      "limits: [{area_id: 1, max_speed: 0.5}, {area_id: 0, max_speed: 0.3}, {area_id: 2, max_speed: -1.0},\n"
      "         {area_id: 3, max_speed: .nan}, {area_id: 1, max_speed: 0.4}, {area_id: 101, max_speed: 1.0}]\n",
      "features.yaml");
  const std::vector<std::string> lines = featuresFileProblems(speedLimitsFromParams(tree, "features.yaml"));
  auto has = [&](const std::string& a, const std::string& b)
  {
    return std::any_of(lines.begin(), lines.end(),
                       [&](const std::string& l)
                       { return l.find(a) != std::string::npos && l.find(b) != std::string::npos; });
  };
  EXPECT_EQ(lines.size(), 5u);
  EXPECT_TRUE(has("error: limits[1] (area_id 0", "1..100"));
  EXPECT_TRUE(has("error: limits[2] (area_id 2, max_speed -1)", ">= 0"));
  EXPECT_TRUE(has("error: limits[3] (area_id 3, max_speed nan)", "finite"));
  EXPECT_TRUE(has("warning: limits[4] (area_id 1", "repeats area id 1"));
  EXPECT_TRUE(has("error: limits[5] (area_id 101", "1..100"));
  const ParamValue good = parseParamsYaml("limits: [{area_id: 1, max_speed: 0.5}, {area_id: 2, max_speed: 0}]", "f");
  EXPECT_TRUE(featuresFileProblems(speedLimitsFromParams(good, "f")).empty());
}

namespace
{
/// Equal trees: the same types, keys in the same order, and bit-for-bit the same doubles (a zero's sign
/// included; NaN equals NaN), so that a write and a read lose nothing.
::testing::AssertionResult sameTree(const ParamValue& a, const ParamValue& b, const std::string& at = "/")
{
  if (a.type() != b.type())
    return ::testing::AssertionFailure() << at << ": " << ParamValue::typeName(a.type()) << " vs "
                                         << ParamValue::typeName(b.type());
  switch (a.type())
  {
    case Type::Null:
      return ::testing::AssertionSuccess();
    case Type::Bool:
      if (a.asBool() == b.asBool()) return ::testing::AssertionSuccess();
      break;
    case Type::Int:
      if (a.asInt() == b.asInt()) return ::testing::AssertionSuccess();
      break;
    case Type::Double:
    {
      const double x = a.asDouble(), y = b.asDouble();
      if ((std::isnan(x) && std::isnan(y)) || (x == y && std::signbit(x) == std::signbit(y)))
        return ::testing::AssertionSuccess();
      break;
    }
    case Type::String:
      if (a.asString() == b.asString()) return ::testing::AssertionSuccess();
      break;
    case Type::List:
    {
      if (a.asList().size() != b.asList().size()) break;
      for (std::size_t k = 0; k < a.asList().size(); ++k)
      {
        auto r = sameTree(a.asList()[k], b.asList()[k], at + std::to_string(k) + "/");
        if (!r) return r;
      }
      return ::testing::AssertionSuccess();
    }
    case Type::Map:
    {
      if (a.entries().size() != b.entries().size()) break;
      for (std::size_t k = 0; k < a.entries().size(); ++k)
      {
        if (a.entries()[k].first != b.entries()[k].first)
          return ::testing::AssertionFailure()
                 << at << ": key '" << a.entries()[k].first << "' vs '" << b.entries()[k].first << "'";
        auto r = sameTree(a.entries()[k].second, b.entries()[k].second, at + a.entries()[k].first + "/");
        if (!r) return r;
      }
      return ::testing::AssertionSuccess();
    }
  }
  return ::testing::AssertionFailure() << at << ": " << a.toString() << " vs " << b.toString();
}

ParamValue str(const std::string& s)
{
  return ParamValue::makeString(s);
}

ParamValue dbl(double d)
{
  return ParamValue::makeDouble(d);
}
}  // namespace

// The layout people write costmap files in (and the hand-written emitter this replaced wrote): block
// maps, inline lists, quoted strings, doubles with a point.
TEST(Yaml, RendersBlockMapsAndInlineLists)
{
  ParamValue ns = ParamValue::makeMap();
  ParamValue layer = ParamValue::makeMap();
  layer.set("observation_sources", str("scan"));
  ParamValue scan = ParamValue::makeMap();
  scan.set("marking", ParamValue::makeBool(true));
  scan.set("range", ParamValue::makeInt(3));
  layer.set("scan", scan);
  ns.set("obstacle_layer", layer);
  ns.set("footprint", ParamValue::makeList({ParamValue::makeList({dbl(1), dbl(2.5)})}));
  EXPECT_EQ(paramToYaml(ns),
            "obstacle_layer:\n  observation_sources: \"scan\"\n  scan:\n    marking: true\n    range: 3\n"
            "footprint: [[1.0, 2.5]]\n");
}

// costmap_node and costmap_tool print the plugin list a pre-Hydro namespace converts to in the form
// costmap_2d's files use: a block list of inline {name, type} maps, then each layer's namespace.
TEST(ParamToYaml, PreHydroPluginListInCostmap2dsForm)
{
  ParamValue ns = ParamValue::makeMap();
  ns.set("static_map", ParamValue::makeBool(true));
  ns.set("inflation_radius", dbl(1.0));
  ns.set("cost_scaling_factor", dbl(3.0));
  ns.set("observation_sources", str("scan"));
  ParamValue scan = ParamValue::makeMap();
  scan.set("topic", str("scan"));
  ns.set("scan", scan);
  const costmap_layers::CompatResult r = costmap_layers::applyCostmap2dRules(ns);
  ASSERT_TRUE(r.converted_pre_hydro);
  const std::string text = paramToYaml(r.plugin_list);
  EXPECT_EQ(text.rfind("plugins:\n  - {name: \"static_layer\", type: \"costmap_2d::StaticLayer\"}\n"
                       "  - {name: \"obstacle_layer\", type: \"costmap_2d::ObstacleLayer\"}\n"
                       "  - {name: \"inflation_layer\", type: \"costmap_2d::InflationLayer\"}\n",
                       0),
            0u)
      << text;
  EXPECT_NE(text.find("inflation_layer:\n  cost_scaling_factor: 3.0\n  inflation_radius: 1.0\n"), std::string::npos)
      << text;
  EXPECT_TRUE(sameTree(parseParamsYaml(text, "plugin list", true), r.plugin_list));
}

TEST(ParamToYaml, DoublesHaveAPointInTheShortestFormThatReadsBack)
{
  auto written = [](double d)
  {
    ParamValue m = ParamValue::makeMap();
    m.set("v", dbl(d));
    return paramToYaml(m);
  };
  EXPECT_EQ(written(3.0), "v: 3.0\n");
  EXPECT_EQ(written(0.1), "v: 0.1\n");
  EXPECT_EQ(written(-2.5), "v: -2.5\n");
  EXPECT_EQ(written(-0.0), "v: -0.0\n");
  // PyYAML (rosparam) reads "1e-300" as a string: a point and a signed exponent make it a float.
  EXPECT_EQ(written(1e-300), "v: 1.0e-300\n");
  EXPECT_EQ(written(1e300), "v: 1.0e+300\n");
  EXPECT_EQ(written(std::numeric_limits<double>::infinity()), "v: .inf\n");
  EXPECT_EQ(written(-std::numeric_limits<double>::infinity()), "v: -.inf\n");
  EXPECT_EQ(written(std::numeric_limits<double>::quiet_NaN()), "v: .nan\n");
  EXPECT_EQ(paramToYaml(ParamValue()), "null\n");
  EXPECT_EQ(paramToYaml(ParamValue::makeMap()), "{}\n");
  EXPECT_EQ(paramToYaml(ParamValue::makeList({dbl(1), ParamValue::makeInt(1)})), "[1.0, 1]\n");
}

TEST(ParamToYaml, ReadsBackToAnEqualTree)
{
  ParamValue tree = ParamValue::makeMap();
  const std::vector<std::string> awkward = {"say \"hi\"",
                                            "back\\slash",
                                            "a: b",
                                            "key: value # not a comment",
                                            "line one\nline two",
                                            "  leading spaces",
                                            "trailing spaces  ",
                                            "true",
                                            "no",
                                            "null",
                                            "~",
                                            "1e3",
                                            "0x10",
                                            "010",
                                            "1:30",
                                            ".inf",
                                            "- dash",
                                            "[not a list]",
                                            "{not: a map}",
                                            "&anchor",
                                            "*alias",
                                            "!tag",
                                            "%directive",
                                            "@at",
                                            "`tick",
                                            "tab\there",
                                            "\x01\x7f",
                                            "é ü 中",
                                            "",
                                            "'single'",
                                            "<<"};
  ParamValue strings = ParamValue::makeList();
  for (const auto& s : awkward)
    strings.push(str(s));
  tree.set("strings", strings);
  // The same texts as keys (always strings when read), in a block map and in an inline one.
  ParamValue keyed = ParamValue::makeMap();
  for (const auto& s : awkward)
    keyed.set(s, str(s));
  tree.set("keyed", keyed);
  tree.set("keyed_inline", ParamValue::makeList({keyed}));
  const std::vector<double> doubles = {0.1,
                                       1e-300,
                                       1e300,
                                       3.0,
                                       -0.0,
                                       1.0 / 3.0,
                                       123456789012345678.0,
                                       std::numeric_limits<double>::min(),
                                       std::numeric_limits<double>::denorm_min(),
                                       std::numeric_limits<double>::max(),
                                       std::numeric_limits<double>::lowest(),
                                       std::numeric_limits<double>::epsilon(),
                                       std::numeric_limits<double>::infinity(),
                                       -std::numeric_limits<double>::infinity(),
                                       std::numeric_limits<double>::quiet_NaN()};
  ParamValue numbers = ParamValue::makeList();
  for (const double d : doubles)
    numbers.push(dbl(d));
  for (const int64_t i :
       {int64_t{0}, int64_t{-7}, std::numeric_limits<int64_t>::max(), std::numeric_limits<int64_t>::min()})
    numbers.push(ParamValue::makeInt(i));
  tree.set("numbers", numbers);
  ParamValue mixed = ParamValue::makeMap();
  mixed.set("null", ParamValue());
  mixed.set("bools", ParamValue::makeList({ParamValue::makeBool(true), ParamValue::makeBool(false)}));
  mixed.set("empty_list", ParamValue::makeList());
  mixed.set("empty_map", ParamValue::makeMap());
  mixed.set("list_of_maps_and_more",
            ParamValue::makeList({keyed, str("x"), ParamValue::makeList({dbl(0.5)}), ParamValue()}));
  ParamValue deep = ParamValue::makeMap();
  deep.set("inner", mixed);
  mixed.set("deep", deep);
  tree.set("mixed", mixed);

  const std::string text = paramToYaml(tree);
  for (const bool rosparam_floats : {false, true})
  {
    const ParamValue back = parseParamsYaml(text, "written", rosparam_floats);
    EXPECT_TRUE(sameTree(back, tree)) << "rosparam_floats " << rosparam_floats << "\n" << text;
  }
  // Not only a map at the top.
  EXPECT_TRUE(sameTree(parseParamsYaml(paramToYaml(strings), "list"), strings));
  EXPECT_TRUE(sameTree(parseParamsYaml(paramToYaml(str("a: b")), "scalar"), str("a: b")));
}
