#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/kernels/simd_targets.hpp"
#include "costmap_layers/core/layers/static_layer.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;
using costmap_layers_test::GridKind;

namespace
{
OccupancyGridData makeMap(uint32_t w, uint32_t h, double res, double ox, double oy, int8_t fill = 0,
                          const std::string& frame = "map")
{
  OccupancyGridData m;
  m.frame_id = frame;
  m.width = w;
  m.height = h;
  m.resolution = res;
  m.origin_x = ox;
  m.origin_y = oy;
  m.data.assign(static_cast<std::size_t>(w) * h, fill);
  return m;
}

void setCell(OccupancyGridData& m, uint32_t x, uint32_t y, int8_t v)
{
  m.data[static_cast<std::size_t>(y) * m.width + x] = v;
}

/// Writes one value over the whole window, below the static layer.
class FillLayer : public Layer
{
public:
  uint8_t value = 0;
  unsigned x = 0, y = 0;  ///< only this cell
  void updateBounds(double, double, double, double*, double*, double*, double*) override {}
  void updateCosts(Costmap2D& master, int min_i, int min_j, int max_i, int max_j) override
  {
    if (int(x) >= min_i && int(x) < max_i && int(y) >= min_j && int(y) < max_j) master.setCost(x, y, value);
  }
};

struct Rig
{
  explicit Rig(ParamValue params = ParamValue::makeMap(), bool rolling = false, bool track_unknown = false,
               std::string global = "map")
      : lc(global, rolling, track_unknown)
  {
    lc.resizeMap(10, 10, 1.0, 0.0, 0.0);
    ctx = std::make_shared<FakeContext>(std::move(params), global);
    layer = std::make_shared<StaticLayer>();
    layer->initialize(&lc, "static_layer", ctx);
    ctx->bind(*layer);
    lc.addPlugin(layer);
  }
  void publish(const OccupancyGridData& m) { ctx->publishGrid(GridKind::Map, m); }
  void update(double x = 0, double y = 0) { lc.updateMap(x, y, 0); }
  uint8_t at(unsigned x, unsigned y) const { return lc.getCostmap().getCost(x, y); }

  LayeredCostmap lc;
  std::shared_ptr<FakeContext> ctx;
  std::shared_ptr<StaticLayer> layer;
};

ParamValue params(std::initializer_list<std::pair<const char*, ParamValue>> items)
{
  ParamValue p = ParamValue::makeMap();
  for (const auto& it : items)
    p.set(it.first, it.second);
  return p;
}
}  // namespace

TEST(StaticConfig, DefaultsFollowCostmap2d)
{
  const ParamValue empty = ParamValue::makeMap();
  for (bool track : {false, true})
  {
    const StaticConfig c = parseStaticConfig(ParamReader(empty, "s"), track);
    EXPECT_EQ(c.map_topic, "map");
    EXPECT_FALSE(c.first_map_only);
    EXPECT_FALSE(c.subscribe_to_updates);
    EXPECT_EQ(c.track_unknown_space, track);
    EXPECT_FALSE(c.use_maximum);
    EXPECT_EQ(c.lethal_cost_threshold, 100);
    EXPECT_EQ(c.unknown_cost_value, -1);
    EXPECT_TRUE(c.trinary_costmap);
  }
  const ParamValue clamp = params({{"lethal_cost_threshold", ParamValue::makeInt(150)}});
  EXPECT_EQ(parseStaticConfig(ParamReader(clamp, "s"), true).lethal_cost_threshold, 100);
  EXPECT_THROW(parseStaticConfig(ParamReader(params({{"map_topic", ParamValue::makeInt(3)}}), "s"), true),
               std::invalid_argument);
  EXPECT_THROW(parseStaticConfig(ParamReader(params({{"unknown_cost_value", ParamValue::makeInt(300)}}), "s"), true),
               std::invalid_argument);
  EXPECT_THROW(parseStaticConfig(ParamReader(params({{"use_maximum", ParamValue::makeString("x")}}), "s"), true),
               std::invalid_argument);
}

