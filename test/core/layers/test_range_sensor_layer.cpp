#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/costmap/costmap_clearing.hpp"
#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/layers/range_sensor_layer.hpp"
#include "fake_context.hpp"
#include "sensor_test_helpers.hpp"

using namespace costmap_layers;
using namespace costmap_layers_test;

namespace
{
RangeData sonar(float range, float min_range = 1.0f, float max_range = 7.0f)
{
  RangeData r;
  r.frame_id = "base_link";
  r.radiation_type = RangeData::ULTRASOUND;
  r.field_of_view = 0.174533f;  // 10 degrees
  r.min_range = min_range;
  r.max_range = max_range;
  r.range = range;
  return r;
}

struct Rig
{
  explicit Rig(ParamValue params, bool rolling = false, bool track_unknown = false) : lc("map", rolling, track_unknown)
  {
    lc.resizeMap(10, 10, 1.0, 0.0, 0.0);
    ctx = std::make_shared<FakeContext>(std::move(params));
    layer = std::make_shared<RangeSensorLayer>();
    layer->initialize(&lc, "range", ctx);
    ctx->bind(*layer);
    lc.addPlugin(layer);
  }
  void range(const RangeData& r, double x, double y, double yaw = 0.0)
  {
    ASSERT_EQ(ctx->publishRange("/range/topic", r, poseAt(x, y, 0.0, yaw)), 1);
  }
  void update(double x = 0, double y = 0) { lc.updateMap(x, y, 0); }
  uint8_t at(unsigned x, unsigned y) const { return lc.getCostmap().getCost(x, y); }

  LayeredCostmap lc;
  std::shared_ptr<FakeContext> ctx;
  std::shared_ptr<RangeSensorLayer> layer;
};

ParamValue nav2Params(bool clear_on_max = true)
{
  return paramMap({{"topics", ParamValue::makeList({S("/range/topic")})},
                   {"phi", D(1.2)},
                   {"clear_on_max_reading", B(clear_on_max)}});
}
}  // namespace

TEST(RangeSensorConfig, DefaultsAndErrors)
{
  const RangeSensorConfig c = parseRangeSensorConfig(ParamReader(ParamValue::makeMap(), "r"));
  EXPECT_TRUE(c.topics.empty());
  EXPECT_DOUBLE_EQ(c.phi, 1.2);
  EXPECT_DOUBLE_EQ(c.inflate_cone, 1.0);
  EXPECT_DOUBLE_EQ(c.no_readings_timeout, 0.0);
  EXPECT_DOUBLE_EQ(c.clear_threshold, 0.2);
  EXPECT_DOUBLE_EQ(c.mark_threshold, 0.8);
  EXPECT_FALSE(c.clear_on_max_reading);
  EXPECT_EQ(c.input_sensor_type, RangeInputType::All);
  EXPECT_EQ(parseRangeSensorConfig(ParamReader(paramMap({{"topics", S("/a /b")}}), "r")).topics.size(), 2u);
  EXPECT_EQ(parseRangeSensorConfig(ParamReader(paramMap({{"input_sensor_type", S("FIXED")}}), "r")).input_sensor_type,
            RangeInputType::Fixed);
  auto bad = [](const char* k, ParamValue v) {
    EXPECT_THROW(parseRangeSensorConfig(ParamReader(paramMap({{k, v}}), "r")), std::invalid_argument) << k;
  };
  bad("topics", I(1));
  bad("topics", ParamValue::makeList({S("")}));
  bad("phi", D(0.0));
  bad("inflate_cone", D(1.5));
  bad("no_readings_timeout", D(-1.0));
  bad("clear_threshold", D(0.9));  // above mark_threshold 0.8
  bad("mark_threshold", D(1.1));
  bad("input_sensor_type", S("SONAR"));
  bad("clear_on_max_reading", S("true"));
}

