// Layer::status(): what each layer says for /diagnostics, without ROS: the default from enabled() and
// isCurrent(), a static layer waiting for its map, a filter without a mask, a late sensor source, a
// silent range sensor, and a rejected input named with its reason.
#include <gtest/gtest.h>

#include "costmap_layers/core/layers/gradient_layer.hpp"
#include "costmap_layers/core/filters/keepout_filter.hpp"
#include "costmap_layers/core/costmap/layer_status.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/layers/obstacle_layer.hpp"
#include "costmap_layers/core/layers/range_sensor_layer.hpp"
#include "costmap_layers/core/layers/static_layer.hpp"
#include "fake_context.hpp"
#include "sensor_test_helpers.hpp"

using namespace costmap_layers;
using namespace costmap_layers_test;

namespace
{
OccupancyGridData grid(uint32_t w, uint32_t h, double res = 1.0)
{
  OccupancyGridData m;
  m.frame_id = "map";
  m.width = w;
  m.height = h;
  m.resolution = res;
  m.data.assign(static_cast<std::size_t>(w) * h, 0);
  return m;
}

template <class L>
std::shared_ptr<L> add(LayeredCostmap& lc, const std::string& name, std::shared_ptr<FakeContext> ctx,
                       bool filter = false)
{
  auto layer = std::make_shared<L>();
  layer->initialize(&lc, name, ctx);
  ctx->bind(*layer);
  if (filter)
    lc.addFilter(layer);
  else
    lc.addPlugin(layer);
  return layer;
}

bool contains(const std::string& text, const std::string& needle)
{
  return text.find(needle) != std::string::npos;
}
}  // namespace