TEST(StaticLayer, InterpretsValuesAsCostmap2d)
{
  StaticConfig c;
  EXPECT_EQ(interpretStaticValue(-1, c), NO_INFORMATION);
  EXPECT_EQ(interpretStaticValue(100, c), LETHAL_OBSTACLE);
  EXPECT_EQ(interpretStaticValue(99, c), FREE_SPACE);
  EXPECT_EQ(interpretStaticValue(0, c), FREE_SPACE);
  c.track_unknown_space = false;
  EXPECT_EQ(interpretStaticValue(-1, c), FREE_SPACE);
  c.track_unknown_space = true;
  c.trinary_costmap = false;
  EXPECT_EQ(interpretStaticValue(50, c), static_cast<uint8_t>(0.5 * 254));
  EXPECT_EQ(interpretStaticValue(1, c), static_cast<uint8_t>(0.01 * 254));
  c.lethal_cost_threshold = 60;
  EXPECT_EQ(interpretStaticValue(60, c), LETHAL_OBSTACLE);
  EXPECT_EQ(interpretStaticValue(30, c), static_cast<uint8_t>(0.5 * 254));
  // Another unknown value: -1 is then a byte of 255, above the threshold.
  c.unknown_cost_value = 50;
  EXPECT_EQ(interpretStaticValue(50, c), NO_INFORMATION);
  EXPECT_EQ(interpretStaticValue(-1, c), LETHAL_OBSTACLE);
  c.unknown_cost_value = 255;  // the same byte as -1
  EXPECT_EQ(interpretStaticValue(-1, c), NO_INFORMATION);
  c.lethal_cost_threshold = 0;
  c.unknown_cost_value = -1;
  EXPECT_EQ(interpretStaticValue(0, c), LETHAL_OBSTACLE);
}

TEST(StaticLayer, SubscribesToMapTopic)
{
  Rig rig(params({{"map_topic", ParamValue::makeString("/other_map")}}));
  ASSERT_EQ(rig.ctx->grid_subs.size(), 1u);
  EXPECT_EQ(rig.ctx->grid_subs[0].topic, "/other_map");
  EXPECT_EQ(rig.ctx->grid_subs[0].kind, GridKind::Map);
  EXPECT_EQ(rig.layer->config().map_topic, "/other_map");
}

TEST(StaticLayer, ResizesMasterToMapAndDrawsIt)
{
  Rig rig(ParamValue::makeMap(), false, true);
  EXPECT_FALSE(rig.layer->isCurrent());
  OccupancyGridData m = makeMap(20, 15, 0.5, -3.0, 2.0);
  setCell(m, 3, 4, 100);
  setCell(m, 5, 6, -1);
  setCell(m, 7, 8, 50);
  rig.publish(m);
  EXPECT_FALSE(rig.layer->mapReceived());  // processed on the update thread
  rig.update();
  EXPECT_TRUE(rig.layer->mapReceived());
  EXPECT_TRUE(rig.layer->isCurrent());
  const Costmap2D& c = rig.lc.getCostmap();
  EXPECT_EQ(c.getSizeInCellsX(), 20u);
  EXPECT_EQ(c.getSizeInCellsY(), 15u);
  EXPECT_DOUBLE_EQ(c.getResolution(), 0.5);
  EXPECT_DOUBLE_EQ(c.getOriginX(), -3.0);
  EXPECT_DOUBLE_EQ(c.getOriginY(), 2.0);
  EXPECT_TRUE(rig.lc.isSizeLocked());
  EXPECT_EQ(rig.at(3, 4), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.at(5, 6), NO_INFORMATION);
  EXPECT_EQ(rig.at(7, 8), FREE_SPACE);
  EXPECT_EQ(rig.at(0, 0), FREE_SPACE);
  const CellWindow w = rig.lc.getUpdatedBounds();
  EXPECT_EQ(w.x0, 0);
  EXPECT_EQ(w.y0, 0);
  EXPECT_EQ(w.xn, 20);
  EXPECT_EQ(w.yn, 15);
  // Nothing new: nothing to update.
  rig.update();
  EXPECT_TRUE(rig.lc.getUpdatedBounds().empty());
}

TEST(StaticLayer, TrackUnknownSpaceAndTrinaryAndThreshold)
{
  OccupancyGridData m = makeMap(10, 10, 1.0, 0, 0);
  setCell(m, 1, 1, -1);
  setCell(m, 2, 2, 70);
  setCell(m, 3, 3, 40);
  {
    Rig rig(params({{"track_unknown_space", ParamValue::makeBool(false)}}), false, true);
    rig.publish(m);
    rig.update();
    EXPECT_EQ(rig.at(1, 1), FREE_SPACE);
    EXPECT_EQ(rig.at(2, 2), FREE_SPACE);
  }
  {
    Rig rig(
        params({{"lethal_cost_threshold", ParamValue::makeInt(65)}, {"trinary_costmap", ParamValue::makeBool(false)}}),
        false, false);
    EXPECT_FALSE(rig.layer->config().track_unknown_space);  // the costmap's
    rig.publish(m);
    rig.update();
    EXPECT_EQ(rig.at(1, 1), FREE_SPACE);
    EXPECT_EQ(rig.at(2, 2), LETHAL_OBSTACLE);
    EXPECT_EQ(rig.at(3, 3), static_cast<uint8_t>(40.0 / 65 * 254));
  }
  {
    Rig rig(params({{"unknown_cost_value", ParamValue::makeInt(40)}}), false, true);
    rig.publish(m);
    rig.update();
    EXPECT_EQ(rig.at(3, 3), NO_INFORMATION);
    EXPECT_EQ(rig.at(1, 1), LETHAL_OBSTACLE);
  }
}