TEST(RangeSensorModel, Pieces)
{
  using namespace range_model;
  EXPECT_DOUBLE_EQ(gamma(0.0, 0.1), 1.0);
  EXPECT_DOUBLE_EQ(gamma(0.1, 0.1), 0.0);
  EXPECT_DOUBLE_EQ(gamma(0.2, 0.1), 0.0);
  EXPECT_NEAR(gamma(0.05, 0.1), 0.75, 1e-12);
  EXPECT_DOUBLE_EQ(delta(1.2, 1.2), 0.5);
  EXPECT_GT(delta(0.1, 1.2), 0.9);
  // Ahead of the reading: below 0.5 (free), at it: above 0.5 (occupied), behind: 0.5.
  EXPECT_LT(sensorModel(3.0, 1.0, 0.0, 0.1, 1.2, 0.1), 0.5);
  EXPECT_GT(sensorModel(3.0, 3.0, 0.0, 0.1, 1.2, 0.1), 0.5);
  EXPECT_DOUBLE_EQ(sensorModel(3.0, 4.0, 0.0, 0.1, 1.2, 0.1), 0.5);
  EXPECT_EQ(toCost(0.5), 127);
  EXPECT_EQ(toCost(1.0), 254);
  EXPECT_DOUBLE_EQ(toProbability(254), 1.0);
  EXPECT_DOUBLE_EQ(toProbability(NO_INFORMATION), 0.5);  // a cleared cell: unknown
}

// Nav2's testClearingAtMaxRange.
TEST(RangeSensorLayer, MarksAtTheReadingAndClearsOnMaxReading)
{
  Rig rig(nav2Params(true));
  ASSERT_EQ(rig.ctx->range_subs.size(), 1u);
  EXPECT_EQ(rig.ctx->range_subs[0].topic, "/range/topic");
  rig.range(sonar(2.0f), 2.0, 5.0);
  rig.update();
  EXPECT_EQ(rig.at(4, 5), 254);
  rig.range(sonar(7.0f), 2.0, 5.0);
  rig.update();
  EXPECT_EQ(rig.at(4, 5), 0);
}

// A clear-costmap request (move_base's recovery through the bridge, ~clear_around_robot) leaves
// NO_INFORMATION (255) in the cleared cells, as costmap_2d's clearArea does. Read as a probability that
// is 255 / 254 > 1: the next reading, whatever it said, made the cell certain (an obstacle where the
// sonar saw free space). A cleared cell is an unknown prior (0.5), as a cell never seen.
TEST(RangeSensorLayer, AClearedCellIsAnUnknownPrior)
{
  Rig cleared(nav2Params(false)), fresh(nav2Params(false));
  cleared.range(sonar(2.0f), 2.5, 5.5);  // an obstacle at (4, 5) (cell centres on the beam's axis)
  cleared.update();
  ASSERT_EQ(cleared.at(4, 5), 254);
  ASSERT_TRUE(clearLayerArea(*cleared.layer, 0, 0, 0, 0, false));  // every cell
  ASSERT_EQ(cleared.layer->costmap().getCost(4, 5), NO_INFORMATION);
  ASSERT_EQ(cleared.layer->costmap().getCost(3, 5), NO_INFORMATION);
  for (Rig* r : {&cleared, &fresh})
  {
    r->range(sonar(5.0f), 2.5, 5.5);  // free up to (7, 5): (3, 5) and (4, 5) lie ahead of the reading
    r->update();
  }
  // Only the reading's own cell (7, 5) is an obstacle; before, (2, 5) to (8, 5) all were.
  for (unsigned x = 0; x < 10; ++x)
    EXPECT_EQ(cleared.at(x, 5), x == 7 ? LETHAL_OBSTACLE : FREE_SPACE) << x;
  // The cells the reading reached hold what they hold in a layer that never saw the first reading;
  // where the model gives no information (p = 0.5: cost 127) the cleared cell is 127, not certain.
  for (unsigned x = 2; x <= 8; ++x)
    EXPECT_EQ(cleared.layer->costmap().getCost(x, 5), fresh.layer->costmap().getCost(x, 5)) << x;
  for (unsigned x : {2u, 5u, 6u, 8u})
    EXPECT_EQ(cleared.layer->costmap().getCost(x, 5), 127) << x;
  EXPECT_EQ(cleared.at(7, 5), LETHAL_OBSTACLE);  // the reading's own cell
}

TEST(RangeSensorLayer, MaxReadingWithoutClearOnMaxDoesNotClear)
{
  Rig rig(nav2Params(false));
  rig.range(sonar(2.0f), 2.0, 5.0);
  rig.update();
  ASSERT_EQ(rig.at(4, 5), 254);
  rig.range(sonar(7.0f), 2.0, 5.0);  // a normal reading at 7 m, not a clearing one
  rig.update();
  EXPECT_EQ(rig.at(9, 5), 254);  // the new target cell
  EXPECT_EQ(rig.at(4, 5), 254);  // outside the 10-degree cone's model weight: unchanged
}

