// Filters in Nav2's form (filter_info_topic): the info rules (which types a filter takes, what it
// checks), the mask port that follows the info's topic, the waiting report, and SpeedFilter's values
// under Nav2's rule. Expected values come from Nav2's documented formulas, written out here:
//   speed limit L = base + multiplier * v for a mask value v in 1..100; v = 0: no limit (0);
//   percent (type 1): L outside [0, 100] -> no limit; m/s (type 2): L < 0 -> no limit.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/filters/filter_info.hpp"
#include "costmap_layers/core/filters/keepout_filter.hpp"
#include "costmap_layers/core/filters/lanes_filter.hpp"
#include "costmap_layers/core/filters/speed_filter.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;

namespace
{
FilterInfoData info(int type, const std::string& topic, double base = 0.0, double multiplier = 1.0)
{
  FilterInfoData i;
  i.type = static_cast<uint8_t>(type);
  i.filter_mask_topic = topic;
  i.base = base;
  i.multiplier = multiplier;
  return i;
}

ParamValue nav2Params(const std::string& info_topic = "/costmap_filter_info")
{
  ParamValue p = ParamValue::makeMap();
  p.set("filter_info_topic", ParamValue::makeString(info_topic));
  return p;
}

/// A w x 1 mask at 1 m, origin (0, 0), holding the given values left to right.
OccupancyGridData row(std::initializer_list<int> values)
{
  OccupancyGridData m;
  m.frame_id = "map";
  m.width = static_cast<uint32_t>(values.size());
  m.height = 1;
  m.resolution = 1.0;
  for (int v : values)
    m.data.push_back(static_cast<int8_t>(v));
  return m;
}

template <class Filter>
struct Rig
{
  LayeredCostmap lc{"map", false, false};
  std::shared_ptr<FakeContext> ctx;
  std::shared_ptr<Filter> filter = std::make_shared<Filter>();

  explicit Rig(ParamValue p, const std::string& name = "filter") : ctx(std::make_shared<FakeContext>(std::move(p)))
  {
    filter->initialize(&lc, name, ctx);
    ctx->bind(*filter);
  }
  void cycle(double x = 0.5, double y = 0.5)
  {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    filter->updateBounds(x, y, 0.0, &x0, &y0, &x1, &y1);
  }
  /// The topic the test host is subscribed to for the mask input.
  std::string maskSubscription() const
  {
    for (const auto& s : ctx->grid_subs)
      return s.topic;
    return "<no mask input>";
  }
};
}  // namespace

// ---- the info rules

TEST(FilterInfoRules, TypesAndFields)
{
  EXPECT_TRUE(validateFilterInfo(info(0, "/m")).ok());
  for (int t : {0, 1, 2, 3, 4})
    EXPECT_TRUE(isKnownFilterInfoType(t)) << t;
  EXPECT_FALSE(isKnownFilterInfoType(5));

  InputError e = validateFilterInfo(info(7, "/m"));
  EXPECT_EQ(e.field, "type");
  EXPECT_NE(e.message.find("got 7"), std::string::npos) << e.message;

  e = validateFilterInfo(info(0, ""));
  EXPECT_EQ(e.field, "filter_mask_topic");
  e = validateFilterInfo(info(0, "/a mask"));
  EXPECT_EQ(e.field, "filter_mask_topic");
  e = validateFilterInfo(info(0, "/" + std::string(2000, 'm')));
  EXPECT_EQ(e.field, "filter_mask_topic");
  EXPECT_LT(e.message.size(), 200u);  // a long topic is not repeated in the report
  // ROS's name grammar (roscpp would refuse these only once the info were in force).
  for (const char* bad : {"/mask-1", "1mask", "~mask", "/a.b", "_m", "/m:1", "/m%"})
  {
    e = validateFilterInfo(info(0, bad));
    EXPECT_EQ(e.field, "filter_mask_topic") << bad;
    EXPECT_NE(e.message.find(std::string("'") + bad + "'"), std::string::npos) << e.message;
  }
  for (const char* good : {"m", "/m", "ns/mask_2", "/ns//mask", "M1"})
    EXPECT_TRUE(validateFilterInfo(info(0, good)).ok()) << good;

  e = validateFilterInfo(info(1, "/m", std::nan(""), 1.0));
  EXPECT_EQ(e.field, "base");
  e = validateFilterInfo(info(1, "/m", 0.0, std::numeric_limits<double>::infinity()));
  EXPECT_EQ(e.field, "multiplier");
}