TEST(StaticLayer, UseMaximum)
{
  for (bool use_max : {false, true})
  {
    LayeredCostmap lc("map", false, false);
    lc.resizeMap(10, 10, 1.0, 0, 0);
    auto below = std::make_shared<FillLayer>();
    below->value = 200;
    below->x = 4;
    below->y = 4;
    below->initialize(&lc, "below", std::make_shared<FakeContext>());
    lc.addPlugin(below);
    auto ctx = std::make_shared<FakeContext>(params({{"use_maximum", ParamValue::makeBool(use_max)}}));
    auto layer = std::make_shared<StaticLayer>();
    layer->initialize(&lc, "static_layer", ctx);
    ctx->bind(*layer);
    lc.addPlugin(layer);
    OccupancyGridData m = makeMap(10, 10, 1.0, 0, 0);
    setCell(m, 5, 5, 100);
    ctx->publishGrid(GridKind::Map, m);
    lc.updateMap(0, 0, 0);
    EXPECT_EQ(lc.getCostmap().getCost(4, 4), use_max ? 200 : FREE_SPACE);
    EXPECT_EQ(lc.getCostmap().getCost(5, 5), LETHAL_OBSTACLE);
  }
}

// The host skips resetting the window when the first layer is a static layer that overwrites it all
// (costmap_2d's true overwrite): the master then holds exactly the map, whatever it held before; when
// the static layer does not overwrite (use_maximum, disabled, no map yet, not first), the window is
// reset to the default value first, as always.
TEST(StaticLayer, FirstOverwritingLayerMakesTheResetNeedless)
{
  for (int variant = 0; variant < 4; ++variant)
  {
    const bool use_max = variant == 1, disabled = variant == 2, no_map = variant == 3;
    Rig rig(params({{"use_maximum", ParamValue::makeBool(use_max)}}), false, false);
    OccupancyGridData m = makeMap(10, 10, 1.0, 0.0, 0.0);
    setCell(m, 2, 3, 100);
    if (!no_map) rig.publish(m);
    rig.update();
    if (disabled) rig.layer->setEnabled(false);
    // Scribble over the master, then ask for a whole redraw.
    Costmap2D& master = rig.lc.getCostmap();
    for (unsigned y = 0; y < master.getSizeInCellsY(); ++y)
      for (unsigned x = 0; x < master.getSizeInCellsX(); ++x)
        master.setCost(x, y, 77);
    rig.lc.requestFullUpdate();
    rig.update();
    const std::string what = "variant " + std::to_string(variant);
    ASSERT_FALSE(rig.lc.getUpdatedBounds().empty()) << what;
    for (unsigned y = 0; y < 10; ++y)
      for (unsigned x = 0; x < 10; ++x)
      {
        const uint8_t expected = (!no_map && !disabled && x == 2 && y == 3) ? LETHAL_OBSTACLE : FREE_SPACE;
        ASSERT_EQ(rig.at(x, y), expected) << what << " cell " << x << "," << y;
      }
    const bool overwrites = rig.layer->overwritesWindow(master, 0, 0, 10, 10);
    EXPECT_EQ(overwrites, variant == 0) << what;
  }
}