// Nav2's testProbabilisticModelForward and testProbabilisticModelDownward.
TEST(RangeSensorLayer, ProbabilisticModelForwardAndDownward)
{
  {
    Rig rig(nav2Params(true));
    for (double x : {2.0, 4.0, 6.0})
    {
      rig.range(sonar(3.0f, 1.0f, 10.0f), x, 5.0);
      rig.update();
    }
    EXPECT_EQ(rig.at(5, 5), 254);
    EXPECT_EQ(rig.at(6, 5), 0);
    EXPECT_EQ(rig.at(7, 5), 254);
    EXPECT_EQ(rig.at(8, 5), 0);
    EXPECT_EQ(rig.at(9, 5), 254);
  }
  {
    Rig rig(nav2Params(true));
    for (double y : {3.0, 5.0, 7.0})
    {
      rig.range(sonar(1.0f, 1.0f, 10.0f), 2.0, y);
      rig.update();
    }
    EXPECT_EQ(rig.at(3, 3), 254);
    EXPECT_EQ(rig.at(3, 4), 0);
    EXPECT_EQ(rig.at(3, 5), 254);
    EXPECT_EQ(rig.at(3, 6), 0);
    EXPECT_EQ(rig.at(3, 7), 254);
  }
}

TEST(RangeSensorLayer, FacingOtherDirections)
{
  Rig rig(nav2Params(true));
  rig.range(sonar(3.0f), 5.0, 5.0, M_PI / 2);  // facing +y: target (5, 8)
  rig.update();
  EXPECT_EQ(rig.at(5, 8), 254);
  EXPECT_EQ(rig.at(8, 5), 0);  // untouched, p = 0.5: neither mark nor clear over the free master
  EXPECT_EQ(rig.layer->costmap().getCost(8, 5), 127);
}

TEST(RangeSensorLayer, FixedRangersUseInfinities)
{
  ParamValue p = nav2Params(true);
  p.set("input_sensor_type", S("FIXED"));
  Rig rig(p);
  RangeData r = sonar(-std::numeric_limits<float>::infinity(), 2.0f, 2.0f);
  rig.range(r, 2.0, 5.0);
  rig.update();
  EXPECT_EQ(rig.at(4, 5), 254);  // detected at min_range
  r.range = 1.5f;                // not +-inf: rejected
  EXPECT_FALSE(rig.layer->addRange(r, poseAt(2, 5, 0)).empty());
  EXPECT_EQ(rig.ctx->countReports("fixed-distance"), 1);
  r.range = std::numeric_limits<float>::infinity();  // nothing in view: clears
  rig.range(r, 2.0, 5.0);
  rig.update();
  EXPECT_EQ(rig.at(4, 5), 0);
}

TEST(RangeSensorLayer, MalformedReadingsAreRejected)
{
  Rig rig(nav2Params(true));
  RangeData r = sonar(2.0f);
  r.field_of_view = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(rig.layer->addRange(r, poseAt(2, 5, 0)).empty());
  r = sonar(std::numeric_limits<float>::quiet_NaN());
  EXPECT_FALSE(rig.layer->addRange(r, poseAt(2, 5, 0)).empty());
  r = sonar(2.0f, 3.0f, 1.0f);  // max below min
  EXPECT_FALSE(rig.layer->addRange(r, poseAt(2, 5, 0)).empty());
  r = sonar(0.5f);  // below min_range: ignored, not an error
  EXPECT_TRUE(rig.layer->addRange(r, poseAt(2, 5, 0)).empty());
  r = sonar(3.0e38f, 1.0f, 3.4e38f);  // absurd but well-formed: ignored when applied
  EXPECT_TRUE(rig.layer->addRange(r, poseAt(2, 5, 0)).empty());
  EXPECT_EQ(rig.layer->pending(), 1u);
  rig.update();
  EXPECT_EQ(rig.ctx->countReports("too far"), 1);
  EXPECT_EQ(rig.ctx->countReports("rejected"), 3);
  for (unsigned k = 0; k < 100; ++k)
    EXPECT_EQ(rig.layer->costmap().getCost(k), 127) << k;
}