TEST(FilterInfoRules, WhichFilterTakesWhichType)
{
  // keepout / lanes: type 0 only.
  EXPECT_TRUE(checkFilterInfoFor(FilterFamily::Keepout, info(0, "/m")).ok());
  for (int t : {1, 2, 3})
  {
    const InputError e = checkFilterInfoFor(FilterFamily::Keepout, info(t, "/m"));
    EXPECT_EQ(e.field, "type") << t;
    EXPECT_NE(e.message.find("type " + std::to_string(t)), std::string::npos) << e.message;
  }
  // speed: 1 (percent) and 2 (m/s).
  EXPECT_TRUE(checkFilterInfoFor(FilterFamily::Speed, info(1, "/m")).ok());
  EXPECT_TRUE(checkFilterInfoFor(FilterFamily::Speed, info(2, "/m")).ok());
  for (int t : {0, 3})
    EXPECT_EQ(checkFilterInfoFor(FilterFamily::Speed, info(t, "/m")).field, "type") << t;
  // binary: 3 only.
  EXPECT_TRUE(checkFilterInfoFor(FilterFamily::Binary, info(3, "/m")).ok());
  for (int t : {0, 1, 2, 4})
    EXPECT_EQ(checkFilterInfoFor(FilterFamily::Binary, info(t, "/m")).field, "type") << t;
}

// ---- Nav2's speed rule, value by value

TEST(Nav2SpeedRule, PercentTutorialMask)
{
  // The tutorial: type 1, base 100, multiplier -1: L = 100 - v percent.
  for (int v = 1; v <= 100; ++v)
  {
    const Nav2SpeedLimit l = nav2SpeedLimit(v, 100.0, -1.0, true);
    EXPECT_DOUBLE_EQ(l.speed_limit, 100.0 - v) << v;
    EXPECT_FALSE(l.out_of_range) << v;
  }
  EXPECT_DOUBLE_EQ(nav2SpeedLimit(20, 100.0, -1.0, true).speed_limit, 80.0);
  EXPECT_DOUBLE_EQ(nav2SpeedLimit(40, 100.0, -1.0, true).speed_limit, 60.0);
  EXPECT_DOUBLE_EQ(nav2SpeedLimit(70, 100.0, -1.0, true).speed_limit, 30.0);
  // A free cell is no limit whatever base says.
  const Nav2SpeedLimit free = nav2SpeedLimit(0, 100.0, -1.0, true);
  EXPECT_EQ(free.speed_limit, 0.0);
  EXPECT_FALSE(free.out_of_range);
}

TEST(Nav2SpeedRule, OutOfRangeBecomesNoLimit)
{
  // percent: [0, 100] inclusive.
  EXPECT_DOUBLE_EQ(nav2SpeedLimit(50, 0.0, 2.0, true).speed_limit, 100.0);  // 100: the edge, kept
  Nav2SpeedLimit l = nav2SpeedLimit(60, 0.0, 2.0, true);                    // 120 %
  EXPECT_TRUE(l.out_of_range);
  EXPECT_EQ(l.speed_limit, 0.0);
  EXPECT_DOUBLE_EQ(l.computed, 120.0);
  l = nav2SpeedLimit(5, -10.0, 1.0, true);  // -5 %
  EXPECT_TRUE(l.out_of_range);
  EXPECT_EQ(l.speed_limit, 0.0);
  l = nav2SpeedLimit(10, -10.0, 1.0, true);  // exactly 0 %: in range, and means no limit
  EXPECT_FALSE(l.out_of_range);
  EXPECT_EQ(l.speed_limit, 0.0);
  // m/s: no upper bound, below 0 is out of range.
  EXPECT_DOUBLE_EQ(nav2SpeedLimit(50, 0.0, 0.01, false).speed_limit, 0.5);
  EXPECT_DOUBLE_EQ(nav2SpeedLimit(100, 1.0, 1.0, false).speed_limit, 101.0);
  l = nav2SpeedLimit(50, -1.0, 0.01, false);  // -0.5 m/s
  EXPECT_TRUE(l.out_of_range);
  EXPECT_EQ(l.speed_limit, 0.0);
}

// ---- configuration

TEST(FilterInfoConfig, MaskTopicAndFilterInfoTopicTogetherIsAnError)
{
  ParamValue p = nav2Params();
  p.set("mask_topic", ParamValue::makeString("/keepout_filter_mask"));
  LayeredCostmap lc{"map", false, false};
  auto filter = std::make_shared<KeepoutFilter>();
  try
  {
    filter->initialize(&lc, "keepout_filter", std::make_shared<FakeContext>(p));
    FAIL() << "accepted both";
  }
  catch (const std::invalid_argument& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("filter_info_topic"), std::string::npos) << what;
    EXPECT_NE(what.find("mask_topic"), std::string::npos) << what;
  }
}