TEST(StaticLayer, NewMapReplacesOldOneAndFirstMapOnly)
{
  for (bool first_only : {false, true})
  {
    Rig rig(params({{"first_map_only", ParamValue::makeBool(first_only)}}));
    OccupancyGridData a = makeMap(10, 10, 1.0, 0, 0);
    setCell(a, 1, 1, 100);
    rig.publish(a);
    rig.update();
    OccupancyGridData b = makeMap(12, 8, 1.0, 1.0, 0);
    setCell(b, 2, 2, 100);
    rig.publish(b);
    rig.update();
    if (first_only)
    {
      EXPECT_EQ(rig.lc.getCostmap().getSizeInCellsX(), 10u);
      EXPECT_EQ(rig.at(1, 1), LETHAL_OBSTACLE);
      EXPECT_EQ(rig.at(2, 2), FREE_SPACE);
    }
    else
    {
      EXPECT_EQ(rig.lc.getCostmap().getSizeInCellsX(), 12u);
      EXPECT_EQ(rig.lc.getCostmap().getSizeInCellsY(), 8u);
      EXPECT_DOUBLE_EQ(rig.lc.getCostmap().getOriginX(), 1.0);
      EXPECT_EQ(rig.at(1, 1), FREE_SPACE);
      EXPECT_EQ(rig.at(2, 2), LETHAL_OBSTACLE);
    }
  }
}

TEST(StaticLayer, SameGeometryMapUpdatesInPlace)
{
  Rig rig;
  OccupancyGridData a = makeMap(10, 10, 1.0, 0, 0);
  rig.publish(a);
  rig.update();
  setCell(a, 6, 7, 100);
  rig.publish(a);
  rig.update();
  EXPECT_FALSE(rig.lc.isSizeLocked());  // the master already had the map's geometry: never resized
  EXPECT_EQ(rig.at(6, 7), LETHAL_OBSTACLE);
}

TEST(StaticLayer, RejectsMalformedMapsAndKeepsThePrevious)
{
  Rig rig;
  OccupancyGridData good = makeMap(10, 10, 1.0, 0, 0);
  setCell(good, 2, 3, 100);
  rig.publish(good);
  rig.update();

  std::vector<OccupancyGridData> bad;
  OccupancyGridData wrong_size = makeMap(10, 10, 1.0, 0, 0);
  wrong_size.data.pop_back();
  bad.push_back(wrong_size);
  OccupancyGridData zero_res = makeMap(10, 10, 0.0, 0, 0);
  bad.push_back(zero_res);
  OccupancyGridData nan_res = makeMap(10, 10, std::numeric_limits<double>::quiet_NaN(), 0, 0);
  bad.push_back(nan_res);
  OccupancyGridData absurd = makeMap(1, 1, 1.0, 0, 0);
  absurd.width = 100000;
  absurd.height = 100000;
  bad.push_back(absurd);
  OccupancyGridData empty = makeMap(0, 0, 1.0, 0, 0);
  bad.push_back(empty);

  for (const auto& m : bad)
  {
    const std::size_t before = rig.ctx->reports.size();
    EXPECT_FALSE(rig.layer->setMap(std::make_shared<const OccupancyGridData>(m)).empty());
    rig.publish(m);
    ASSERT_EQ(rig.ctx->reports.size(), before + 2);
    EXPECT_EQ(rig.ctx->reports.back().severity, Severity::Error);
    EXPECT_NE(rig.ctx->reports.back().message.find("rejected, keeping the previous one"), std::string::npos);
    rig.layer->reset();
    rig.update();
    EXPECT_EQ(rig.lc.getCostmap().getSizeInCellsX(), 10u);
    EXPECT_EQ(rig.at(2, 3), LETHAL_OBSTACLE);
  }
  EXPECT_GE(rig.ctx->countReports("data has 99 values"), 1);
  EXPECT_GE(rig.ctx->countReports("resolution"), 2);
  EXPECT_GE(rig.ctx->countReports("exceeds the limit"), 1);
}

TEST(StaticLayer, PartialUpdates)
{
  Rig off;
  off.publish(makeMap(10, 10, 1.0, 0, 0));
  EXPECT_NE(off.layer->applyUpdate(0, 0, 1, 1, {100}).find("subscribe_to_updates"), std::string::npos);

  Rig rig(params({{"subscribe_to_updates", ParamValue::makeBool(true)}}), false, true);
  EXPECT_NE(rig.layer->applyUpdate(0, 0, 1, 1, {100}).find("no map"), std::string::npos);
  rig.publish(makeMap(10, 10, 1.0, 0, 0));
  rig.update();
  EXPECT_TRUE(rig.layer->applyUpdate(2, 3, 3, 2, {100, 0, -1, 0, 100, 0}).empty());
  EXPECT_TRUE(rig.layer->applyUpdate(8, 8, 1, 1, {100}).empty());
  EXPECT_FALSE(rig.layer->applyUpdate(8, 8, 3, 1, {0, 0, 0}).empty());  // leaves the map
  EXPECT_FALSE(rig.layer->applyUpdate(0, 0, 2, 2, {0, 0, 0}).empty());  // wrong data size
  rig.update();
  EXPECT_EQ(rig.at(2, 3), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.at(4, 3), NO_INFORMATION);
  EXPECT_EQ(rig.at(3, 4), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.at(8, 8), LETHAL_OBSTACLE);
  // Only the union of the updated rectangles is redrawn.
  const CellWindow w = rig.lc.getUpdatedBounds();
  EXPECT_EQ(w.x0, 2);
  EXPECT_EQ(w.y0, 3);
  EXPECT_EQ(w.xn, 9);
  EXPECT_EQ(w.yn, 9);
  // An update queued before a new map is dropped with it.
  EXPECT_TRUE(rig.layer->applyUpdate(0, 0, 1, 1, {100}).empty());
  rig.publish(makeMap(10, 10, 1.0, 0, 0));
  rig.update();
  EXPECT_EQ(rig.at(0, 0), FREE_SPACE);
  EXPECT_EQ(rig.at(2, 3), FREE_SPACE);
}