TEST(RangeSensorLayer, NoReadingsTimeout)
{
  ParamValue p = nav2Params(true);
  p.set("no_readings_timeout", D(1.0));
  Rig rig(p);
  rig.ctx->now_ns = 500'000'000;
  rig.update();
  EXPECT_TRUE(rig.layer->isCurrent());
  rig.ctx->now_ns = 1'500'000'000;
  rig.update();
  EXPECT_FALSE(rig.layer->isCurrent());
  EXPECT_EQ(rig.ctx->countReports("no range readings for 1.50 s"), 1);
  rig.range(sonar(2.0f), 2.0, 5.0);
  rig.update();
  EXPECT_TRUE(rig.layer->isCurrent());
}

TEST(RangeSensorLayer, ResetAndRollingWindow)
{
  Rig rig(nav2Params(true), true);
  rig.range(sonar(2.0f), 2.0, 5.0);
  rig.update(5.0, 5.0);  // origin (0, 0)
  ASSERT_EQ(rig.at(4, 5), 254);
  rig.update(6.0, 5.0);  // origin (1, 0): the obstacle moves one cell left in the grid
  EXPECT_EQ(rig.layer->costmap().getCost(3, 5), 233);
  EXPECT_EQ(rig.layer->costmap().getCost(9, 5), 127);  // new cells start at p = 0.5
  rig.layer->reset();
  EXPECT_EQ(rig.layer->costmap().getCost(3, 5), 127);
  EXPECT_TRUE(rig.layer->isClearable());
}

// The outside attack: ~750 ranges a second queued without a bound and were all applied in one cycle,
// under the lock services need. Now the queue holds at most kMaxPending; the oldest are dropped and
// counted in one report at the next update.
TEST(RangeSensorLayer, AFloodIsBoundedAndReported)
{
  Rig r(nav2Params());
  for (int k = 0; k < 10000; ++k)
    r.range(sonar(2.0f), 1.5, 5.0);
  EXPECT_EQ(r.layer->pending(), RangeSensorLayer::kMaxPending);
  r.update(1.5, 5.0);
  EXPECT_EQ(r.layer->pending(), 0u);
  ASSERT_EQ(r.ctx->countReports("dropped the " + std::to_string(10000 - RangeSensorLayer::kMaxPending) + " oldest"), 1);
  for (const auto& rep : r.ctx->reports)
    if (rep.message.find("oldest") != std::string::npos) EXPECT_EQ(rep.key, "flood");
  // The readings kept still mark: the cell 2 m ahead of the sensor.
  EXPECT_GT(r.at(3, 5), 0u);
  // No flood, no report.
  r.ctx->reports.clear();
  r.range(sonar(2.0f), 1.5, 5.0);
  r.update(1.5, 5.0);
  EXPECT_EQ(r.ctx->countReports("oldest"), 0);
}

// Readings with big cones on a big grid: the readings' count alone does not bound a cycle's work, the
// cells their cones cover do. The oldest are dropped once kMaxCellsPerUpdate cells are spent.
TEST(RangeSensorLayer, TheWorkOfOneUpdateIsBoundedByCells)
{
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(2000, 2000, 0.05, 0.0, 0.0);  // 100 m square, 4 M cells
  auto ctx = std::make_shared<FakeContext>(nav2Params());
  auto layer = std::make_shared<RangeSensorLayer>();
  layer->initialize(&lc, "range", ctx);
  ctx->bind(*layer);
  lc.addPlugin(layer);
  RangeData wide = sonar(6.0f, 0.1f, 7.0f);
  wide.field_of_view = 1.5f;
  // Each cone's bounding box is about (2 x 1.2 x 6 m / 0.05 m)^2 = 82 944 cells: 100 of them are 8 M.
  const double box = std::pow(2 * 1.2 * 6.0 / 0.05, 2);
  ASSERT_GT(100 * box, static_cast<double>(RangeSensorLayer::kMaxCellsPerUpdate));
  for (int k = 0; k < 100; ++k)
    ASSERT_EQ(ctx->publishRange("/range/topic", wide, poseAt(50.0, 50.0, 0.0, 0.0)), 1);
  lc.updateMap(50.0, 50.0, 0.0);
  ASSERT_EQ(ctx->countReports("oldest since the last update"), 1);
  std::string report;
  for (const auto& r : ctx->reports)
    if (r.message.find("oldest") != std::string::npos) report = r.message;
  const int dropped = std::stoi(report.substr(report.find("dropped the ") + 12));
  // At most the budget was spent (each applied cone costs at least its box within a few cells).
  EXPECT_GE(dropped, 100 - static_cast<int>(RangeSensorLayer::kMaxCellsPerUpdate / (0.9 * box))) << report;
  EXPECT_LT(dropped, 100) << report;  // the newest readings were applied
  unsigned mx, my;
  ASSERT_TRUE(lc.getCostmap().worldToMap(56.0, 50.0, mx, my));
  EXPECT_GT(lc.getCostmap().getCost(mx, my), 0u);
}