TEST(FilterInfoConfig, SpeedParametersTheInfoHoldsAreErrors)
{
  for (const char* held : {"mask_mode", "base", "multiplier", "speed_limit_in_percent", "features_topic"})
  {
    ParamValue p = nav2Params();
    p.set(held, std::string(held) == "speed_limit_in_percent" ? ParamValue::makeBool(true)
                : std::string(held) == "mask_mode"            ? ParamValue::makeString("nav2")
                : std::string(held) == "features_topic"       ? ParamValue::makeString("/features")
                                                              : ParamValue::makeDouble(1.0));
    LayeredCostmap lc{"map", false, false};
    auto filter = std::make_shared<SpeedFilter>();
    try
    {
      filter->initialize(&lc, "speed_filter", std::make_shared<FakeContext>(p));
      ADD_FAILURE() << "accepted " << held;
    }
    catch (const std::invalid_argument& e)
    {
      const std::string what = e.what();
      EXPECT_NE(what.find(held), std::string::npos) << what;
      EXPECT_NE(what.find("filter_info_topic"), std::string::npos) << what;
    }
  }
}

// ---- the keepout filter in Nav2's form

TEST(FilterInfoKeepout, WaitsForTheInfoThenReadsTheMaskItNames)
{
  Rig<KeepoutFilter> r(nav2Params(), "keepout_filter");
  ASSERT_EQ(r.ctx->info_subs.size(), 1u);
  EXPECT_EQ(r.ctx->info_subs[0].topic, "/costmap_filter_info");
  EXPECT_EQ(r.maskSubscription(), "");  // not connected yet

  r.cycle();
  EXPECT_EQ(r.ctx->countKey("waiting"), 0);  // the start-up grace
  r.ctx->now_ns += kStartupGraceNs;
  r.cycle();
  ASSERT_EQ(r.ctx->countKey("waiting"), 1);
  EXPECT_EQ(r.ctx->countReports("waiting for filter info on /costmap_filter_info"), 1);

  r.ctx->publishFilterInfo(info(0, "/keepout_filter_mask"));
  EXPECT_EQ(r.ctx->replaced_inputs, 1);
  EXPECT_EQ(r.maskSubscription(), "/keepout_filter_mask");
  EXPECT_EQ(r.filter->maskTopic(), "/keepout_filter_mask");
  r.cycle();
  EXPECT_EQ(r.ctx->countReports("no mask yet on /keepout_filter_mask"), 1);

  r.lc.resizeMap(4, 1, 1.0, 0.0, 0.0);
  r.lc.addFilter(r.filter);
  EXPECT_EQ(r.ctx->publishGridOn("/keepout_filter_mask", row({0, 100, 50, 0})), 1);
  r.lc.updateMap(0.5, 0.5, 0.0);
  EXPECT_EQ(r.lc.getCostmap().getCost(1, 0), LETHAL_OBSTACLE);
  EXPECT_EQ(r.lc.getCostmap().getCost(2, 0), 127);  // round(50 * 254 / 100), as in the mask_topic form
  EXPECT_EQ(r.lc.getCostmap().getCost(0, 0), FREE_SPACE);
}

TEST(FilterInfoKeepout, WrongInfoIsReportedAndTheOldOneStays)
{
  Rig<KeepoutFilter> r(nav2Params(), "keepout_filter");
  r.ctx->publishFilterInfo(info(0, "/keepout_filter_mask"));
  ASSERT_TRUE(r.ctx->publishGridOn("/keepout_filter_mask", row({100})) == 1);
  const std::string before = r.maskSubscription();

  r.ctx->publishFilterInfo(info(1, "/speed_filter_mask", 100.0, -1.0));  // a speed info on the same topic
  EXPECT_EQ(r.ctx->countKey("filter_info/type"), 1);
  EXPECT_EQ(r.ctx->reports.back().severity, Severity::Error);
  EXPECT_EQ(r.maskSubscription(), before);
  EXPECT_NE(r.filter->getMask(), nullptr);
  EXPECT_EQ(r.filter->getFilterInfo()->type, 0);

  r.ctx->publishFilterInfo(info(0, ""));
  EXPECT_EQ(r.ctx->countKey("filter_info/filter_mask_topic"), 1);
  // A topic ROS would refuse: refused here, before the mask in force is dropped.
  r.ctx->publishFilterInfo(info(0, "/keepout-mask"));
  EXPECT_EQ(r.ctx->countKey("filter_info/filter_mask_topic"), 2);
  EXPECT_EQ(r.maskSubscription(), before);
  EXPECT_NE(r.filter->getMask(), nullptr);

  // base and multiplier: Nav2's keepout filter wants 0 and 1; used all the same, with a warning.
  r.ctx->publishFilterInfo(info(0, "/keepout_filter_mask", 5.0, 2.0));
  EXPECT_EQ(r.ctx->countKey("filter_info/base"), 1);
  EXPECT_NE(r.filter->getMask(), nullptr);  // same topic: the mask stays
}

