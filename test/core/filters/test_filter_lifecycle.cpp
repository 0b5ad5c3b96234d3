// The filters' lifecycle (Nav2's resetFilter() and initializeFilter(); in ROS 1 move_base's costmap
// stop() and start(), which the bridge passes on as deactivate() and activate()): deactivate() drops the
// mask and the filter info (isActive() false, as Nav2's zone_parameter_filter_test expects after
// resetFilter()), puts the outputs to "no effect", ends the subscriptions and ignores what still
// arrives; activate() subscribes again and the filter waits for a new mask as at start. Every filter
// of the package, and the inputs of the same class: no mask yet, deactivate twice, a mask or an info
// arriving while deactivated, activate without deactivate, the filter_info_topic form.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "costmap_layers/core/filters/binary_filter.hpp"
#include "costmap_layers/core/filters/keepout_filter.hpp"
#include "costmap_layers/core/filters/lanes_filter.hpp"
#include "costmap_layers/core/filters/speed_filter.hpp"
#include "costmap_layers/core/filters/zone_parameter_filter.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;
using costmap_layers_test::GridKind;

namespace
{
constexpr uint64_t kSecond = 1'000'000'000;

OccupancyGridData makeMask(uint32_t w, uint32_t h, double ox, double oy, int8_t fill)
{
  OccupancyGridData m;
  m.frame_id = "map";
  m.width = w;
  m.height = h;
  m.resolution = 1.0;
  m.origin_x = ox;
  m.origin_y = oy;
  m.data.assign(static_cast<std::size_t>(w) * h, fill);
  return m;
}

/// A filter on a 10 x 10 master grid of 1 m cells (free, unknown not tracked), bound to a fake host.
template <class Filter>
struct Rig
{
  LayeredCostmap lc{"map", false, false};
  std::shared_ptr<FakeContext> ctx;
  std::shared_ptr<Filter> filter = std::make_shared<Filter>();

  explicit Rig(ParamValue p = ParamValue::makeMap()) : ctx(std::make_shared<FakeContext>(std::move(p)))
  {
    lc.resizeMap(10, 10, 1.0, 0.0, 0.0);
    filter->initialize(&lc, "filter", ctx);
    ctx->bind(*filter);
    lc.addFilter(filter);
  }
  /// One update of the whole costmap with the robot at (x, y).
  void update(double x = 0.5, double y = 0.5) { lc.updateMap(x, y, 0.0); }
  uint8_t cost(unsigned x, unsigned y) const { return lc.getCostmap().getCost(x, y); }
  /// The topic the host's mask subscription reads ("" when it ended).
  std::string subscribedMaskTopic() const { return ctx->grid_subs.at(0).topic; }
};

ParamValue withParam(ParamValue p, const std::string& name, ParamValue value)
{
  p.set(name, std::move(value));
  return p;
}
}  // namespace

// The case, with Nav2's expectation: after deactivate() the filter is not active, its mask is
// gone and so are its costs (cells 3..5 x 3..5 were lethal); it stays so after activate() until a new
// mask arrives, and then the zone is back.
TEST(FilterLifecycle, KeepoutDropsItsMaskAndCostsUntilANewMaskArrives)
{
  Rig<KeepoutFilter> rig;
  rig.ctx->publishGrid(GridKind::Mask, makeMask(3, 3, 3.0, 3.0, 100));
  rig.update();
  ASSERT_TRUE(rig.filter->isActive());
  ASSERT_EQ(rig.cost(4, 4), LETHAL_OBSTACLE);
  const std::string topic = rig.subscribedMaskTopic();
  ASSERT_FALSE(topic.empty());

  rig.filter->deactivate();
  EXPECT_FALSE(rig.filter->isActive());
  EXPECT_EQ(rig.filter->getMask(), nullptr);
  EXPECT_EQ(rig.subscribedMaskTopic(), "");  // the host ends the subscription
  rig.update();
  for (unsigned y = 0; y < 10; ++y)
    for (unsigned x = 0; x < 10; ++x)
      EXPECT_EQ(rig.cost(x, y), FREE_SPACE) << x << "," << y;
  EXPECT_EQ(rig.filter->status().level, StatusLevel::Ok);
  EXPECT_NE(rig.filter->status().message.find("deactivated"), std::string::npos) << rig.filter->status().message;

  rig.filter->activate();
  EXPECT_EQ(rig.subscribedMaskTopic(), topic);  // subscribed again: a latched mask comes anew
  EXPECT_FALSE(rig.filter->isActive());
  rig.update();
  EXPECT_EQ(rig.cost(4, 4), FREE_SPACE);  // the old mask does not come back by itself
  rig.ctx->publishGrid(GridKind::Mask, makeMask(3, 3, 3.0, 3.0, 100));
  EXPECT_TRUE(rig.filter->isActive());
  rig.update();
  EXPECT_EQ(rig.cost(4, 4), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.cost(2, 4), FREE_SPACE);
}