TEST(StaticLayer, RollingWindowSamplesMapThroughTransform)
{
  Rig rig(ParamValue::makeMap(), true, true, "odom");
  rig.lc.resizeMap(20, 20, 0.5, 0, 0);
  // The map frame sits 3 m along x and rotated by 90 degrees relative to odom.
  // (Offsets keep cell centres away from map cell borders, where rounding could go either way.)
  Transform2D odom_from_map{3.07, 0.0, M_PI / 2};
  rig.ctx->transforms[{"odom", "map"}] = odom_from_map;
  rig.ctx->transforms[{"map", "odom"}] = odom_from_map.inverse();
  OccupancyGridData m = makeMap(40, 40, 0.25, -5.1, -4.91, 0, "map");
  for (uint32_t y = 0; y < 40; ++y)
    for (uint32_t x = 0; x < 40; ++x)
      setCell(m, x, y, static_cast<int8_t>((x * 7 + y * 3) % 5 == 0 ? 100 : 0));
  setCell(m, 0, 0, -1);
  rig.publish(m);
  rig.update(2.0, 1.0);  // the window is [-3, 7) x [-4, 6) in odom
  const Costmap2D& c = rig.lc.getCostmap();
  EXPECT_EQ(c.getSizeInCellsX(), 20u);  // never resized
  const Transform2D map_from_odom = odom_from_map.inverse();
  int inside = 0;
  for (unsigned j = 0; j < 20; ++j)
    for (unsigned i = 0; i < 20; ++i)
    {
      double wx, wy, mx, my;
      c.mapToWorld(i, j, wx, wy);
      map_from_odom.apply(wx, wy, mx, my);
      const double gx = (mx + 5.1) / 0.25, gy = (my + 4.91) / 0.25;
      if (gx < 0 || gy < 0 || gx >= 40 || gy >= 40)
      {
        EXPECT_EQ(c.getCost(i, j), NO_INFORMATION) << i << "," << j;
        continue;
      }
      ++inside;
      const int8_t v = m.data[unsigned(gy) * 40 + unsigned(gx)];
      EXPECT_EQ(c.getCost(i, j), v == 100 ? LETHAL_OBSTACLE : (v == -1 ? NO_INFORMATION : FREE_SPACE)) << i << "," << j;
    }
  EXPECT_GT(inside, 100);
  // Without the transform: reported, nothing drawn.
  rig.ctx->transforms.clear();
  const std::size_t before = rig.ctx->reports.size();
  rig.update(2.5, 1.0);
  EXPECT_GT(rig.ctx->reports.size(), before);
  EXPECT_EQ(rig.ctx->reports.back().severity, Severity::Error);
}

TEST(StaticLayer, MapsFromAnotherThread)
{
  Rig rig;
  std::atomic<bool> stop{false};
  std::atomic<int> published{0};
  std::thread publisher(
      [&]
      {
        int k = 0;
        while (!stop || k < 50)
        {
          OccupancyGridData m = makeMap(10, 10, 1.0, 0, 0);
          setCell(m, static_cast<uint32_t>(k % 10), 0, 100);
          rig.publish(m);
          published = ++k;
        }
      });
  for (int i = 0; i < 200 || published < 50; ++i)
    rig.update();
  stop = true;
  publisher.join();
  rig.update();
  int lethal = 0;
  for (unsigned x = 0; x < 10; ++x)
    lethal += rig.at(x, 0) == LETHAL_OBSTACLE;
  EXPECT_EQ(lethal, 1);
}

