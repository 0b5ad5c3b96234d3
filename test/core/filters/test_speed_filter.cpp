// SpeedFilter: what it publishes as the robot moves over a mask, in area_id mode (limits from
// features messages) and in nav2 mode (limits encoded in the mask), and how it checks its inputs.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/filters/speed_filter.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;
using costmap_layers_test::GridKind;

namespace
{
constexpr double kDefault = 2.0;

/// The 10 x 11 test mask at 1 m, origin (0, 0): cell k = (k % 10, k / 10) holds k + 1 for k < 100 (every
/// area id 1..100 once); the top row (y in [10, 11)) holds 0 in columns 0..4 and -1 in columns 5..9.
OccupancyGridData makeMask(const std::string& frame = "map")
{
  OccupancyGridData m;
  m.frame_id = frame;
  m.width = 10;
  m.height = 11;
  m.resolution = 1.0;
  m.data.resize(110);
  for (int k = 0; k < 100; ++k)
    m.data[static_cast<std::size_t>(k)] = static_cast<int8_t>(k + 1);
  for (int k = 100; k < 110; ++k)
    m.data[static_cast<std::size_t>(k)] = static_cast<int8_t>(k < 105 ? 0 : -1);
  return m;
}

/// Centre of the test mask's cell holding area id `id` (1..100).
std::pair<double, double> centreOf(int id)
{
  return {(id - 1) % 10 + 0.5, (id - 1) / 10 + 0.5};
}
constexpr double kFreeX = 2.5, kFreeY = 10.5;        // a 0 cell
constexpr double kUnknownX = 7.5, kUnknownY = 10.5;  // a -1 cell

/// Limit of area id in the test features: id * 0.01 m/s (all different, all below the default).
double limitOf(int id)
{
  return id * 0.01;
}

SpeedLimitsData allLimits()
{
  SpeedLimitsData s;
  s.frame_id = "map";
  for (uint32_t id = 1; id <= 100; ++id)
    s.limits.push_back({id, limitOf(static_cast<int>(id))});
  return s;
}

ParamValue params(double def = kDefault)
{
  ParamValue p = ParamValue::makeMap();
  p.set("default_max_speed", ParamValue::makeDouble(def));
  return p;
}

struct Rig
{
  LayeredCostmap lc{"map", false, false};
  std::shared_ptr<FakeContext> ctx;
  std::shared_ptr<SpeedFilter> filter = std::make_shared<SpeedFilter>();

  explicit Rig(ParamValue p = params()) : ctx(std::make_shared<FakeContext>(std::move(p)))
  {
    filter->initialize(&lc, "speed_filter", ctx);
    ctx->bind(*filter);
  }
  /// One update cycle with the robot at (x, y); returns how many values were published by it.
  std::size_t at(double x, double y)
  {
    const std::size_t before = ctx->published_speeds.size();
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    filter->updateBounds(x, y, 0.3, &x0, &y0, &x1, &y1);
    return ctx->published_speeds.size() - before;
  }
  std::size_t atArea(int id) { return at(centreOf(id).first, centreOf(id).second); }
  double last() const { return ctx->published_speeds.empty() ? std::nan("") : ctx->published_speeds.back(); }
};
}  // namespace

// ---------------------------------------------------------------- configuration

TEST(SpeedFilterConfig, DefaultsAndParsing)
{
  const ParamValue empty = ParamValue::makeMap();
  const SpeedFilterConfig d = parseSpeedFilterConfig(ParamReader(empty, "speed"));
  EXPECT_EQ(d.features_topic, "/features");
  EXPECT_EQ(d.max_speed_topic, "/max_speed");
  EXPECT_EQ(d.default_max_speed, 0.0);
  EXPECT_FALSE(d.speed_limit_in_percent);
  EXPECT_EQ(d.mask_mode, SpeedMaskMode::AreaId);
  EXPECT_EQ(d.base, 0.0);
  EXPECT_EQ(d.multiplier, 1.0);

  ParamValue p = ParamValue::makeMap();
  p.set("features_topic", ParamValue::makeString("/zones"));
  p.set("max_speed_topic", ParamValue::makeString("/limit"));
  p.set("default_max_speed", ParamValue::makeDouble(1.5));
  p.set("speed_limit_in_percent", ParamValue::makeBool(true));
  p.set("mask_mode", ParamValue::makeString("nav2"));
  p.set("base", ParamValue::makeDouble(-10.0));
  p.set("multiplier", ParamValue::makeDouble(2.0));
  const SpeedFilterConfig c = parseSpeedFilterConfig(ParamReader(p, "speed"));
  EXPECT_EQ(c.features_topic, "/zones");
  EXPECT_EQ(c.max_speed_topic, "/limit");
  EXPECT_EQ(c.default_max_speed, 1.5);
  EXPECT_TRUE(c.speed_limit_in_percent);
  EXPECT_EQ(c.mask_mode, SpeedMaskMode::Nav2);
  EXPECT_EQ(c.base, -10.0);
  EXPECT_EQ(c.multiplier, 2.0);
}