TEST(FilterInfoKeepout, AnotherMaskTopicMovesTheSubscription)
{
  Rig<KeepoutFilter> r(nav2Params(), "keepout_filter");
  r.lc.resizeMap(4, 1, 1.0, 0.0, 0.0);
  r.lc.addFilter(r.filter);
  r.ctx->publishFilterInfo(info(0, "/mask_a"));
  const GridCallback old_handler = r.ctx->grid_subs[0].cb;
  ASSERT_EQ(r.ctx->publishGridOn("/mask_a", row({100, 0, 0, 0})), 1);
  r.lc.updateMap(0.5, 0.5, 0.0);
  EXPECT_EQ(r.lc.getCostmap().getCost(0, 0), LETHAL_OBSTACLE);

  r.ctx->publishFilterInfo(info(0, "/mask_b"));
  EXPECT_EQ(r.ctx->replaced_inputs, 2);
  EXPECT_EQ(r.maskSubscription(), "/mask_b");
  EXPECT_EQ(r.filter->getMask(), nullptr);  // mask_a is not what the new info describes
  EXPECT_EQ(r.ctx->publishGridOn("/mask_a", row({100, 100, 0, 0})), 0);
  // A delivery from the old subscription still in flight is ignored.
  old_handler(std::make_shared<const OccupancyGridData>(row({100, 100, 100, 100})));
  EXPECT_EQ(r.filter->getMask(), nullptr);

  ASSERT_EQ(r.ctx->publishGridOn("/mask_b", row({0, 0, 0, 100})), 1);
  r.lc.updateMap(0.5, 0.5, 0.0);
  EXPECT_EQ(r.lc.getCostmap().getCost(0, 0), FREE_SPACE);  // mask_a's wall is gone
  EXPECT_EQ(r.lc.getCostmap().getCost(3, 0), LETHAL_OBSTACLE);
}

TEST(FilterInfoKeepout, MaskTopicFormUnchanged)
{
  ParamValue p = ParamValue::makeMap();
  p.set("mask_topic", ParamValue::makeString("/keepout_filter_mask"));
  Rig<KeepoutFilter> r(p, "keepout_filter");
  EXPECT_TRUE(r.ctx->info_subs.empty());
  EXPECT_EQ(r.maskSubscription(), "/keepout_filter_mask");
  EXPECT_FALSE(r.filter->usesFilterInfo());
}

TEST(FilterInfoLanes, TakesTypeZero)
{
  Rig<LanesFilter> r(nav2Params("/lanes_info"), "lanes_filter");
  r.ctx->publishFilterInfo(info(2, "/lanes_mask"));
  EXPECT_EQ(r.ctx->countKey("filter_info/type"), 1);
  EXPECT_EQ(r.maskSubscription(), "");
  r.ctx->publishFilterInfo(info(0, "/lanes_mask"));
  EXPECT_EQ(r.maskSubscription(), "/lanes_mask");
}

// ---- the speed filter in Nav2's form

namespace
{
ParamValue speedParams(double default_max_speed)
{
  ParamValue p = nav2Params();
  p.set("speed_limit_topic", ParamValue::makeString("/speed_limit"));
  p.set("default_max_speed", ParamValue::makeDouble(default_max_speed));
  return p;
}
}  // namespace

