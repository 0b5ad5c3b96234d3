// dynamic_reconfigure for a layer without a node: the description its specs make (describe), the values
// as a Config (toConfig), and what a set_parameters request does to the parameters (applyConfig, the
// part of LayerReconfigure::onSet that needs no layer and no master).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "costmap_layers/ros/layer_reconfigure.hpp"

using costmap_layers::ParamSpec;
using costmap_layers::ParamValue;
using costmap_layers_ros::LayerReconfigure;

namespace
{
ParamSpec spec(const std::string& name, ParamValue::Type type, ParamValue dflt, ParamValue value, double min = 0.0,
               double max = 0.0, std::vector<std::string> choices = {})
{
  ParamSpec s;
  s.name = name;
  s.type = type;
  s.default_value = std::move(dflt);
  s.value = std::move(value);
  s.min = min;
  s.max = max;
  s.choices = std::move(choices);
  return s;
}

/// A layer's four kinds of tunable parameter, each with a value other than its default.
std::vector<ParamSpec> specs()
{
  return {
      spec("enabled", ParamValue::Type::Bool, ParamValue::makeBool(true), ParamValue::makeBool(false)),
      spec("radius", ParamValue::Type::Double, ParamValue::makeDouble(0.5), ParamValue::makeDouble(0.75), -1e12, 2e9),
      spec("cells", ParamValue::Type::Int, ParamValue::makeInt(3), ParamValue::makeInt(4), 1, 10),
      spec("mode", ParamValue::Type::String, ParamValue::makeString("max"), ParamValue::makeString("add"), 0, 0,
           {"max", "add"})};
}

void expectDefaultGroup(const dynamic_reconfigure::Config& c)
{
  ASSERT_EQ(c.groups.size(), 1u);
  EXPECT_EQ(c.groups[0].name, "Default");
  EXPECT_TRUE(c.groups[0].state);
  EXPECT_EQ(c.groups[0].id, 0);
  EXPECT_EQ(c.groups[0].parent, 0);
}
}  // namespace

TEST(LayerReconfigure, ToConfigListsEachValueUnderItsType)
{
  const dynamic_reconfigure::Config c = LayerReconfigure::toConfig(specs(), false);
  ASSERT_EQ(c.bools.size(), 1u);
  EXPECT_EQ(c.bools[0].name, "enabled");
  EXPECT_FALSE(c.bools[0].value);
  ASSERT_EQ(c.doubles.size(), 1u);
  EXPECT_EQ(c.doubles[0].name, "radius");
  EXPECT_EQ(c.doubles[0].value, 0.75);
  ASSERT_EQ(c.ints.size(), 1u);
  EXPECT_EQ(c.ints[0].name, "cells");
  EXPECT_EQ(c.ints[0].value, 4);
  ASSERT_EQ(c.strs.size(), 1u);
  EXPECT_EQ(c.strs[0].name, "mode");
  EXPECT_EQ(c.strs[0].value, "add");
  expectDefaultGroup(c);
}

TEST(LayerReconfigure, ToConfigGivesDefaultsAndBounds)
{
  const dynamic_reconfigure::Config d = LayerReconfigure::toConfig(specs(), true);
  EXPECT_TRUE(d.bools[0].value);
  EXPECT_EQ(d.doubles[0].value, 0.5);
  EXPECT_EQ(d.ints[0].value, 3);
  EXPECT_EQ(d.strs[0].value, "max");
  // Upper bounds: true, max clamped to 1e9 (rqt cannot show more), the int max, no string.
  const dynamic_reconfigure::Config hi = LayerReconfigure::toConfig(specs(), false, 1);
  EXPECT_TRUE(hi.bools[0].value);
  EXPECT_EQ(hi.doubles[0].value, 1e9);
  EXPECT_EQ(hi.ints[0].value, 10);
  EXPECT_EQ(hi.strs[0].value, "");
  const dynamic_reconfigure::Config lo = LayerReconfigure::toConfig(specs(), false, -1);
  EXPECT_FALSE(lo.bools[0].value);
  EXPECT_EQ(lo.doubles[0].value, -1e9);
  EXPECT_EQ(lo.ints[0].value, 1);
  EXPECT_EQ(lo.strs[0].value, "");
}

TEST(LayerReconfigure, DescribeNamesTypesChoicesAndRanges)
{
  std::vector<ParamSpec> defaults = specs();
  defaults[1].default_value = ParamValue::makeDouble(0.25);  // what the layer's parse gives with no parameters
  const dynamic_reconfigure::ConfigDescription d = LayerReconfigure::describe(specs(), defaults);
  ASSERT_EQ(d.groups.size(), 1u);
  EXPECT_EQ(d.groups[0].name, "Default");
  EXPECT_EQ(d.groups[0].type, "");
  const auto& p = d.groups[0].parameters;
  ASSERT_EQ(p.size(), 4u);
  EXPECT_EQ(p[0].name, "enabled");
  EXPECT_EQ(p[0].type, "bool");
  EXPECT_EQ(p[0].description, "enabled");
  EXPECT_EQ(p[1].type, "double");
  EXPECT_EQ(p[2].type, "int");
  EXPECT_EQ(p[3].name, "mode");
  EXPECT_EQ(p[3].type, "str");
  EXPECT_EQ(p[3].description, "mode (one of: max, add)");
  EXPECT_EQ(p[3].level, 0u);
  EXPECT_EQ(d.max.doubles[0].value, 1e9);
  EXPECT_EQ(d.min.ints[0].value, 1);
  EXPECT_EQ(d.dflt.doubles[0].value, 0.25);  // from the defaults, not the current values
  EXPECT_EQ(d.dflt.strs[0].value, "max");
  expectDefaultGroup(d.dflt);
}