TEST(SpeedFilterConfig, BadValuesAreRefused)
{
  auto expectThrows = [](const char* name, ParamValue v, const char* needle)
  {
    ParamValue p = ParamValue::makeMap();
    p.set(name, std::move(v));
    try
    {
      parseSpeedFilterConfig(ParamReader(p, "speed"));
      ADD_FAILURE() << name << " accepted";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expectThrows("default_max_speed", ParamValue::makeDouble(-1.0), "default_max_speed");
  expectThrows("mask_mode", ParamValue::makeString("speed"), "mask_mode");
  expectThrows("multiplier", ParamValue::makeDouble(std::nan("")), "multiplier");
}

TEST(SpeedFilterConfig, PercentModeWithoutDefaultIsRefusedAtStartUp)
{
  ParamValue p = ParamValue::makeMap();
  p.set("speed_limit_in_percent", ParamValue::makeBool(true));
  auto ctx = std::make_shared<FakeContext>(p);
  LayeredCostmap lc("map", false, false);
  auto filter = std::make_shared<SpeedFilter>();
  try
  {
    filter->initialize(&lc, "speed_filter", ctx);
    ctx->bind(*filter);
    ADD_FAILURE() << "percent mode with default_max_speed 0 accepted";
  }
  catch (const std::invalid_argument& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("speed_filter"), std::string::npos) << what;
    EXPECT_NE(what.find("speed_limit_in_percent"), std::string::npos) << what;
    EXPECT_NE(what.find("default_max_speed"), std::string::npos) << what;
  }
  // The same in nav2 mode; with a default it is fine.
  p.set("mask_mode", ParamValue::makeString("nav2"));
  EXPECT_THROW(parseSpeedFilterConfig(ParamReader(p, "speed")), std::invalid_argument);
  p.set("default_max_speed", ParamValue::makeDouble(0.5));
  EXPECT_NO_THROW(parseSpeedFilterConfig(ParamReader(p, "speed")));
}

TEST(SpeedFilter, SubscribesAdvertisesAndWritesNothing)
{
  ParamValue p = params();
  p.set("features_topic", ParamValue::makeString("/zones"));
  p.set("max_speed_topic", ParamValue::makeString("/limit"));
  Rig r(p);
  ASSERT_EQ(r.ctx->speed_subs.size(), 1u);
  EXPECT_EQ(r.ctx->speed_subs[0].topic, "/zones");
  EXPECT_EQ(r.ctx->max_speed_topic, "/limit");
  ASSERT_EQ(r.ctx->grid_subs.size(), 1u);
  EXPECT_EQ(r.ctx->grid_subs[0].topic, "/map_filter");
  EXPECT_FALSE(r.filter->isClearable());

  r.ctx->publishGrid(GridKind::Mask, makeMask());
  r.ctx->publishSpeedLimits(allLimits());
  r.atArea(1);
  Costmap2D master(12, 12, 1.0, 0.0, 0.0, 17);
  r.filter->updateCosts(master, 0, 0, 12, 12);
  for (unsigned j = 0; j < 12; ++j)
    for (unsigned i = 0; i < 12; ++i)
      ASSERT_EQ(master.getCost(i, j), 17);

  // nav2 mode needs no features.
  ParamValue q = params();
  q.set("mask_mode", ParamValue::makeString("nav2"));
  Rig n(q);
  EXPECT_TRUE(n.ctx->speed_subs.empty());
  EXPECT_EQ(n.ctx->max_speed_topic, "/max_speed");
}

TEST(SpeedFilter, WithoutMaskTheDefaultIsInForce)
{
  // No mask yet: the robot is in no area, so the default is published once, then nothing new.
  Rig r;
  r.ctx->publishSpeedLimits(allLimits());
  EXPECT_EQ(r.at(1.5, 1.5), 1u);
  EXPECT_DOUBLE_EQ(r.last(), kDefault);
  EXPECT_EQ(r.at(2.5, 1.5), 0u);
  ASSERT_TRUE(r.filter->lastPublished().has_value());
  EXPECT_DOUBLE_EQ(*r.filter->lastPublished(), kDefault);
}

// ---------------------------------------------------------------- area_id mode

TEST(SpeedFilter, EveryAreaCellGivesItsLimit)
{
  Rig r;
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  r.ctx->publishSpeedLimits(allLimits());
  for (int id = 1; id <= 100; ++id)
  {
    ASSERT_EQ(r.atArea(id), 1u) << "area " << id;
    EXPECT_DOUBLE_EQ(r.last(), limitOf(id)) << "area " << id;
    EXPECT_DOUBLE_EQ(*r.filter->lastPublished(), limitOf(id));
    // Anywhere inside the same cell: the same value, nothing new published.
    const auto c = centreOf(id);
    EXPECT_EQ(r.at(c.first - 0.49, c.second + 0.49), 0u) << "area " << id;
    EXPECT_EQ(r.at(c.first + 0.49, c.second - 0.49), 0u) << "area " << id;
  }
  EXPECT_EQ(r.ctx->published_speeds.size(), 100u);
  EXPECT_TRUE(r.ctx->reports.empty());
}

TEST(SpeedFilter, FreeCellsAndOutsideGiveTheDefaultAndUnknownKeepsTheLast)
{
  Rig r;
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  r.ctx->publishSpeedLimits(allLimits());
  // Every 0 cell gives the default.
  EXPECT_EQ(r.atArea(42), 1u);
  for (int i = 0; i < 5; ++i)
  {
    EXPECT_EQ(r.at(i + 0.5, kFreeY), i == 0 ? 1u : 0u);
    EXPECT_DOUBLE_EQ(r.last(), kDefault);
  }
  // Every -1 cell keeps what was published last, whatever it was.
  EXPECT_EQ(r.atArea(42), 1u);
  for (int i = 5; i < 10; ++i)
    EXPECT_EQ(r.at(i + 0.5, kUnknownY), 0u);
  EXPECT_DOUBLE_EQ(r.last(), limitOf(42));
  EXPECT_EQ(r.at(kFreeX, kFreeY), 1u);
  EXPECT_EQ(r.at(kUnknownX, kUnknownY), 0u);
  EXPECT_DOUBLE_EQ(r.last(), kDefault);
  // Outside the mask on every side: the default.
  for (const auto& p : {std::pair<double, double>{-0.01, 5.0}, {10.0, 5.0}, {5.0, -0.5}, {5.0, 11.0}, {-50, 300}})
  {
    EXPECT_EQ(r.atArea(7), 1u);
    EXPECT_EQ(r.at(p.first, p.second), 1u) << p.first << "," << p.second;
    EXPECT_DOUBLE_EQ(r.last(), kDefault);
  }
  EXPECT_TRUE(r.ctx->reports.empty());
}

TEST(SpeedFilter, FirstCycleAlwaysPublishesThenOnlyChanges)
{
  {
    Rig r;  // first cycle outside the mask: the default
    r.ctx->publishGrid(GridKind::Mask, makeMask());
    EXPECT_EQ(r.at(-3, -3), 1u);
    EXPECT_DOUBLE_EQ(r.last(), kDefault);
    EXPECT_EQ(r.at(-3, -3), 0u);
    EXPECT_EQ(r.at(kFreeX, kFreeY), 0u);  // same value
  }
  {
    Rig r;  // first cycle on an unknown cell: the default
    r.ctx->publishGrid(GridKind::Mask, makeMask());
    EXPECT_EQ(r.at(kUnknownX, kUnknownY), 1u);
    EXPECT_DOUBLE_EQ(r.last(), kDefault);
  }
  {
    Rig r(params(0.0));  // the default 0.0 ("no limit") is published too
    r.ctx->publishGrid(GridKind::Mask, makeMask());
    EXPECT_EQ(r.at(kFreeX, kFreeY), 1u);
    EXPECT_EQ(r.last(), 0.0);
    r.ctx->publishSpeedLimits(allLimits());
    EXPECT_EQ(r.atArea(30), 1u);
    EXPECT_DOUBLE_EQ(r.last(), 0.3);
  }
  {
    Rig r;  // two areas with the same limit: moving between them publishes nothing
    r.ctx->publishGrid(GridKind::Mask, makeMask());
    SpeedLimitsData s = allLimits();
    s.limits[3].max_speed = s.limits[4].max_speed;  // areas 4 and 5
    r.ctx->publishSpeedLimits(s);
    EXPECT_EQ(r.atArea(4), 1u);
    EXPECT_EQ(r.atArea(5), 0u);
    EXPECT_EQ(r.atArea(6), 1u);
  }
}

TEST(SpeedFilter, RepublishedFeaturesTakeEffectAtTheNextCycle)
{
  Rig r;
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  r.ctx->publishSpeedLimits(allLimits());
  EXPECT_EQ(r.atArea(7), 1u);
  EXPECT_DOUBLE_EQ(r.last(), 0.07);
  SpeedLimitsData s = allLimits();
  s.limits[6].max_speed = 0.9;
  r.ctx->publishSpeedLimits(s);
  EXPECT_EQ(r.ctx->published_speeds.size(), 1u);  // nothing until the next cycle
  EXPECT_EQ(r.atArea(7), 1u);
  EXPECT_DOUBLE_EQ(r.last(), 0.9);
  r.ctx->publishSpeedLimits(s);  // the same limits again: nothing new
  EXPECT_EQ(r.atArea(7), 0u);
  s.limits[7].max_speed = 0.5;  // another area changed: nothing new here
  r.ctx->publishSpeedLimits(s);
  EXPECT_EQ(r.atArea(7), 0u);
  // A message without area 7: it becomes "no area".
  SpeedLimitsData only8;
  only8.limits.push_back({8, 0.25});
  r.ctx->publishSpeedLimits(only8);
  EXPECT_EQ(r.atArea(7), 1u);
  EXPECT_DOUBLE_EQ(r.last(), kDefault);
  EXPECT_EQ(r.atArea(8), 1u);
  EXPECT_DOUBLE_EQ(r.last(), 0.25);
}

TEST(SpeedFilter, ABadEntryKeepsItsAreasLastGoodLimit)
{
  Rig r;
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  r.ctx->publishSpeedLimits(allLimits());
  EXPECT_EQ(r.atArea(2), 1u);
  EXPECT_DOUBLE_EQ(r.last(), limitOf(2));
  SpeedLimitsData bad;
  bad.limits = {{2, std::nan("")}, {3, -1.0}, {4, 0.44}};
  EXPECT_EQ(r.filter->setSpeedLimits(bad), 2u);
  EXPECT_EQ(r.atArea(2), 0u);  // still the last good limit: nothing new to publish
  EXPECT_EQ(r.atArea(3), 1u);
  EXPECT_DOUBLE_EQ(r.last(), limitOf(3));  // kept as well
  EXPECT_EQ(r.atArea(4), 1u);
  EXPECT_DOUBLE_EQ(r.last(), 0.44);  // the good entry took effect
  EXPECT_EQ(r.atArea(5), 1u);
  EXPECT_DOUBLE_EQ(r.last(), kDefault);  // left out of the message: no limit any more
}

TEST(SpeedFilter, RepublishedMaskTakesEffectAtTheNextCycle)
{
  Rig r;
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  r.ctx->publishSpeedLimits(allLimits());
  EXPECT_EQ(r.atArea(23), 1u);
  OccupancyGridData m = makeMask();
  m.data[22] = 61;  // the robot's cell now belongs to area 61
  r.ctx->publishGrid(GridKind::Mask, m);
  EXPECT_EQ(r.atArea(23), 1u);
  EXPECT_DOUBLE_EQ(r.last(), limitOf(61));
  m.data[22] = 0;
  r.ctx->publishGrid(GridKind::Mask, m);
  EXPECT_EQ(r.atArea(23), 1u);
  EXPECT_DOUBLE_EQ(r.last(), kDefault);
  // A mask moved away: the robot is outside now.
  m = makeMask();
  m.origin_x = 100.0;
  r.ctx->publishGrid(GridKind::Mask, m);
  EXPECT_EQ(r.atArea(1), 0u);  // still the default
  EXPECT_EQ(r.at(100.5, 0.5), 1u);
  EXPECT_DOUBLE_EQ(r.last(), limitOf(1));
}

TEST(SpeedFilter, MaskInAnotherFrame)
{
  Rig r;
  const Transform2D to_mask{-1.0, -2.0, 0.0};  // map -> odom: points move by (-1, -2)
  r.ctx->transforms[{"odom", "map"}] = to_mask;
  r.ctx->transforms[{"map", "odom"}] = to_mask.inverse();
  r.ctx->publishGrid(GridKind::Mask, makeMask("odom"));
  r.ctx->publishSpeedLimits(allLimits());
  EXPECT_EQ(r.at(1.5, 2.5), 1u);  // odom (0.5, 0.5): area 1
  EXPECT_DOUBLE_EQ(r.last(), limitOf(1));
  EXPECT_EQ(r.at(4.5, 5.5), 1u);  // odom (3.5, 3.5): area 34
  EXPECT_DOUBLE_EQ(r.last(), limitOf(34));
  EXPECT_EQ(r.at(0.5, 0.5), 1u);  // odom (-0.5, -1.5): outside
  EXPECT_DOUBLE_EQ(r.last(), kDefault);
}

TEST(SpeedFilter, PercentMode)
{
  ParamValue p = params();
  p.set("speed_limit_in_percent", ParamValue::makeBool(true));
  Rig r(p);
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  SpeedLimitsData s;
  for (uint32_t id = 1; id <= 100; ++id)
    s.limits.push_back({id, static_cast<double>(id)});  // id %
  EXPECT_EQ(r.filter->setSpeedLimits(s), 0u);
  for (int id = 1; id <= 100; ++id)
  {
    ASSERT_EQ(r.atArea(id), 1u);
    EXPECT_DOUBLE_EQ(r.last(), kDefault * id / 100.0);
  }
  EXPECT_EQ(r.at(kFreeX, kFreeY), 0u);  // area 100 is 100 % = the default already
  EXPECT_DOUBLE_EQ(r.last(), kDefault);
  EXPECT_TRUE(r.ctx->reports.empty());
}

TEST(SpeedFilter, BadFeaturesAreRejectedPerEntry)
{
  Rig r;
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  SpeedLimitsData s;
  s.limits = {{1, 0.5}, {2, std::nan("")}, {3, -0.1}, {4, std::numeric_limits<double>::infinity()},
              {0, 0.3}, {101, 0.3},        {5, 0.0},  // 0 m/s is valid (it means "no limit")
              {6, 1.25}};
  EXPECT_EQ(r.filter->setSpeedLimits(s), 5u);
  // One report for the whole message, keyed by the field, naming every bad entry.
  ASSERT_EQ(r.ctx->reports.size(), 1u);
  const auto& rep = r.ctx->reports[0];
  EXPECT_EQ(rep.severity, Severity::Error);
  EXPECT_EQ(rep.key, "features/limits");
  EXPECT_NE(rep.message.find("speed_filter: /features: 5 of 8 entries dropped"), std::string::npos) << rep.message;
  EXPECT_EQ(r.ctx->countReports("limits[1] (area_id 2, max_speed nan)"), 1);
  EXPECT_EQ(r.ctx->countReports("limits[2] (area_id 3, max_speed -0.1)"), 1);
  EXPECT_EQ(r.ctx->countReports("limits[3] (area_id 4, max_speed inf)"), 1);
  EXPECT_EQ(r.ctx->countReports("area_id 0,"), 1);
  EXPECT_EQ(r.ctx->countReports("area_id 101,"), 1);
  r.ctx->reports.clear();
  // The good entries are in force; the dropped ones count as no limit (warned when met).
  EXPECT_EQ(r.atArea(1), 1u);
  EXPECT_DOUBLE_EQ(r.last(), 0.5);
  EXPECT_EQ(r.atArea(5), 1u);
  EXPECT_EQ(r.last(), 0.0);
  EXPECT_EQ(r.atArea(6), 1u);
  EXPECT_DOUBLE_EQ(r.last(), 1.25);
  EXPECT_EQ(r.atArea(2), 1u);
  EXPECT_DOUBLE_EQ(r.last(), kDefault);
  EXPECT_EQ(r.ctx->countReports("area 2 "), 1);

  // Percent mode: percentages outside (0, 100] are dropped too.
  ParamValue p = params();
  p.set("speed_limit_in_percent", ParamValue::makeBool(true));
  Rig q(p);
  q.ctx->publishGrid(GridKind::Mask, makeMask());
  SpeedLimitsData t;
  t.limits = {{1, 0.0}, {2, 100.5}, {3, -5.0}, {4, 100.0}, {5, 0.001}};
  EXPECT_EQ(q.filter->setSpeedLimits(t), 3u);
  ASSERT_EQ(q.ctx->reports.size(), 1u);
  EXPECT_NE(q.ctx->reports[0].message.find("3 of 5 entries dropped"), std::string::npos) << q.ctx->reports[0].message;
  // limits[0] and limits[1] break the percent rule; the negative one fails the m/s rule first.
  EXPECT_NE(q.ctx->reports[0].message.find("limits[0]"), std::string::npos) << q.ctx->reports[0].message;
  EXPECT_NE(q.ctx->reports[0].message.find("limits[1]"), std::string::npos) << q.ctx->reports[0].message;
  EXPECT_EQ(q.atArea(4), 1u);
  EXPECT_DOUBLE_EQ(q.last(), kDefault);
  EXPECT_EQ(q.atArea(5), 1u);
  EXPECT_DOUBLE_EQ(q.last(), kDefault * 0.001 / 100.0);
  EXPECT_EQ(q.atArea(1), 1u);  // dropped: default
  EXPECT_DOUBLE_EQ(q.last(), kDefault);
}

// The outside attack: 20 000 bad entries with distinct area ids printed 40 000 lines and left a
// throttle key per id. Now: one report with a fixed key and a bounded text, whatever the count.
TEST(SpeedFilter, ManyBadEntriesGiveOneBoundedReportWithAFixedKey)
{
  Rig r;
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  SpeedLimitsData s;
  for (uint32_t k = 0; k < 20000; ++k)
    s.limits.push_back({1000 + k, -1.0});
  for (uint32_t k = 0; k < 20000; ++k)
    s.limits.push_back({7, 0.1 + 1e-6 * k});
  EXPECT_EQ(r.filter->setSpeedLimits(s), 20000u);
  ASSERT_EQ(r.ctx->reports.size(), 2u);
  EXPECT_EQ(r.ctx->reports[0].key, "features/limits");
  EXPECT_EQ(r.ctx->reports[1].key, "features/limits.area_id");
  for (const auto& rep : r.ctx->reports)
  {
    EXPECT_LT(rep.message.size(), 2000u) << rep.message.substr(0, 300);
    EXPECT_NE(rep.message.find("more"), std::string::npos);
  }
  EXPECT_NE(r.ctx->reports[0].message.find("20000 of 40000 entries dropped"), std::string::npos);
  EXPECT_NE(r.ctx->reports[0].message.find("and 19992 more"), std::string::npos);
  // The good entries still apply (the later duplicate of area 7 wins).
  EXPECT_EQ(r.atArea(7), 1u);
  EXPECT_NEAR(r.last(), 0.1 + 1e-6 * 19999, 1e-9);
}

TEST(SpeedFilter, DuplicateIdsLaterWinsWithAWarning)
{
  Rig r;
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  SpeedLimitsData s;
  s.limits = {{9, 0.3}, {10, 0.4}, {9, 0.6}, {9, 0.7}};
  EXPECT_EQ(r.filter->setSpeedLimits(s), 0u);
  ASSERT_EQ(r.ctx->reports.size(), 1u);
  EXPECT_EQ(r.ctx->reports[0].severity, Severity::Warn);
  EXPECT_EQ(r.ctx->reports[0].key, "features/limits.area_id");
  EXPECT_NE(r.ctx->reports[0].message.find("2 repeated area id(s)"), std::string::npos) << r.ctx->reports[0].message;
  EXPECT_NE(r.ctx->reports[0].message.find("repeats area id 9"), std::string::npos) << r.ctx->reports[0].message;
  EXPECT_EQ(r.atArea(9), 1u);
  EXPECT_DOUBLE_EQ(r.last(), 0.7);
  // A later bad duplicate does not replace a good one.
  SpeedLimitsData t;
  t.limits = {{9, 0.3}, {9, -1.0}};
  EXPECT_EQ(r.filter->setSpeedLimits(t), 1u);
  EXPECT_EQ(r.atArea(9), 1u);
  EXPECT_DOUBLE_EQ(r.last(), 0.3);
}

TEST(SpeedFilter, UnknownIdsAreNoAreaWarnedOncePerId)
{
  Rig r;
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  // No features yet: every area is unknown.
  EXPECT_EQ(r.atArea(12), 1u);
  EXPECT_DOUBLE_EQ(r.last(), kDefault);
  EXPECT_EQ(r.ctx->countReports("area 12 "), 1);
  EXPECT_EQ(r.ctx->countReports("nothing received on /features"), 1);
  SpeedLimitsData s;
  s.limits = {{1, 0.1}};
  r.ctx->publishSpeedLimits(s);
  for (int k = 0; k < 5; ++k)
  {
    r.atArea(13);
    r.atArea(1);
    r.atArea(14);
    r.atArea(13);
  }
  EXPECT_EQ(r.ctx->countReports("area 13 "), 1);
  EXPECT_EQ(r.ctx->countReports("area 14 "), 1);
  EXPECT_EQ(r.ctx->countReports("area 1 "), 0);
  for (const auto& rep : r.ctx->reports)
    EXPECT_EQ(rep.severity, Severity::Warn);
  EXPECT_DOUBLE_EQ(r.last(), kDefault);
  // A new message that still lacks area 13: warned again, once.
  r.ctx->publishSpeedLimits(s);
  r.atArea(13);
  r.atArea(13);
  EXPECT_EQ(r.ctx->countReports("area 13 "), 2);
}

TEST(SpeedFilter, InvalidMaskValuesGiveTheDefaultWarnedOnce)
{
  Rig r;
  OccupancyGridData m = makeMask();
  m.data[0] = 120;
  m.data[1] = -7;
  r.ctx->publishGrid(GridKind::Mask, m);
  r.ctx->publishSpeedLimits(allLimits());
  for (int k = 0; k < 3; ++k)
  {
    r.atArea(3);
    EXPECT_DOUBLE_EQ(r.last(), limitOf(3));
    r.atArea(1);
    EXPECT_DOUBLE_EQ(r.last(), kDefault);
    r.atArea(3);
    r.atArea(2);
    EXPECT_DOUBLE_EQ(r.last(), kDefault);
  }
  EXPECT_EQ(r.ctx->countReports("value 120"), 1);
  EXPECT_EQ(r.ctx->countReports("value -7"), 1);
}

TEST(SpeedFilter, SwitchedOffRestoresTheDefaultAndOnAgainTheZone)
{
  Rig r;
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  r.ctx->publishSpeedLimits(allLimits());
  EXPECT_EQ(r.atArea(5), 1u);
  EXPECT_DOUBLE_EQ(r.last(), limitOf(5));
  const std::size_t before = r.ctx->published_speeds.size();
  r.ctx->toggle(false);  // no zone limits the robot any more: published by the switch itself, at once
  EXPECT_EQ(r.ctx->published_speeds.size() - before, 1u);
  EXPECT_DOUBLE_EQ(r.last(), kDefault);
  EXPECT_EQ(r.atArea(6), 0u);  // and nothing more while off
  r.ctx->toggle(true);
  EXPECT_EQ(r.atArea(5), 1u);
  EXPECT_DOUBLE_EQ(r.last(), limitOf(5));
}

// The filter writes no cost: its switch asks the host for no redraw (a keepout filter's does, the
// whole grid once: test_costmap_filter), while its output changes at once.
TEST(SpeedFilter, ASwitchAsksTheHostForNoRedraw)
{
  Rig r;
  r.lc.resizeMap(10, 10, 1.0, 0.0, 0.0);
  r.lc.addFilter(r.filter);
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  r.ctx->publishSpeedLimits(allLimits());
  r.lc.updateMap(centreOf(5).first, centreOf(5).second, 0.0);
  r.lc.updateMap(centreOf(5).first, centreOf(5).second, 0.0);
  EXPECT_TRUE(r.lc.getUpdatedBounds().empty());
  EXPECT_DOUBLE_EQ(r.last(), limitOf(5));
  r.ctx->toggle(false);
  EXPECT_DOUBLE_EQ(r.last(), kDefault);
  r.lc.updateMap(centreOf(5).first, centreOf(5).second, 0.0);
  EXPECT_TRUE(r.lc.getUpdatedBounds().empty());
  r.ctx->toggle(true);
  r.lc.updateMap(centreOf(5).first, centreOf(5).second, 0.0);
  EXPECT_TRUE(r.lc.getUpdatedBounds().empty());
  EXPECT_DOUBLE_EQ(r.last(), limitOf(5));
}

TEST(SpeedFilter, FeaturesFromAnotherThread)
{
  Rig r;
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  std::atomic<bool> stop{false};
  std::thread writer(
      [&]
      {
        SpeedLimitsData a = allLimits(), b = allLimits();
        for (auto& e : b.limits)
          e.max_speed *= 2.0;
        for (int k = 0; !stop; ++k)
          r.filter->setSpeedLimits(k % 2 ? a : b);
      });
  for (int k = 0; k < 2000; ++k)
  {
    r.atArea(k % 100 + 1);
    const double v = r.last();
    const double a = limitOf(k % 100 + 1);
    EXPECT_TRUE(v == kDefault || std::fabs(v - a) < 1e-12 || std::fabs(v - 2 * a) < 1e-12) << v;
  }
  stop = true;
  writer.join();
  r.filter->setSpeedLimits(allLimits());
  r.atArea(50);
  EXPECT_DOUBLE_EQ(r.last(), limitOf(50));
}

// ---------------------------------------------------------------- nav2 mode

TEST(SpeedFilterNav2, MetresPerSecond)
{
  ParamValue p = params();
  p.set("mask_mode", ParamValue::makeString("nav2"));
  p.set("base", ParamValue::makeDouble(0.1));
  p.set("multiplier", ParamValue::makeDouble(0.01));
  Rig r(p);
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  for (int v = 1; v <= 100; ++v)
  {
    ASSERT_EQ(r.atArea(v), 1u);
    EXPECT_DOUBLE_EQ(r.last(), 0.1 + 0.01 * v);
  }
  EXPECT_EQ(r.at(kFreeX, kFreeY), 1u);  // 0: no limit
  EXPECT_DOUBLE_EQ(r.last(), kDefault);
  EXPECT_EQ(r.atArea(40), 1u);
  EXPECT_EQ(r.at(kUnknownX, kUnknownY), 0u);  // -1 keeps the last value
  EXPECT_DOUBLE_EQ(r.last(), 0.5);
  EXPECT_EQ(r.at(-1, -1), 1u);
  EXPECT_DOUBLE_EQ(r.last(), kDefault);
  // Features are ignored in this mode.
  r.filter->setSpeedLimits(allLimits());
  EXPECT_EQ(r.atArea(40), 1u);
  EXPECT_DOUBLE_EQ(r.last(), 0.5);
  EXPECT_TRUE(r.ctx->reports.empty());
}

TEST(SpeedFilterNav2, LimitsNotAboveZeroMeanNoLimit)
{
  ParamValue p = params();
  p.set("mask_mode", ParamValue::makeString("nav2"));
  p.set("base", ParamValue::makeDouble(-0.5));
  p.set("multiplier", ParamValue::makeDouble(0.1));
  Rig r(p);
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  for (int k = 0; k < 2; ++k)
    for (int v = 1; v <= 8; ++v)
    {
      r.atArea(v);
      const double l = -0.5 + 0.1 * v;
      if (v <= 5)  // -0.4 .. 0.0 m/s
        EXPECT_DOUBLE_EQ(r.last(), kDefault) << v;
      else
        EXPECT_DOUBLE_EQ(r.last(), l) << v;
    }
  for (int v = 1; v <= 4; ++v)
    EXPECT_EQ(r.ctx->countReports("mask value " + std::to_string(v) + " gives"), 1) << v;
  // v = 5 gives exactly 0: no limit, which Nav2's rule does not count as out of range (not warned).
  EXPECT_EQ(r.ctx->reports.size(), 4u);
}

TEST(SpeedFilterNav2, Percent)
{
  ParamValue p = params();
  p.set("mask_mode", ParamValue::makeString("nav2"));
  p.set("speed_limit_in_percent", ParamValue::makeBool(true));
  p.set("base", ParamValue::makeDouble(-20.0));
  p.set("multiplier", ParamValue::makeDouble(2.0));
  Rig r(p);
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  // v = 1..9 give -18 .. -2 % and 61..100 give > 100 %: out of range (no limit, warned); v = 10 gives
  // 0 %, which is no limit itself (Nav2's rule: in range, not warned); 11..60 give 2 .. 100 %.
  for (int v = 1; v <= 100; ++v)
  {
    r.atArea(v);
    const double pct = -20.0 + 2.0 * v;
    if (pct > 0.0 && pct <= 100.0)
      EXPECT_DOUBLE_EQ(r.last(), kDefault * pct / 100.0) << v;
    else
      EXPECT_DOUBLE_EQ(r.last(), kDefault) << v;
  }
  EXPECT_EQ(r.ctx->countReports("outside [0, 100]"), 9 + 40);
  EXPECT_EQ(r.ctx->countReports("mask value 61 gives base + multiplier * v = -20 + 2 * 61 = 102 %"), 1);
  EXPECT_EQ(r.ctx->countReports("mask value 10 gives"), 0);
  // Once per value.
  r.atArea(61);
  r.atArea(30);
  r.atArea(61);
  EXPECT_EQ(r.ctx->countReports("outside [0, 100]"), 49);
}

TEST(SpeedFilter, OutOfOrderFeaturesAreDroppedWhole)
{
  Rig r;
  r.ctx->now_ns = 100'000'000'000;
  r.ctx->publishGrid(GridKind::Mask, makeMask());
  SpeedLimitsData good = allLimits();
  good.stamp_ns = 50'000'000'000;
  r.ctx->publishSpeedLimits(good);
  ASSERT_EQ(r.atArea(5), 1u);
  EXPECT_DOUBLE_EQ(r.last(), limitOf(5));

  // Every limit 0.9 m/s, but stamped before the message in force: dropped whole.
  SpeedLimitsData older = allLimits();
  older.stamp_ns = 40'000'000'000;
  for (auto& l : older.limits)
    l.max_speed = 0.9;
  EXPECT_EQ(r.filter->setSpeedLimits(older), older.limits.size());
  ASSERT_EQ(r.atArea(6), 1u);
  EXPECT_DOUBLE_EQ(r.last(), limitOf(6));
  ASSERT_EQ(r.ctx->reports.size(), 1u);
  EXPECT_EQ(r.ctx->reports[0].key, "features_stamp");
  EXPECT_NE(r.ctx->reports[0].message.find("header.stamp 40.000 s is older than the speed limits message in force"),
            std::string::npos)
      << r.ctx->reports[0].message;

  // After the clock went back (a restarted simulation) it is accepted.
  r.ctx->now_ns = 10'000'000'000;
  EXPECT_EQ(r.filter->setSpeedLimits(older), 0u);
  ASSERT_EQ(r.atArea(7), 1u);
  EXPECT_DOUBLE_EQ(r.last(), 0.9);
}

// ---------------------------------------------------------------- bounds

// SpeedFilter writes nothing into the costmap: a new mask, a switch off and on, ask for no redraw; the
// bounds stay exactly what the layers before it asked for (here: an empty box, then a small one).
TEST(SpeedFilter, NewMaskAsksForNoRedraw)
{
  Rig rig;
  rig.filter->setSpeedLimits(allLimits());
  for (int round = 0; round < 3; ++round)
  {
    if (round == 0) ASSERT_EQ(rig.filter->setMask(std::make_shared<OccupancyGridData>(makeMask())), "");
    if (round == 1) rig.filter->setEnabled(false);
    if (round == 2) rig.filter->setEnabled(true);
    double x0 = 1e30, y0 = 1e30, x1 = -1e30, y1 = -1e30;
    rig.filter->updateBounds(centreOf(5).first, centreOf(5).second, 0.0, &x0, &y0, &x1, &y1);
    EXPECT_EQ(x0, 1e30) << "round " << round;
    EXPECT_EQ(y0, 1e30);
    EXPECT_EQ(x1, -1e30);
    EXPECT_EQ(y1, -1e30);
    double a0 = 2.0, b0 = 3.0, a1 = 2.5, b1 = 3.5;
    ASSERT_EQ(rig.filter->setMask(std::make_shared<OccupancyGridData>(makeMask())), "");
    rig.filter->updateBounds(centreOf(5).first, centreOf(5).second, 0.0, &a0, &b0, &a1, &b1);
    EXPECT_EQ(a0, 2.0);
    EXPECT_EQ(b0, 3.0);
    EXPECT_EQ(a1, 2.5);
    EXPECT_EQ(b1, 3.5);
  }
  // It still acts: the robot in area 5 gets area 5's limit.
  EXPECT_DOUBLE_EQ(rig.last(), limitOf(5));
}