// Masks arriving while deactivated (from the subscription that is ending, or handed over directly) are
// ignored without an error: Nav2 has no subscription then. Deactivating twice does nothing more;
// activate() without deactivate() does nothing.
TEST(FilterLifecycle, WhatArrivesWhileDeactivatedIsIgnoredAndRepeatedCallsDoNothing)
{
  Rig<KeepoutFilter> rig;
  rig.ctx->publishGrid(GridKind::Mask, makeMask(3, 3, 3.0, 3.0, 100));
  rig.update();
  const int replaced = rig.ctx->replaced_inputs;
  rig.filter->activate();  // not deactivated: nothing happens
  EXPECT_EQ(rig.ctx->replaced_inputs, replaced);
  EXPECT_TRUE(rig.filter->isActive());

  rig.filter->deactivate();
  EXPECT_EQ(rig.ctx->replaced_inputs, replaced + 1);
  rig.filter->deactivate();
  EXPECT_EQ(rig.ctx->replaced_inputs, replaced + 1);
  rig.ctx->publishGrid(GridKind::Mask, makeMask(2, 2, 0.0, 0.0, 100));
  EXPECT_FALSE(rig.filter->setMask(std::make_shared<const OccupancyGridData>(makeMask(2, 2, 0.0, 0.0, 100))).empty());
  EXPECT_FALSE(rig.filter->isActive());
  EXPECT_EQ(rig.filter->getMask(), nullptr);
  rig.update();
  EXPECT_EQ(rig.cost(0, 0), FREE_SPACE);
  EXPECT_EQ(rig.cost(4, 4), FREE_SPACE);
  for (const auto& r : rig.ctx->reports)
    EXPECT_NE(r.severity, Severity::Error) << r.key << ": " << r.message;

  rig.filter->activate();
  EXPECT_EQ(rig.ctx->replaced_inputs, replaced + 2);
  rig.update();
  EXPECT_EQ(rig.cost(0, 0), FREE_SPACE);  // what came while deactivated was not kept for later
  EXPECT_FALSE(rig.filter->isActive());
}

// Deactivated before any mask came: nothing to drop, the filter still waits; after activate() the
// "no mask yet" warning waits out the start-up grace again (a latched mask comes moments after the
// subscription), and is said while deactivated never.
TEST(FilterLifecycle, DeactivatedBeforeAnyMaskWaitsAsAtStart)
{
  Rig<KeepoutFilter> rig;
  rig.ctx->now_ns = 1 * kSecond;
  rig.update();
  rig.ctx->now_ns = 4 * kSecond;
  rig.update();
  ASSERT_EQ(rig.ctx->countKey("waiting"), 1);  // at start, once the 2 s grace passed

  rig.filter->deactivate();
  EXPECT_FALSE(rig.filter->isActive());
  rig.ctx->now_ns = 10 * kSecond;
  rig.update();
  EXPECT_EQ(rig.ctx->countKey("waiting"), 1);

  rig.filter->activate();
  rig.ctx->now_ns = 11 * kSecond;
  rig.update();
  rig.ctx->now_ns = 12 * kSecond + kSecond / 2;
  rig.update();
  EXPECT_EQ(rig.ctx->countKey("waiting"), 1);  // within the grace of the new subscription
  EXPECT_EQ(rig.filter->status().level, StatusLevel::Warn);
  rig.ctx->now_ns = 13 * kSecond + kSecond / 2;
  rig.update();
  EXPECT_EQ(rig.ctx->countKey("waiting"), 2);
  rig.ctx->publishGrid(GridKind::Mask, makeMask(3, 3, 3.0, 3.0, 100));
  rig.update();
  EXPECT_TRUE(rig.filter->isActive());
  EXPECT_EQ(rig.cost(3, 3), LETHAL_OBSTACLE);
}