TEST(FilterInfoSpeed, PercentAsNav2Publishes)
{
  Rig<SpeedFilter> r(speedParams(0.5), "speed_filter");
  EXPECT_EQ(r.ctx->speed_limit_topic, "/speed_limit");
  r.cycle();  // no info yet: no limit
  r.ctx->now_ns += kStartupGraceNs;
  r.cycle();
  EXPECT_EQ(r.ctx->countReports("waiting for filter info on /costmap_filter_info"), 1);
  ASSERT_EQ(r.ctx->published_limits.size(), 1u);
  EXPECT_EQ(r.ctx->published_limits.back().second, 0.0);
  EXPECT_EQ(r.ctx->published_speeds.back(), 0.5);

  r.ctx->publishFilterInfo(info(1, "/speed_filter_mask", 100.0, -1.0));
  ASSERT_EQ(r.ctx->publishGridOn("/speed_filter_mask", row({0, 20, 40, 70, 100, -1})), 1);
  const int values[] = {20, 40, 70};
  for (int k = 0; k < 3; ++k)
  {
    r.cycle(1.5 + k, 0.5);
    const double percent = 100.0 - values[k];  // Nav2: base + multiplier * v
    ASSERT_FALSE(r.ctx->published_limits.empty());
    EXPECT_TRUE(r.ctx->published_limits.back().first);
    EXPECT_DOUBLE_EQ(r.ctx->published_limits.back().second, percent) << values[k];
    EXPECT_DOUBLE_EQ(r.ctx->published_speeds.back(), 0.5 * percent / 100.0) << values[k];
  }
  r.cycle(4.5, 0.5);  // 100: 0 %, which is no limit
  EXPECT_EQ(r.ctx->published_limits.back(), std::make_pair(true, 0.0));
  EXPECT_EQ(r.ctx->published_speeds.back(), 0.5);
  const std::size_t n = r.ctx->published_limits.size();
  r.cycle(5.5, 0.5);  // -1: keeps what is in force
  EXPECT_EQ(r.ctx->published_limits.size(), n);
  r.cycle(0.5, 0.5);  // 0: no limit (unchanged: nothing new)
  EXPECT_EQ(r.ctx->published_limits.size(), n);
  r.cycle(2.5, 0.5);
  EXPECT_DOUBLE_EQ(r.ctx->published_limits.back().second, 60.0);
  r.cycle(10.0, 10.0);  // outside the mask: no limit
  EXPECT_EQ(r.ctx->published_limits.back(), std::make_pair(true, 0.0));
  EXPECT_EQ(r.ctx->countKey("mask/value"), 0);
}

// Nav2's speed_filter_test testInfoRePublish: the info re-sent on its topic with another type, base
// and multiplier, the mask topic the same: the mask stays, and the next limits follow the new info
// (m/s 1.23 + 4.5 v, then percent 0.1 + 0.2 v: 7.1 % for 35, 20.1 % for 100).
TEST(FilterInfoSpeed, InfoResentWithAnotherTypeKeepsTheMask)
{
  Rig<SpeedFilter> r(speedParams(0.0), "speed_filter");
  // The last (in percent, value) published, the value to 1e-4 (float32 in Nav2's message).
  auto last = [&](double x)
  {
    r.cycle(x, 0.5);
    const auto [percent, value] = r.ctx->published_limits.back();
    return std::make_pair(percent, std::round(value * 1e4) / 1e4);
  };
  r.ctx->publishFilterInfo(info(2, "/speed_filter_mask", 1.23, 4.5));
  ASSERT_EQ(r.ctx->publishGridOn("/speed_filter_mask", row({35, 100})), 1);
  EXPECT_EQ(last(0.5), std::make_pair(false, 158.73));  // 1.23 + 4.5 * 35 m/s
  const int replaced = r.ctx->replaced_inputs;
  r.ctx->publishFilterInfo(info(1, "/speed_filter_mask", 0.1, 0.2));
  EXPECT_EQ(r.ctx->replaced_inputs, replaced);  // the same topic: not subscribed again
  EXPECT_NE(r.filter->getMask(), nullptr);      // and the mask kept
  EXPECT_EQ(last(0.5), std::make_pair(true, 7.1));
  EXPECT_EQ(last(1.5), std::make_pair(true, 20.1));
}

TEST(FilterInfoSpeed, MetresPerSecond)
{
  Rig<SpeedFilter> r(speedParams(0.0), "speed_filter");
  r.ctx->publishFilterInfo(info(2, "/speed_filter_mask", 0.0, 0.01));
  ASSERT_EQ(r.ctx->publishGridOn("/speed_filter_mask", row({50, 30})), 1);
  r.cycle(0.5, 0.5);
  EXPECT_EQ(r.ctx->published_limits.back().first, false);
  EXPECT_DOUBLE_EQ(r.ctx->published_limits.back().second, 0.5);  // 0 + 0.01 * 50
  EXPECT_DOUBLE_EQ(r.ctx->published_speeds.back(), 0.5);
  r.cycle(1.5, 0.5);
  EXPECT_DOUBLE_EQ(r.ctx->published_speeds.back(), 0.3);
}

