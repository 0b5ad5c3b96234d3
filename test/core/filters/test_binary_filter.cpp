// BinaryFilter: Nav2's flip rule, the state published along a route over a mask (initial state, on
// change only, unknown cells, leaving the mask), Nav2's filter-info form, and bad configuration.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "costmap_layers/core/filters/binary_filter.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;
using costmap_layers_test::GridKind;

namespace
{
/// A 10 x 1 mask at 1 m, origin (0, 0), holding `values` from x = 0 on.
OccupancyGridData rowMask(const std::vector<int8_t>& values)
{
  OccupancyGridData m;
  m.frame_id = "map";
  m.width = static_cast<uint32_t>(values.size());
  m.height = 1;
  m.resolution = 1.0;
  m.data = values;
  return m;
}

struct Rig
{
  LayeredCostmap lc{"map", false, false};
  std::shared_ptr<FakeContext> ctx;
  std::shared_ptr<BinaryFilter> filter = std::make_shared<BinaryFilter>();

  explicit Rig(ParamValue p = ParamValue::makeMap()) : ctx(std::make_shared<FakeContext>(std::move(p)))
  {
    filter->initialize(&lc, "binary_filter", ctx);
    ctx->bind(*filter);
  }
  /// One update cycle with the robot at (x, 0.5).
  void at(double x)
  {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    filter->updateBounds(x, 0.5, 0.0, &x0, &y0, &x1, &y1);
  }
};

ParamValue withParam(const std::string& name, ParamValue value)
{
  ParamValue p = ParamValue::makeMap();
  p.set(name, std::move(value));
  return p;
}
}  // namespace

TEST(BinaryFilterConfig, NavTwoDefaults)
{
  const ParamValue empty = ParamValue::makeMap();
  const BinaryFilterConfig c = parseBinaryFilterConfig(ParamReader(empty, "binary"));
  EXPECT_EQ(c.binary_state_topic, "binary_state");
  EXPECT_FALSE(c.default_state);
  EXPECT_EQ(c.flip_threshold, 50.0);
  EXPECT_EQ(c.base, 0.0);
  EXPECT_EQ(c.multiplier, 1.0);
}

TEST(BinaryFilterConfig, BadValuesNameTheParameter)
{
  auto fails = [](const ParamValue& p, const std::string& name)
  {
    try
    {
      parseBinaryFilterConfig(ParamReader(p, "binary"));
    }
    catch (const std::invalid_argument& e)
    {
      return std::string(e.what()).find("'" + name + "'") != std::string::npos;
    }
    return false;
  };
  EXPECT_TRUE(fails(withParam("flip_threshold", ParamValue::makeDouble(std::nan(""))), "flip_threshold"));
  EXPECT_TRUE(fails(withParam("flip_threshold", ParamValue::makeDouble(INFINITY)), "flip_threshold"));
  EXPECT_TRUE(fails(withParam("base", ParamValue::makeDouble(-INFINITY)), "base"));
  EXPECT_TRUE(fails(withParam("multiplier", ParamValue::makeString("two")), "multiplier"));
  EXPECT_TRUE(fails(withParam("default_state", ParamValue::makeString("yes")), "default_state"));
  EXPECT_TRUE(fails(withParam("binary_state_topic", ParamValue::makeString("")), "binary_state_topic"));
  ParamValue both = withParam("filter_info_topic", ParamValue::makeString("/binary_info"));
  both.set("multiplier", ParamValue::makeDouble(2.0));
  EXPECT_TRUE(fails(both, "multiplier"));
}

TEST(BinaryFilterRule, FlipsAboveTheThresholdOnly)
{
  // base 0, multiplier 1, threshold 50: the filter-space value is v itself, so v = 51..100 flip.
  for (int v = 0; v <= 100; ++v)
  {
    EXPECT_EQ(binaryState(v, 0.0, 1.0, 50.0, false), v >= 51) << v;
    EXPECT_EQ(binaryState(v, 0.0, 1.0, 50.0, true), v <= 50) << v;
  }
  // base 10, multiplier 2: 10 + 2 v > 50 <=> v > 20; base 100, multiplier -1: 100 - v > 50 <=> v < 50.
  for (int v = 0; v <= 100; ++v)
  {
    EXPECT_EQ(binaryState(v, 10.0, 2.0, 50.0, false), v > 20) << v;
    EXPECT_EQ(binaryState(v, 100.0, -1.0, 50.0, false), v < 50) << v;
  }
}