// Nav2's form: the info goes with the mask, and the reactivated filter waits for a new info, then for
// the mask on the topic it names. An info arriving while deactivated is ignored.
TEST(FilterLifecycle, FilterInfoFormDropsTheInfoAndWaitsForANewOne)
{
  Rig<KeepoutFilter> rig(withParam(ParamValue::makeMap(), "filter_info_topic", ParamValue::makeString("/info")));
  FilterInfoData info;
  info.type = filter_info::kKeepout;
  info.filter_mask_topic = "/keepout_mask";
  rig.ctx->publishFilterInfo(info);
  ASSERT_EQ(rig.ctx->publishGridOn("/keepout_mask", makeMask(3, 3, 3.0, 3.0, 100)), 1);
  rig.update();
  ASSERT_TRUE(rig.filter->isActive());
  ASSERT_EQ(rig.cost(4, 4), LETHAL_OBSTACLE);

  rig.filter->deactivate();
  EXPECT_FALSE(rig.filter->isActive());
  EXPECT_EQ(rig.filter->getFilterInfo(), nullptr);
  EXPECT_EQ(rig.filter->maskTopic(), "");
  EXPECT_EQ(rig.subscribedMaskTopic(), "");
  const int replaced = rig.ctx->replaced_inputs;
  rig.ctx->publishFilterInfo(info);  // ignored: no subscription to the mask follows
  EXPECT_EQ(rig.filter->getFilterInfo(), nullptr);
  EXPECT_EQ(rig.ctx->replaced_inputs, replaced);
  EXPECT_EQ(rig.ctx->publishGridOn("/keepout_mask", makeMask(3, 3, 3.0, 3.0, 100)), 0);
  rig.update();
  EXPECT_EQ(rig.cost(4, 4), FREE_SPACE);

  rig.filter->activate();
  EXPECT_EQ(rig.ctx->replaced_inputs, replaced + 1);  // the info's subscription, anew
  EXPECT_FALSE(rig.filter->isActive());
  rig.ctx->publishFilterInfo(info);  // the latched info, delivered to the new subscription
  EXPECT_NE(rig.filter->getFilterInfo(), nullptr);
  EXPECT_EQ(rig.subscribedMaskTopic(), "/keepout_mask");
  EXPECT_FALSE(rig.filter->isActive());  // an info alone is not enough
  ASSERT_EQ(rig.ctx->publishGridOn("/keepout_mask", makeMask(3, 3, 3.0, 3.0, 100)), 1);
  EXPECT_TRUE(rig.filter->isActive());
  rig.update();
  EXPECT_EQ(rig.cost(4, 4), LETHAL_OBSTACLE);
}

// LanesFilter writes costs like the keepout filter: they go with the mask.
TEST(FilterLifecycle, LanesCostsGoWithTheMask)
{
  Rig<LanesFilter> rig;
  rig.ctx->publishGrid(GridKind::Mask, makeMask(10, 10, 0.0, 0.0, 100));  // no lane: all of it lethal
  rig.update();
  ASSERT_TRUE(rig.filter->isActive());
  ASSERT_EQ(rig.cost(5, 5), LETHAL_OBSTACLE);
  rig.filter->deactivate();
  EXPECT_FALSE(rig.filter->isActive());
  rig.update();
  for (unsigned y = 0; y < 10; ++y)
    for (unsigned x = 0; x < 10; ++x)
      EXPECT_EQ(rig.cost(x, y), FREE_SPACE) << x << "," << y;
  rig.filter->activate();
  rig.update();
  EXPECT_EQ(rig.cost(5, 5), FREE_SPACE);
  EXPECT_FALSE(rig.filter->isActive());
}

// SpeedFilter: deactivated, no zone limits the robot: default_max_speed (2 m/s) is published at once,
// as when it is switched off; after activate() it stays so until a mask arrives. The mask value 40
// gives 0.1 + 0.01 * 40 = 0.5 m/s (nav2 mode).
TEST(FilterLifecycle, SpeedLimitIsLiftedUntilANewMaskArrives)
{
  ParamValue p = ParamValue::makeMap();
  p.set("default_max_speed", ParamValue::makeDouble(2.0));
  p.set("mask_mode", ParamValue::makeString("nav2"));
  p.set("base", ParamValue::makeDouble(0.1));
  p.set("multiplier", ParamValue::makeDouble(0.01));
  Rig<SpeedFilter> rig(p);
  rig.ctx->publishGrid(GridKind::Mask, makeMask(2, 2, 0.0, 0.0, 40));
  rig.update();
  ASSERT_TRUE(rig.filter->isActive());
  ASSERT_FALSE(rig.ctx->published_speeds.empty());
  ASSERT_DOUBLE_EQ(rig.ctx->published_speeds.back(), 0.5);
  const std::size_t before = rig.ctx->published_speeds.size();

  rig.filter->deactivate();
  EXPECT_FALSE(rig.filter->isActive());
  ASSERT_EQ(rig.ctx->published_speeds.size(), before + 1);
  EXPECT_DOUBLE_EQ(rig.ctx->published_speeds.back(), 2.0);
  rig.filter->deactivate();  // twice: nothing more published
  rig.update();
  EXPECT_EQ(rig.ctx->published_speeds.size(), before + 1);

  rig.filter->activate();
  rig.update();
  EXPECT_EQ(rig.ctx->published_speeds.size(), before + 1);
  EXPECT_DOUBLE_EQ(rig.ctx->published_speeds.back(), 2.0);
  rig.ctx->publishGrid(GridKind::Mask, makeMask(2, 2, 0.0, 0.0, 40));
  rig.update();
  EXPECT_TRUE(rig.filter->isActive());
  EXPECT_DOUBLE_EQ(rig.ctx->published_speeds.back(), 0.5);
}