TEST(LayerStatus, RaiseKeepsTheWorstAndJoinsEquals)
{
  LayerStatus s;
  s.message = "fine";
  s.raise(StatusLevel::Warn, "a");
  EXPECT_EQ(s.level, StatusLevel::Warn);
  EXPECT_EQ(s.message, "a");
  s.raise(StatusLevel::Warn, "b");
  EXPECT_EQ(s.message, "a; b");
  s.raise(StatusLevel::Error, "c");
  EXPECT_EQ(s.message, "c");
  s.raise(StatusLevel::Warn, "d");
  EXPECT_EQ(s.level, StatusLevel::Error);
  EXPECT_EQ(s.message, "c");
  s.add("k", "v");
  EXPECT_EQ(s.value("k"), "v");
  EXPECT_EQ(s.value("none"), "");
  EXPECT_EQ(describeAge(1.5), "1.50 s ago");
  EXPECT_EQ(describeAge(-1), "never");
  EXPECT_DOUBLE_EQ(secondsBetween(2'000'000'000, 500'000'000), 0.0);  // a clock that jumped back
}

TEST(LayerStatus, DefaultFollowsEnabledAndCurrent)
{
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(10, 10, 1.0, 0, 0);
  auto g = add<GradientLayer>(lc, "gradient", std::make_shared<FakeContext>());
  LayerStatus s = g->status();
  EXPECT_EQ(s.level, StatusLevel::Ok);
  EXPECT_EQ(s.message, "current");
  EXPECT_EQ(s.value("enabled"), "true");
  EXPECT_EQ(s.value("current"), "true");
  g->setEnabled(false);
  s = g->status();
  EXPECT_EQ(s.level, StatusLevel::Ok);
  EXPECT_EQ(s.message, "disabled");
}

TEST(LayerStatus, StaticLayerWithoutMapIsAnErrorNamingTheTopic)
{
  LayeredCostmap lc("map", false, true);
  lc.resizeMap(10, 10, 1.0, 0, 0);
  auto ctx = std::make_shared<FakeContext>(paramMap({{"map_topic", S("/warehouse_map")}}));
  auto layer = add<StaticLayer>(lc, "static_layer", ctx);
  ctx->now_ns = 1'000'000'000;
  lc.updateMap(0, 0, 0);
  LayerStatus s = layer->status();
  EXPECT_EQ(s.level, StatusLevel::Error);
  EXPECT_TRUE(contains(s.message, "no map yet on /warehouse_map")) << s.message;
  EXPECT_EQ(s.value("map topic"), "/warehouse_map");
  EXPECT_EQ(s.value("last map accepted"), "never");

  // A bad map is named with its reason while none is in force.
  OccupancyGridData bad = grid(4, 4);
  bad.data.resize(3);
  EXPECT_FALSE(layer->setMap(std::make_shared<const OccupancyGridData>(bad)).empty());
  s = layer->status();
  EXPECT_EQ(s.level, StatusLevel::Error);
  EXPECT_TRUE(contains(s.message, "every map so far rejected")) << s.message;
  EXPECT_EQ(s.value("maps rejected"), "1");

  // A good map: OK once drawn, with when it arrived.
  EXPECT_EQ(layer->setMap(std::make_shared<const OccupancyGridData>(grid(6, 5))), "");
  s = layer->status();
  EXPECT_EQ(s.level, StatusLevel::Ok);
  EXPECT_TRUE(contains(s.message, "drawn at the next update")) << s.message;
  ctx->now_ns = 3'500'000'000;
  lc.updateMap(0, 0, 0);
  s = layer->status();
  EXPECT_EQ(s.level, StatusLevel::Ok) << s.message;
  EXPECT_TRUE(contains(s.message, "6 x 5 cells")) << s.message;
  EXPECT_EQ(s.value("last map accepted"), "2.50 s ago");
  EXPECT_EQ(s.value("maps accepted"), "1");

  // A later bad map: WARN, the previous one stays.
  EXPECT_FALSE(layer->setMap(std::make_shared<const OccupancyGridData>(bad)).empty());
  s = layer->status();
  EXPECT_EQ(s.level, StatusLevel::Warn);
  EXPECT_TRUE(contains(s.message, "previous one stays")) << s.message;
}

TEST(LayerStatus, FilterWithoutMaskWarnsNamingTheTopic)
{
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(10, 10, 1.0, 0, 0);
  auto ctx = std::make_shared<FakeContext>(paramMap({{"mask_topic", S("/keepout_mask")}}));
  auto filter = add<KeepoutFilter>(lc, "keepout", ctx, true);
  lc.updateMap(0, 0, 0);
  LayerStatus s = filter->status();
  EXPECT_EQ(s.level, StatusLevel::Warn);
  EXPECT_TRUE(contains(s.message, "no mask yet on /keepout_mask")) << s.message;
  filter->setEnabled(false);
  EXPECT_EQ(filter->status().level, StatusLevel::Ok);
  EXPECT_EQ(filter->status().message, "switched off");
  filter->setEnabled(true);
  EXPECT_EQ(filter->setMask(std::make_shared<const OccupancyGridData>(grid(10, 10))), "");
  lc.updateMap(0, 0, 0);
  s = filter->status();
  EXPECT_EQ(s.level, StatusLevel::Ok) << s.message;
  EXPECT_TRUE(contains(s.message, "in force")) << s.message;
  EXPECT_EQ(s.value("masks accepted"), "1");
  // A mask in a frame tf cannot reach: WARN, naming the frame.
  OccupancyGridData elsewhere = grid(10, 10);
  elsewhere.frame_id = "nowhere";
  EXPECT_EQ(filter->setMask(std::make_shared<const OccupancyGridData>(elsewhere)), "");
  lc.updateMap(0, 0, 0);
  s = filter->status();
  EXPECT_EQ(s.level, StatusLevel::Warn);
  EXPECT_TRUE(contains(s.message, "no transform into nowhere")) << s.message;
}

TEST(LayerStatus, ObstacleLayerNamesTheLateSource)
{
  ParamValue p = paramMap({{"observation_sources", S("front_scan rear")}});
  p.set("front_scan",
        paramMap({{"data_type", S("LaserScan")}, {"topic", S("/front/scan")}, {"expected_update_rate", D(0.5)}}));
  p.set("rear", paramMap({{"data_type", S("LaserScan")}}));
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(10, 10, 1.0, 0, 0);
  auto ctx = std::make_shared<FakeContext>(p);
  auto layer = add<ObstacleLayer>(lc, "obstacles", ctx);
  ctx->now_ns = 100'000'000;
  ASSERT_EQ(ctx->publishScan("/front/scan", makeScan(10, -1, 1, 1.0f), poseAt(5, 5, 0)), 1);
  ctx->now_ns = 400'000'000;
  lc.updateMap(5, 5, 0);
  LayerStatus s = layer->status();
  EXPECT_EQ(s.level, StatusLevel::Ok) << s.message;
  EXPECT_EQ(s.message, "2 source(s) current");
  EXPECT_TRUE(contains(s.value("source front_scan (/front/scan)"), "1 accepted, 0 rejected, last accepted 0.30 s ago"))
      << s.value("source front_scan (/front/scan)");
  EXPECT_TRUE(contains(s.value("source rear (rear)"), "never")) << s.value("source rear (rear)");
  ctx->now_ns = 1'000'000'000;  // 0.9 s since the last scan, 0.5 s expected
  lc.updateMap(5, 5, 0);
  s = layer->status();
  EXPECT_EQ(s.level, StatusLevel::Warn);
  EXPECT_TRUE(contains(s.message,
                       "source front_scan on /front/scan is late: 0.90 s without a reading (expected every "
                       "0.50 s)"))
      << s.message;
  EXPECT_FALSE(contains(s.message, "rear")) << s.message;  // unchecked: expected_update_rate 0
  // A refused scan (stamped 10 s ahead of the clock) is counted and its reason kept.
  LaserScanData bad = makeScan(10, -1, 1, 1.0f);
  bad.stamp_ns = ctx->now_ns + 10'000'000'000ull;
  ctx->publishScan("rear", bad, poseAt(5, 5, 0));
  s = layer->status();
  EXPECT_FALSE(s.value("source rear last rejection").empty());
  EXPECT_TRUE(contains(s.message, "source rear on rear: every reading rejected")) << s.message;
}

TEST(LayerStatus, RangeSensorLayerSaysWhenItHearsNothing)
{
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(10, 10, 1.0, 0, 0);
  auto ctx = std::make_shared<FakeContext>(
      paramMap({{"topics", ParamValue::makeList({S("/sonar")})}, {"no_readings_timeout", D(1.0)}}));
  auto layer = add<RangeSensorLayer>(lc, "range", ctx);
  lc.updateMap(0, 0, 0);
  LayerStatus s = layer->status();
  EXPECT_EQ(s.level, StatusLevel::Ok);
  EXPECT_EQ(s.message, "no reading yet on /sonar");
  ctx->now_ns = 2'000'000'000;
  lc.updateMap(0, 0, 0);
  s = layer->status();
  EXPECT_EQ(s.level, StatusLevel::Warn);
  EXPECT_TRUE(contains(s.message, "no range readings on /sonar")) << s.message;
  RangeData r;
  r.frame_id = "base_link";
  r.field_of_view = 0.17f;
  r.min_range = 0.1f;
  r.max_range = 5.0f;
  r.range = 2.0f;
  ASSERT_EQ(ctx->publishRange("/sonar", r, poseAt(2, 5, 0)), 1);
  lc.updateMap(0, 0, 0);
  s = layer->status();
  EXPECT_EQ(s.level, StatusLevel::Ok) << s.message;
  EXPECT_EQ(s.value("readings accepted"), "1");
}