TEST(LayerReconfigure, TypeNamesAndAddToConfig)
{
  EXPECT_STREQ(costmap_layers_ros::reconfigureTypeName(ParamValue::Type::Bool), "bool");
  EXPECT_STREQ(costmap_layers_ros::reconfigureTypeName(ParamValue::Type::Int), "int");
  EXPECT_STREQ(costmap_layers_ros::reconfigureTypeName(ParamValue::Type::Double), "double");
  EXPECT_STREQ(costmap_layers_ros::reconfigureTypeName(ParamValue::Type::String), "str");
  EXPECT_STREQ(costmap_layers_ros::reconfigureTypeName(ParamValue::Type::List), "str");
  dynamic_reconfigure::Config c;
  costmap_layers_ros::addToConfig(c, "n", ParamValue::makeInt(-7));
  costmap_layers_ros::addToConfig(c, "s", ParamValue::makeString("abc"));
  ASSERT_EQ(c.ints.size(), 1u);
  EXPECT_EQ(c.ints[0].value, -7);
  ASSERT_EQ(c.strs.size(), 1u);
  EXPECT_EQ(c.strs[0].value, "abc");
  EXPECT_TRUE(c.bools.empty());
  EXPECT_TRUE(c.doubles.empty());
}

TEST(LayerReconfigure, SetChangesKnownNamesAndKeepsTheRest)
{
  ParamValue current = ParamValue::makeMap();
  current.set("radius", ParamValue::makeDouble(0.5));
  current.set("topic", ParamValue::makeString("/map"));  // not tunable: kept as it is
  dynamic_reconfigure::Config req;
  dynamic_reconfigure::DoubleParameter radius;
  radius.name = "radius";
  radius.value = 1.25;
  req.doubles.push_back(radius);
  dynamic_reconfigure::BoolParameter enabled;
  enabled.name = "enabled";
  enabled.value = true;
  req.bools.push_back(enabled);
  const costmap_layers_ros::ReconfigureChange change = costmap_layers_ros::applyConfig(current, specs(), req);
  EXPECT_EQ(change.ignored_count, 0u);
  EXPECT_EQ(change.ignored, "");
  ASSERT_TRUE(change.next.find("radius"));
  EXPECT_EQ(change.next.find("radius")->asDouble(), 1.25);
  ASSERT_TRUE(change.next.find("enabled"));
  EXPECT_TRUE(change.next.find("enabled")->asBool());
  ASSERT_TRUE(change.next.find("topic"));
  EXPECT_EQ(change.next.find("topic")->asString(), "/map");
  EXPECT_EQ(current.find("radius")->asDouble(), 0.5);  // the current parameters are not touched
}

TEST(LayerReconfigure, SetIgnoresNamesThatCannotChange)
{
  dynamic_reconfigure::Config req;
  dynamic_reconfigure::StrParameter s;
  s.name = "bogus";
  s.value = "x";
  req.strs.push_back(s);
  dynamic_reconfigure::IntParameter i;
  i.name = "unknown_a";
  i.value = 1;
  req.ints.push_back(i);
  dynamic_reconfigure::IntParameter cells;
  cells.name = "cells";
  cells.value = 9;
  req.ints.push_back(cells);
  // Not a map (nothing was set): the change starts from an empty map.
  const auto change = costmap_layers_ros::applyConfig(ParamValue(), specs(), req);
  EXPECT_EQ(change.ignored_count, 2u);
  EXPECT_EQ(change.ignored, " unknown_a bogus");  // ints are read before strs
  ASSERT_TRUE(change.next.isMap());
  EXPECT_EQ(change.next.entries().size(), 1u);
  EXPECT_EQ(change.next.find("cells")->asInt(), 9);
}

TEST(LayerReconfigure, AFloodOfNamesIsClippedAndCounted)
{
  dynamic_reconfigure::Config req;
  for (int k = 0; k < 10; ++k)
  {
    dynamic_reconfigure::BoolParameter b;
    b.name = "n" + std::to_string(k);
    req.bools.push_back(b);
  }
  dynamic_reconfigure::BoolParameter huge;
  huge.name = std::string(100, 'x');
  req.bools.insert(req.bools.begin(), huge);
  const auto change = costmap_layers_ros::applyConfig(ParamValue::makeMap(), specs(), req);
  EXPECT_EQ(change.ignored_count, 11u);
  EXPECT_EQ(change.ignored, " " + std::string(64, 'x') + "... (100 characters) n0 n1 n2 n3 n4 n5 n6 (11 in all)");
}