// BinaryFilter: deactivated, the default state (false) is published at once; a mask value 90 at the
// robot flips it (above flip_threshold 50) again only once a new mask arrived after activate().
TEST(FilterLifecycle, BinaryStateReturnsToItsDefaultUntilANewMaskArrives)
{
  Rig<BinaryFilter> rig;
  rig.ctx->publishGrid(GridKind::Mask, makeMask(2, 2, 0.0, 0.0, 90));
  rig.update();
  ASSERT_EQ(rig.ctx->published_states, (std::vector<bool>{false, true}));
  rig.filter->deactivate();
  EXPECT_FALSE(rig.filter->isActive());
  EXPECT_EQ(rig.ctx->published_states, (std::vector<bool>{false, true, false}));
  rig.update();
  rig.filter->activate();
  rig.update();
  EXPECT_EQ(rig.ctx->published_states, (std::vector<bool>{false, true, false}));
  rig.ctx->publishGrid(GridKind::Mask, makeMask(2, 2, 0.0, 0.0, 90));
  rig.update();
  EXPECT_EQ(rig.ctx->published_states, (std::vector<bool>{false, true, false, true}));
}

// ZoneParameterFilter: deactivated, state 0 (the nominal defaults) is entered at once, as Nav2's
// resetFilter() resets its state; state 1 comes back only with a new mask.
TEST(FilterLifecycle, ZoneStateReturnsToNominalUntilANewMaskArrives)
{
  ParamValue entry = ParamValue::makeMap();
  entry.set("node", ParamValue::makeString("/move_base/DWAPlannerROS"));
  entry.set("parameter", ParamValue::makeString("max_vel_x"));
  entry.set("value", ParamValue::makeDouble(0.3));
  ParamValue nominal_entry = entry;
  nominal_entry.set("value", ParamValue::makeDouble(0.8));
  ParamValue setpoints = ParamValue::makeList();
  setpoints.push(ParamValue::makeString("speed"));
  ParamValue slow = ParamValue::makeMap();
  slow.set("id", ParamValue::makeInt(1));
  slow.set("setpoints", setpoints);
  slow.set("speed", entry);
  ParamValue nominal = ParamValue::makeMap();
  nominal.set("speed", nominal_entry);
  ParamValue states = ParamValue::makeList();
  states.push(ParamValue::makeString("slow"));
  ParamValue p = ParamValue::makeMap();
  p.set("states", states);
  p.set("slow", slow);
  p.set("nominal_defaults", nominal);
  Rig<ZoneParameterFilter> rig(p);
  std::vector<double> zone_states;
  rig.filter->setOutputListener(
      [&](const OutputEvent& e)
      {
        if (e.kind == OutputKind::ZoneState) zone_states.push_back(e.value);
      });
  rig.ctx->publishGrid(GridKind::Mask, makeMask(2, 2, 0.0, 0.0, 1));
  rig.update();
  ASSERT_EQ(rig.filter->stateInForce(), 1);
  zone_states.clear();

  rig.filter->deactivate();
  EXPECT_FALSE(rig.filter->isActive());
  EXPECT_EQ(rig.filter->stateInForce(), 0);
  EXPECT_EQ(zone_states, std::vector<double>{0.0});
  rig.filter->activate();
  rig.update();
  EXPECT_EQ(rig.filter->stateInForce(), 0);
  rig.ctx->publishGrid(GridKind::Mask, makeMask(2, 2, 0.0, 0.0, 1));
  rig.update();
  EXPECT_TRUE(rig.filter->isActive());
  EXPECT_EQ(zone_states, (std::vector<double>{0.0, 1.0}));
}