TEST(BinaryFilter, PublishesTheInitialStateThenChangesOnly)
{
  Rig rig;
  ASSERT_EQ(rig.ctx->binary_state_topic, "binary_state");
  EXPECT_EQ(rig.ctx->published_states, std::vector<bool>{false});  // at start, latched
  // No mask yet: default, nothing new.
  rig.at(0.5);
  EXPECT_EQ(rig.ctx->published_states.size(), 1u);
  rig.ctx->publishGrid(GridKind::Mask, rowMask({0, 0, 60, 60, -1, 60, 50, 51, 0, 100}));
  // The route: x = 0.5 .. 9.5, then off the mask, then back on a flipping cell.
  const std::vector<double> route{0.5, 1.5, 2.5, 3.5, 4.5, 5.5, 6.5, 7.5, 8.5, 9.5, 12.0, 9.5};
  for (double x : route)
    rig.at(x);
  // 0 0 -> false; 60 -> true; 60; -1 keeps true; 60; 50 (not above) -> false; 51 -> true; 0 -> false;
  // 100 -> true; off the mask -> false; 100 -> true.
  EXPECT_EQ(rig.ctx->published_states, (std::vector<bool>{false, true, false, true, false, true, false, true}));
}

// Nav2's binary_filter_test testDifferentFrame: the mask in another frame than the costmap's; the
// robot's cell is looked up through the transform (map -> odom moves points by (-2, 0) here).
TEST(BinaryFilter, MaskInAnotherFrame)
{
  Rig rig;
  const Transform2D to_mask{-2.0, 0.0, 0.0};
  rig.ctx->transforms[{"odom", "map"}] = to_mask;
  rig.ctx->transforms[{"map", "odom"}] = to_mask.inverse();
  OccupancyGridData mask = rowMask({0, 100, 0, 100});
  mask.frame_id = "odom";
  rig.ctx->publishGrid(GridKind::Mask, mask);
  rig.at(2.5);  // odom 0.5: 0
  rig.at(3.5);  // odom 1.5: 100 -> flips
  rig.at(4.5);  // odom 2.5: 0
  rig.at(1.5);  // odom -0.5: off the mask, default (unchanged)
  rig.at(5.5);  // odom 3.5: 100
  EXPECT_EQ(rig.ctx->published_states, (std::vector<bool>{false, true, false, true}));
}

TEST(BinaryFilter, UnknownCellKeepsTheStateAndOffMaskIsDefault)
{
  ParamValue p = withParam("default_state", ParamValue::makeBool(true));
  Rig rig(p);
  EXPECT_EQ(rig.ctx->published_states, std::vector<bool>{true});
  rig.ctx->publishGrid(GridKind::Mask, rowMask({-1, 80, -1, 0}));
  rig.at(0.5);  // -1 first: keeps the initial (default) state
  rig.at(1.5);  // 80 > 50: flips to !default = false
  rig.at(2.5);  // -1: keeps false
  EXPECT_EQ(rig.ctx->published_states, (std::vector<bool>{true, false}));
  rig.at(-3.0);  // off the mask: default
  EXPECT_EQ(rig.ctx->published_states, (std::vector<bool>{true, false, true}));
}

TEST(BinaryFilter, SwitchedOffIsDefault)
{
  Rig rig;
  rig.ctx->publishGrid(GridKind::Mask, rowMask({90}));
  rig.at(0.5);
  ASSERT_EQ(rig.ctx->published_states, (std::vector<bool>{false, true}));
  rig.ctx->toggle(false);
  rig.at(0.5);
  EXPECT_EQ(rig.ctx->published_states, (std::vector<bool>{false, true, false}));
  rig.ctx->toggle(true);
  rig.at(0.5);
  EXPECT_EQ(rig.ctx->published_states, (std::vector<bool>{false, true, false, true}));
}

TEST(BinaryFilter, InvalidMaskValueIsDefaultWarnedOnce)
{
  Rig rig;
  rig.ctx->publishGrid(GridKind::Mask, rowMask({90, static_cast<int8_t>(120)}));
  rig.at(0.5);
  rig.at(1.5);
  rig.at(1.5);
  EXPECT_EQ(rig.ctx->published_states, (std::vector<bool>{false, true, false}));
  EXPECT_EQ(rig.ctx->countKey("mask/value"), 1);
}

TEST(BinaryFilter, FilterInfoGivesBaseAndMultiplier)
{
  Rig rig(withParam("filter_info_topic", ParamValue::makeString("/binary_info")));
  FilterInfoData info;
  info.type = 1;  // a speed info: refused, keyed by the field
  info.filter_mask_topic = "/binary_mask";
  rig.ctx->publishFilterInfo(info);
  EXPECT_EQ(rig.ctx->countKey("filter_info/type"), 1);
  info.type = filter_info::kBinary;
  info.base = 10.0;
  info.multiplier = 2.0;
  rig.ctx->publishFilterInfo(info);
  ASSERT_EQ(rig.ctx->publishGridOn("/binary_mask", rowMask({20, 21, 0})), 1);
  rig.at(0.5);  // 10 + 2 * 20 = 50: not above
  rig.at(1.5);  // 52: flips
  rig.at(2.5);  // 10: back
  EXPECT_EQ(rig.ctx->published_states, (std::vector<bool>{false, true, false}));
}