TEST(StaticLayer, OutOfOrderMapsAndUpdatesAreDropped)
{
  Rig rig(params({{"subscribe_to_updates", ParamValue::makeBool(true)}}));
  rig.ctx->now_ns = 100'000'000'000;
  OccupancyGridData newer = makeMap(10, 10, 1.0, 0, 0);
  setCell(newer, 2, 3, 100);
  newer.stamp_ns = 50'000'000'000;
  rig.publish(newer);
  rig.update();
  ASSERT_EQ(rig.at(2, 3), LETHAL_OBSTACLE);

  // An all-free map stamped earlier than the one in force: dropped, the wall stays.
  OccupancyGridData older = makeMap(10, 10, 1.0, 0, 0);
  older.stamp_ns = 40'000'000'000;
  rig.publish(older);
  rig.update();
  EXPECT_EQ(rig.at(2, 3), LETHAL_OBSTACLE);
  ASSERT_EQ(rig.ctx->reports.size(), 1u);
  EXPECT_EQ(rig.ctx->reports[0].key, "map/header.stamp");
  EXPECT_NE(rig.ctx->reports[0].message.find("header.stamp 40.000 s is older than the map in force (stamped 50.000 s)"),
            std::string::npos)
      << rig.ctx->reports[0].message;

  // An update made for an older map would be drawn on the wrong one: dropped.
  EXPECT_NE(rig.layer->applyUpdate(2, 3, 1, 1, {0}, 40'000'000'000).find("header.stamp 40.000 s"), std::string::npos);
  // Updates stamped with or after the map, or unstamped, apply.
  EXPECT_EQ(rig.layer->applyUpdate(4, 4, 1, 1, {100}, 50'000'000'000), "");
  EXPECT_EQ(rig.layer->applyUpdate(5, 5, 1, 1, {100}, 0), "");
  rig.update();
  EXPECT_EQ(rig.at(2, 3), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.at(4, 4), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.at(5, 5), LETHAL_OBSTACLE);

  // The clock went back below the map's stamp (a restarted simulation): older stamps are accepted.
  rig.ctx->now_ns = 10'000'000'000;
  older.stamp_ns = 5'000'000'000;
  rig.publish(older);
  rig.update();
  EXPECT_EQ(rig.at(2, 3), FREE_SPACE);
}

// A map topic that never publishes left an all-free costmap and said nothing. Now each update without
// a map says what it waits for (the adapter throttles it) once the start-up grace (2 s from the first
// update: a latched map comes moments after start) is over, and the layer is not current.
TEST(StaticLayer, WaitingForTheMapIsReported)
{
  Rig r;
  r.ctx->now_ns = 10'000'000'000;
  r.update();
  r.ctx->now_ns += 1'999'999'999;
  r.update();
  EXPECT_EQ(r.ctx->countReports("waiting"), 0);  // within the grace: a start-up that works says nothing
  r.ctx->now_ns += 1;
  r.update();
  r.update();
  EXPECT_EQ(r.ctx->countReports("static_layer: waiting for the map on map (nothing received yet)"), 2);
  for (const auto& rep : r.ctx->reports)
  {
    EXPECT_EQ(rep.key, "waiting");
    EXPECT_EQ(rep.severity, Severity::Warn);
  }
  EXPECT_FALSE(r.layer->isCurrent());
  EXPECT_FALSE(r.lc.isCurrent());
  r.publish(makeMap(3, 3, 1.0, 0, 0));
  r.ctx->reports.clear();
  r.update();
  EXPECT_EQ(r.ctx->countReports("waiting"), 0);
  EXPECT_TRUE(r.layer->isCurrent());
}

// A trinary map is converted by compares, one vector at a time (on every SIMD target): every byte
// value, at every position of a vector, gives the costmap_2d rule's cost, stated here by hand:
// the unknown value -> 255 (tracking) or 0, a value >= the threshold (as unsigned bytes) -> 254, else 0.
TEST(StaticLayer, TrinaryConversionOfEveryByteOnEveryTarget)
{
  for (const std::string& target : simdTargets())
    for (const int threshold : {0, 1, 65, 100})
      for (const int unknown : {-1, 0, 50, 200})
        for (const bool track : {false, true})
        {
          SCOPED_TRACE(target + " threshold " + std::to_string(threshold) + " unknown " + std::to_string(unknown) +
                       (track ? " tracked" : ""));
          ASSERT_TRUE(setSimdTarget(target));
          Rig rig(params({{"lethal_cost_threshold", ParamValue::makeInt(threshold)},
                          {"unknown_cost_value", ParamValue::makeInt(unknown)},
                          {"track_unknown_space", ParamValue::makeBool(track)}}),
                  false, track);
          // 37 x 29 cells (not a multiple of any vector), byte values cycling with an odd step.
          OccupancyGridData m = makeMap(37, 29, 1.0, 0, 0);
          for (std::size_t k = 0; k < m.data.size(); ++k)
            m.data[k] = static_cast<int8_t>(static_cast<uint8_t>(k * 7 % 256));
          rig.publish(m);
          rig.update();
          for (uint32_t y = 0; y < 29; ++y)
            for (uint32_t x = 0; x < 37; ++x)
            {
              const uint8_t v = static_cast<uint8_t>(m.data[static_cast<std::size_t>(y) * 37 + x]);
              const uint8_t expected =
                  v == static_cast<uint8_t>(unknown) ? (track ? 255 : 0) : (v >= threshold ? 254 : 0);
              ASSERT_EQ(rig.at(x, y), expected) << "value " << int{v};
            }
        }
  setSimdTarget("");
}

TEST(StaticLayer, RollingWindowSamplesAnAxisAlignedMapAtAnyResolution)
{
  // The map in the costmap's own frame, no rotation: the sampler's offset path (same resolution) and its
  // row/column tables (another resolution). Expected: the map cell under each master cell's centre,
  // computed here cell by cell; the offsets keep centres off map cell borders.
  for (const double map_res : {0.5, 0.25, 1.5})
  {
    Rig rig(ParamValue::makeMap(), true, true, "odom");
    rig.lc.resizeMap(20, 20, 0.5, 0, 0);
    const uint32_t w = static_cast<uint32_t>(std::lround(12.0 / map_res));
    OccupancyGridData m = makeMap(w, w, map_res, -4.1, -2.9, 0, "odom");
    for (uint32_t y = 0; y < w; ++y)
      for (uint32_t x = 0; x < w; ++x)
        setCell(m, x, y, static_cast<int8_t>((x * 5 + y * 2) % 3 == 0 ? 100 : ((x + y) % 7 == 0 ? -1 : 0)));
    rig.publish(m);
    rig.update(1.0, 0.5);  // the window is [-4, 6) x [-4.5, 5.5)
    const Costmap2D& c = rig.lc.getCostmap();
    int inside = 0;
    for (unsigned j = 0; j < 20; ++j)
      for (unsigned i = 0; i < 20; ++i)
      {
        double wx, wy;
        c.mapToWorld(i, j, wx, wy);
        const double gx = (wx + 4.1) / map_res, gy = (wy + 2.9) / map_res;
        if (gx < 0 || gy < 0 || gx >= w || gy >= w)
        {
          EXPECT_EQ(c.getCost(i, j), NO_INFORMATION) << map_res << ": " << i << "," << j;
          continue;
        }
        ++inside;
        const int8_t v = m.data[unsigned(gy) * w + unsigned(gx)];
        EXPECT_EQ(c.getCost(i, j), v == 100 ? LETHAL_OBSTACLE : (v == -1 ? NO_INFORMATION : FREE_SPACE))
            << map_res << ": " << i << "," << j;
      }
    EXPECT_GT(inside, 200) << map_res;
  }
}

// Nav2's StaticLayer footprint_clearing_enabled (static_layer.cpp: the own cells under the footprint set
// FREE_SPACE before the copy into the master, restored after it when restore_cleared_footprint, the
// default): a robot that starts inside a mapped obstacle sees free cells under itself; the map itself
// stays; where the robot was is the map's again once it has moved.
TEST(StaticLayer, FootprintClearingAsNav2)
{
  auto run = [](bool enabled, bool restore, bool use_max)
  {
    auto rig = std::make_unique<Rig>(params({{"footprint_clearing_enabled", ParamValue::makeBool(enabled)},
                                             {"restore_cleared_footprint", ParamValue::makeBool(restore)},
                                             {"use_maximum", ParamValue::makeBool(use_max)}}));
    // A 1.2 m square robot (cells 1 m): at (3.5, 3.5) it covers cells 2..4 in x and y.
    rig->lc.setFootprint({{-0.6, -0.6}, {0.6, -0.6}, {0.6, 0.6}, {-0.6, 0.6}});
    OccupancyGridData m = makeMap(10, 10, 1.0, 0, 0);
    for (uint32_t y = 0; y < 10; ++y)
      for (uint32_t x = 0; x < 10; ++x)
        if (x <= 5 && y <= 5) setCell(m, x, y, 100);  // a lethal block around the robot's start
    rig->publish(m);
    rig->lc.updateMap(3.5, 3.5, 0);
    return rig;
  };
  {
    const auto rig = run(true, true, false);
    for (unsigned y = 0; y < 10; ++y)
      for (unsigned x = 0; x < 10; ++x)
      {
        const bool under = x >= 2 && x <= 4 && y >= 2 && y <= 4;
        const uint8_t map_cost = x <= 5 && y <= 5 ? LETHAL_OBSTACLE : FREE_SPACE;
        EXPECT_EQ(rig->at(x, y), under ? FREE_SPACE : map_cost) << x << "," << y;
        EXPECT_EQ(rig->layer->costmap().getCost(x, y), map_cost) << x << "," << y;  // restored
      }
    // The robot moves to (7.5, 7.5): its old cells are the map's again, the new ones (free) stay free.
    rig->lc.updateMap(7.5, 7.5, 0);
    EXPECT_EQ(rig->at(3, 3), LETHAL_OBSTACLE);
    EXPECT_EQ(rig->at(2, 4), LETHAL_OBSTACLE);
    EXPECT_EQ(rig->at(5, 5), LETHAL_OBSTACLE);  // the new footprint covers cells 6..8 only
    EXPECT_EQ(rig->at(7, 7), FREE_SPACE);
  }
  {
    // restore_cleared_footprint false: the map's cells under the robot stay free after it moves on.
    const auto rig = run(true, false, false);
    EXPECT_EQ(rig->layer->costmap().getCost(3, 3), FREE_SPACE);
    rig->lc.updateMap(7.5, 7.5, 0);
    EXPECT_EQ(rig->at(3, 3), FREE_SPACE);
    EXPECT_EQ(rig->at(1, 1), LETHAL_OBSTACLE);
  }
  {
    // Off (the default, as Nav2's): the map under the robot.
    const auto rig = run(false, true, false);
    EXPECT_EQ(rig->at(3, 3), LETHAL_OBSTACLE);
    EXPECT_EQ(rig->layer->config().footprint_clearing_enabled, false);
  }
  {
    // use_maximum: the static layer gives FREE_SPACE there, so the master keeps what it held (its
    // default here), the lethal block elsewhere.
    const auto rig = run(true, true, true);
    EXPECT_EQ(rig->at(3, 3), FREE_SPACE);
    EXPECT_EQ(rig->at(1, 1), LETHAL_OBSTACLE);
  }
  {
    // A vertex off the map: nothing is cleared (costmap_2d's and Nav2's polygon fill refuse it too).
    auto rig = run(true, true, false);
    rig->lc.updateMap(0.3, 3.5, 0);
    EXPECT_EQ(rig->at(0, 3), LETHAL_OBSTACLE);
    EXPECT_EQ(rig->at(1, 3), LETHAL_OBSTACLE);
  }
}

// In a rolling window the footprint (in the costmap's frame) clears the map's cells it lies on, through
// the transform into the map's frame.
TEST(StaticLayer, FootprintClearingInARollingWindowGoesThroughTheTransform)
{
  Rig rig(params({{"footprint_clearing_enabled", ParamValue::makeBool(true)}}), true, true, "odom");
  rig.lc.resizeMap(10, 10, 1.0, 0, 0);
  rig.lc.setFootprint({{-0.4, -0.4}, {0.4, -0.4}, {0.4, 0.4}, {-0.4, 0.4}});
  Transform2D odom_from_map{2.0, 1.0, 0.0};  // the map's origin lies at (2, 1) in odom
  rig.ctx->transforms[{"odom", "map"}] = odom_from_map;
  rig.ctx->transforms[{"map", "odom"}] = odom_from_map.inverse();
  rig.publish(makeMap(20, 20, 1.0, 0, 0, 100, "map"));  // all lethal
  rig.update(5.5, 5.5);  // the window [0, 10) in odom (whole cells from its origin); the robot: map cell (3, 4)
  const Costmap2D& c = rig.lc.getCostmap();
  unsigned i, j;
  ASSERT_TRUE(c.worldToMap(5.5, 5.5, i, j));
  EXPECT_EQ(c.getCost(i, j), FREE_SPACE);
  int free_cells = 0;
  for (unsigned y = 0; y < 10; ++y)
    for (unsigned x = 0; x < 10; ++x)
      free_cells += c.getCost(x, y) == FREE_SPACE;
  EXPECT_EQ(free_cells, 1);                                        // the 0.8 m square lies inside the map cell (3, 4)
  EXPECT_EQ(rig.layer->costmap().getCost(3, 4), LETHAL_OBSTACLE);  // restored
}