TEST(FilterInfoSpeed, OutOfRangeSaysWhatIsPublished)
{
  Rig<SpeedFilter> r(speedParams(0.8), "speed_filter");
  r.ctx->publishFilterInfo(info(1, "/speed_filter_mask", 0.0, 2.0));  // v = 60 gives 120 %
  ASSERT_EQ(r.ctx->publishGridOn("/speed_filter_mask", row({60, 30})), 1);
  r.cycle(1.5, 0.5);
  EXPECT_DOUBLE_EQ(r.ctx->published_limits.back().second, 60.0);
  r.cycle(0.5, 0.5);
  EXPECT_EQ(r.ctx->published_limits.back(), std::make_pair(true, 0.0));
  EXPECT_DOUBLE_EQ(r.ctx->published_speeds.back(), 0.8);
  ASSERT_EQ(r.ctx->countKey("mask/value"), 1);
  const std::string& text = r.ctx->reports.back().message;
  EXPECT_NE(text.find("120"), std::string::npos) << text;
  EXPECT_NE(text.find("max_speed 0.8 m/s"), std::string::npos) << text;
  EXPECT_NE(text.find("speed_limit 0 % (no limit) on /speed_limit"), std::string::npos) << text;
}

TEST(FilterInfoSpeed, PercentWithoutDefaultMaxSpeedPublishesOnlyThePercentage)
{
  Rig<SpeedFilter> r(speedParams(0.0), "speed_filter");
  r.cycle();
  ASSERT_EQ(r.ctx->published_speeds.size(), 1u);  // no limit: 0, publishable
  r.ctx->publishFilterInfo(info(1, "/speed_filter_mask", 100.0, -1.0));
  EXPECT_EQ(r.ctx->countKey("default_max_speed"), 1);
  ASSERT_EQ(r.ctx->publishGridOn("/speed_filter_mask", row({40})), 1);
  r.cycle(0.5, 0.5);
  EXPECT_DOUBLE_EQ(r.ctx->published_limits.back().second, 60.0);
  EXPECT_EQ(r.ctx->published_speeds.size(), 1u);  // 60 % of an unknown top speed: not sent in m/s
}

TEST(FilterInfoSpeed, RejectsKeepoutInfo)
{
  Rig<SpeedFilter> r(speedParams(0.5), "speed_filter");
  r.ctx->publishFilterInfo(info(0, "/keepout_filter_mask"));
  EXPECT_EQ(r.ctx->countKey("filter_info/type"), 1);
  EXPECT_EQ(r.maskSubscription(), "");
}

// ---- threads: infos and masks arrive on the host's threads while the update loop runs

TEST(FilterInfoThreads, InfosAndMasksFromOtherThreads)
{
  Rig<SpeedFilter> r(speedParams(1.0), "speed_filter");
  // Two infos alternate between two mask topics; each topic's mask holds one value everywhere, read by
  // its own info as 40 % (a: 10 + 1 * 30) or 70 % (b: 20 + 0.5 * 100). A mask read with the other
  // topic's info would give 35 % (b on 30) or 110 %, out of range (a on 100): any mix-up shows.
  const FilterInfoData info_a = info(1, "/mask_a", 10.0, 1.0);
  const FilterInfoData info_b = info(1, "/mask_b", 20.0, 0.5);
  const OccupancyGridData mask_a = row({30, 30}), mask_b = row({100, 100});
  std::atomic<bool> stop{false};
  std::thread infos(
      [&]
      {
        for (int k = 0; !stop; ++k)
          r.ctx->publishFilterInfo(k % 2 ? info_a : info_b);
      });
  std::thread masks(
      [&]
      {
        while (!stop)
        {
          r.ctx->publishGridOn("/mask_a", mask_a);
          r.ctx->publishGridOn("/mask_b", mask_b);
        }
      });
  for (int k = 0; k < 3000; ++k)
  {
    r.cycle(0.5, 0.5);
    if (r.ctx->published_limits.empty()) continue;
    const double v = r.ctx->published_limits.back().second;
    EXPECT_TRUE(v == 0.0 || v == 40.0 || v == 70.0) << v;
  }
  stop = true;
  infos.join();
  masks.join();
  EXPECT_EQ(r.ctx->countKey("mask/value"), 0);
}