TEST(RangeSensorLayer, NoReadingsTimeoutAfterAClockJumpBack)
{
  // The clock restarts (looping bag, restarted simulator): silence is measured on the new clock from
  // the jump on, instead of looking current until the clock is back at the last reading's time.
  ParamValue p = nav2Params(true);
  p.set("no_readings_timeout", D(1.0));
  Rig rig(p);
  rig.ctx->now_ns = 1000'000'000'000;
  rig.range(sonar(2.0f), 2.0, 5.0);
  rig.update();
  EXPECT_TRUE(rig.layer->isCurrent());
  rig.ctx->now_ns = 5'000'000'000;
  rig.update();
  EXPECT_TRUE(rig.layer->isCurrent());
  EXPECT_EQ(rig.ctx->countReports("jumped back"), 1);
  rig.ctx->now_ns = 6'500'000'000;
  rig.update();
  EXPECT_FALSE(rig.layer->isCurrent());
  EXPECT_EQ(rig.ctx->countReports("no range readings for 1.50 s"), 1);
  EXPECT_EQ(rig.ctx->countReports("jumped back"), 1);  // one warning per jump
  // A step back of 0.2 s is the jitter of threads reading the clock, not a jump.
  rig.range(sonar(2.0f), 2.0, 5.0);
  rig.update();
  rig.ctx->now_ns = 6'300'000'000;
  rig.update();
  EXPECT_TRUE(rig.layer->isCurrent());
  EXPECT_EQ(rig.ctx->countReports("jumped back"), 1);
}

TEST(RangeSensorLayer, ReadingStampedAheadOfNowIsRejected)
{
  Rig rig(nav2Params(true));
  rig.ctx->now_ns = 10'000'000'000;
  RangeData r = sonar(2.0f);
  r.stamp_ns = 100'000'000'000;
  const std::string err = rig.layer->addRange(r, poseAt(2.0, 5.0, 0.0));
  EXPECT_NE(err.find("header.stamp 100.000 s"), std::string::npos) << err;
  EXPECT_NE(err.find("now 10.000 s"), std::string::npos) << err;
  EXPECT_EQ(rig.layer->pending(), 0u);
  r.stamp_ns = UINT64_MAX;
  EXPECT_FALSE(rig.layer->addRange(r, poseAt(2.0, 5.0, 0.0)).empty());
  r.stamp_ns = 10'400'000'000;  // skew within half a second: accepted
  EXPECT_EQ(rig.layer->addRange(r, poseAt(2.0, 5.0, 0.0)), "");
  r.stamp_ns = 0;  // no stamp: accepted
  EXPECT_EQ(rig.layer->addRange(r, poseAt(2.0, 5.0, 0.0)), "");
  EXPECT_EQ(rig.layer->pending(), 2u);
}

// A sender's megabyte frame_id is named by its first 64 characters and its length, not copied whole
// into the report (the log line and the throttled report stay small).
TEST(RangeSensorLayer, AHugeFrameIdIsShownClipped)
{
  Rig rig(nav2Params(true));
  RangeData r = sonar(std::numeric_limits<float>::quiet_NaN());
  r.frame_id = std::string(1000000, 'f');
  EXPECT_FALSE(rig.layer->addRange(r, poseAt(2, 5, 0)).empty());
  ASSERT_FALSE(rig.ctx->reports.empty());
  const std::string& said = rig.ctx->reports.back().message;
  EXPECT_LT(said.size(), 400u) << said.substr(0, 400);
  EXPECT_NE(said.find(std::string(64, 'f') + "... (1000000 characters)"), std::string::npos) << said.substr(0, 400);
}

TEST(ShownText, ClipsAfterMaxAndSaysHowLong)
{
  EXPECT_EQ(shownText("base_link"), "base_link");
  EXPECT_EQ(shownText(std::string(64, 'a')), std::string(64, 'a'));
  EXPECT_EQ(shownText(std::string(65, 'a')), std::string(64, 'a') + "... (65 characters)");
  EXPECT_EQ(shownText("abcdef", 3), "abc... (6 characters)");
  EXPECT_EQ(shownText(""), "");
}
