#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "beam_reference.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/core/layers/obstacle_layer.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/layers/static_layer.hpp"
#include "fake_context.hpp"
#include "sensor_test_helpers.hpp"
#include "ten_by_ten.hpp"

using namespace costmap_layers;
using namespace costmap_layers_test;

namespace
{
constexpr double MAX_Z = 1.0;

/// One cloud source "cloud" with generous ranges (costmap_2d's test helper uses 100 m).
ParamValue obstacleParams(std::initializer_list<std::pair<const char*, ParamValue>> layer_extra = {},
                          std::initializer_list<std::pair<const char*, ParamValue>> source_extra = {})
{
  ParamValue src = paramMap({{"data_type", S("PointCloud2")},
                             {"marking", B(true)},
                             {"clearing", B(true)},
                             {"obstacle_max_range", D(100.0)},
                             {"raytrace_max_range", D(100.0)}});
  for (const auto& it : source_extra)
    src.set(it.first, it.second);
  ParamValue p = paramMap({{"observation_sources", S("cloud")}});
  p.set("cloud", src);
  for (const auto& it : layer_extra)
    p.set(it.first, it.second);
  return p;
}

int count(const Costmap2D& c, uint8_t v)
{
  int n = 0;
  for (std::size_t k = 0; k < c.cellCount(); ++k)
    n += c.data()[k] == v;
  return n;
}

struct Rig
{
  Rig(ParamValue params, bool with_static, bool track_unknown = false, bool rolling = false, unsigned size = 10,
      double res = 1.0, double ox = 0.0, double oy = 0.0)
      : lc("map", rolling, track_unknown)
  {
    lc.resizeMap(size, size, res, ox, oy);
    if (with_static)
    {
      static_ctx = std::make_shared<FakeContext>(ParamValue::makeMap());
      static_layer = std::make_shared<StaticLayer>();
      static_layer->initialize(&lc, "static_layer", static_ctx);
      static_ctx->bind(*static_layer);
      lc.addPlugin(static_layer);
      static_ctx->publishGrid(GridKind::Map, tenByTen());
    }
    ctx = std::make_shared<FakeContext>(std::move(params));
    layer = std::make_shared<ObstacleLayer>();
    layer->initialize(&lc, "obstacles", ctx);
    ctx->bind(*layer);
    lc.addPlugin(layer);
  }
  /// Publishes points given in the global frame, seen from a sensor at pose (translation only).
  void cloud(const std::vector<XYZ>& pts, const SensorPose& pose, uint64_t stamp = 0)
  {
    std::vector<XYZ> local;
    for (const XYZ& p : pts)
      local.push_back({p.x - pose.origin_x, p.y - pose.origin_y, p.z - pose.origin_z});
    ASSERT_EQ(ctx->publishCloud("cloud", makeCloud(local, false, false, stamp), pose), 1);
  }
  void update(double x = 0, double y = 0, double yaw = 0) { lc.updateMap(x, y, yaw); }
  const Costmap2D& master() const { return lc.getCostmap(); }

  LayeredCostmap lc;
  std::shared_ptr<FakeContext> static_ctx, ctx;
  std::shared_ptr<StaticLayer> static_layer;
  std::shared_ptr<ObstacleLayer> layer;
};
}  // namespace

TEST(ObstacleConfig, DefaultsAndSources)
{
  const ObstacleConfig none = parseObstacleConfig(ParamReader(ParamValue::makeMap(), "o"), true);
  EXPECT_TRUE(none.footprint_clearing_enabled);
  EXPECT_DOUBLE_EQ(none.max_obstacle_height, 2.0);
  EXPECT_EQ(none.combination_method, 1);
  EXPECT_TRUE(none.track_unknown_space);
  EXPECT_TRUE(none.sources.empty());
  EXPECT_FALSE(parseObstacleConfig(ParamReader(ParamValue::makeMap(), "o"), false).track_unknown_space);

  ParamValue p = paramMap({{"observation_sources", S("  scan   cam ")}});
  p.set("scan", paramMap({{"data_type", S("LaserScan")},
                          {"obstacle_range", D(4.0)},
                          {"raytrace_range", D(5.0)},
                          {"sensor_frame", S("laser_link")},
                          {"inf_is_valid", B(true)}}));
  const ObstacleConfig c = parseObstacleConfig(ParamReader(p, "o"), false);
  ASSERT_EQ(c.sources.size(), 2u);
  const ObservationSourceConfig& scan = c.sources[0];
  EXPECT_EQ(scan.name, "scan");
  EXPECT_EQ(scan.topic, "scan");
  EXPECT_EQ(scan.sensor_frame, "laser_link");
  EXPECT_EQ(scan.data_type, SensorDataType::LaserScan);
  EXPECT_DOUBLE_EQ(scan.obstacle_max_range, 4.0);
  EXPECT_DOUBLE_EQ(scan.raytrace_max_range, 5.0);
  EXPECT_TRUE(scan.inf_is_valid);
  const ObservationSourceConfig& cam = c.sources[1];  // nothing set: every default
  EXPECT_EQ(cam.topic, "cam");
  EXPECT_EQ(cam.sensor_frame, "");
  EXPECT_EQ(cam.data_type, SensorDataType::PointCloud2);
  EXPECT_DOUBLE_EQ(cam.observation_persistence, 0.0);
  EXPECT_DOUBLE_EQ(cam.expected_update_rate, 0.0);
  EXPECT_DOUBLE_EQ(cam.min_obstacle_height, 0.0);
  EXPECT_DOUBLE_EQ(cam.max_obstacle_height, 2.0);
  EXPECT_FALSE(cam.inf_is_valid);
  EXPECT_TRUE(cam.marking);
  EXPECT_FALSE(cam.clearing);
  EXPECT_DOUBLE_EQ(cam.obstacle_min_range, 0.0);
  EXPECT_DOUBLE_EQ(cam.obstacle_max_range, 2.5);
  EXPECT_DOUBLE_EQ(cam.raytrace_min_range, 0.0);
  EXPECT_DOUBLE_EQ(cam.raytrace_max_range, 3.0);
  EXPECT_DOUBLE_EQ(cam.observation_keep_distance, 0.0);

  // The new names win over the old ones; a list of names works as well as a string.
  ParamValue q = paramMap({{"observation_sources", ParamValue::makeList({S("a")})}});
  q.set("a", paramMap({{"obstacle_range", D(4.0)}, {"obstacle_max_range", D(1.5)}}));
  EXPECT_DOUBLE_EQ(parseObstacleConfig(ParamReader(q, "o"), false).sources[0].obstacle_max_range, 1.5);
}

// sensor_msgs/PointCloud, the older type: costmap_2d reads it (its default), and so does this layer,
// on a port of its own kind that hands the points on as a PointCloud2 of x, y, z.
TEST(ObstacleConfig, ReadsTheOlderPointCloudType)
{
  ParamValue p = paramMap({{"observation_sources", S("a b")}});
  p.set("a", paramMap({{"data_type", S("PointCloud")}, {"topic", S("/old_cloud")}}));
  p.set("b", paramMap({{"data_type", S("PointCloud2")}, {"topic", S("/cloud")}}));
  const ObstacleConfig c = parseObstacleConfig(ParamReader(p, "o"), false);
  ASSERT_EQ(c.sources.size(), 2u);
  EXPECT_EQ(c.sources[0].data_type, SensorDataType::PointCloud);
  EXPECT_EQ(c.sources[1].data_type, SensorDataType::PointCloud2);
  EXPECT_STREQ(sensorDataTypeName(c.sources[0].data_type), "PointCloud");

  LayeredCostmap lc("map", false, false);
  lc.resizeMap(10, 10, 1.0, 0.0, 0.0);
  auto ctx = std::make_shared<FakeContext>(p);
  auto layer = std::make_shared<ObstacleLayer>();
  layer->initialize(&lc, "obstacles", ctx);
  ASSERT_EQ(layer->inputs().size(), 2u);
  EXPECT_EQ(layer->inputs()[0].kind, InputKind::PointCloud);
  EXPECT_EQ(layer->inputs()[0].topic, "/old_cloud");
  EXPECT_TRUE(static_cast<bool>(layer->inputs()[0].on_cloud));
  EXPECT_EQ(layer->inputs()[1].kind, InputKind::PointCloud2);
}

TEST(ObstacleConfig, RejectsBadValues)
{
  auto bad = [](ParamValue p) { EXPECT_THROW(parseObstacleConfig(ParamReader(p, "o"), false), std::invalid_argument); };
  bad(paramMap({{"combination_method", I(3)}}));
  bad(paramMap({{"combination_method", I(-1)}}));
  bad(paramMap({{"max_obstacle_height", S("high")}}));
  bad(paramMap({{"observation_sources", I(3)}}));
  bad(paramMap({{"observation_sources", S("a a")}}));
  bad(paramMap({{"observation_sources", S("a")}, {"a", S("not a map")}}));
  auto bad_source = [&](const char* key, ParamValue v)
  {
    ParamValue p = paramMap({{"observation_sources", S("a")}});
    p.set("a", paramMap({{key, v}}));
    bad(p);
  };
  bad_source("data_type", S("PointCloud3"));
  bad_source("data_type", S("pointcloud"));
  bad_source("obstacle_max_range", D(-1.0));
  bad_source("raytrace_min_range", D(5.0));   // above raytrace_max_range 3.0
  bad_source("min_obstacle_height", D(3.0));  // above max_obstacle_height 2.0
  bad_source("expected_update_rate", D(-0.1));
  bad_source("observation_persistence", D(std::nan("")));
  bad_source("topic", S(""));
  bad_source("marking", S("yes"));
  try
  {
    ParamValue p = paramMap({{"observation_sources", S("front")}});
    p.set("front", paramMap({{"obstacle_max_range", D(-1.0)}}));
    parseObstacleConfig(ParamReader(p, "obstacles"), false);
    FAIL();
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("obstacles/front"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("obstacle_max_range"), std::string::npos) << e.what();
  }
}

TEST(ObstacleLayer, SubscribesEachSourceWithItsFrame)
{
  ParamValue p = paramMap({{"observation_sources", S("scan cam")}});
  p.set("scan", paramMap({{"data_type", S("LaserScan")}, {"topic", S("/base_scan")}, {"sensor_frame", S("laser")}}));
  p.set("cam", paramMap({{"data_type", S("PointCloud2")}}));
  Rig rig(p, false);
  ASSERT_EQ(rig.ctx->scan_subs.size(), 1u);
  EXPECT_EQ(rig.ctx->scan_subs[0].topic, "/base_scan");
  EXPECT_EQ(rig.ctx->scan_subs[0].sensor_frame, "laser");
  ASSERT_EQ(rig.ctx->cloud_subs.size(), 1u);
  EXPECT_EQ(rig.ctx->cloud_subs[0].topic, "cam");
  EXPECT_EQ(rig.ctx->cloud_subs[0].sensor_frame, "");
  EXPECT_TRUE(rig.layer->isClearable());
  EXPECT_EQ(rig.layer->sourceCount(), 2u);
}

// costmap_2d's testRaytracing: one marking observation adds one lethal cell to the 20 static ones.
TEST(ObstacleLayer, OneObservationAddsOneLethalCell)
{
  Rig rig(obstacleParams(), true);
  rig.update();
  ASSERT_EQ(count(rig.master(), LETHAL_OBSTACLE), 20);
  rig.cloud({{0.0, 0.0, MAX_Z / 2}}, poseAt(0, 0, MAX_Z / 2));
  rig.update();
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 21);
  EXPECT_EQ(rig.master().getCost(0, 0), LETHAL_OBSTACLE);
}

// costmap_2d's testRaytracing2: the diagonal marked by hand is cleared again by the persisting
// observation's ray, leaving the static map plus the observed end cell.
TEST(ObstacleLayer, ReRaytracingClearsTheDiagonal)
{
  Rig rig(obstacleParams(), true);
  rig.update();
  ASSERT_EQ(count(rig.master(), LETHAL_OBSTACLE), 20);
  rig.cloud({{9.5, 9.5, MAX_Z / 2}}, poseAt(0.5, 0.5, MAX_Z / 2));
  rig.update();
  const int after = count(rig.master(), LETHAL_OBSTACLE);
  ASSERT_EQ(after, 21);
  for (unsigned i = 0; i < 10; ++i)
    rig.layer->costmap().setCost(i, i, LETHAL_OBSTACLE);
  rig.update();
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 21);
  EXPECT_EQ(count(rig.master(), FREE_SPACE), 79);
  EXPECT_EQ(rig.master().getCost(9, 9), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.layer->costmap().getCost(8, 8), FREE_SPACE);
}

// costmap_2d's testWaveInterference: three hits on the diagonal seen from the origin.
TEST(ObstacleLayer, WaveInterferenceWithUnknownSpace)
{
  Rig rig(obstacleParams(), false, true);
  EXPECT_TRUE(rig.layer->config().track_unknown_space);
  rig.cloud({{3.0, 3.0, MAX_Z}, {5.0, 5.0, MAX_Z}, {7.0, 7.0, MAX_Z}}, poseAt(0, 0, MAX_Z));
  rig.update();
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 3);
  EXPECT_EQ(count(rig.master(), FREE_SPACE), 5);
  EXPECT_EQ(count(rig.master(), NO_INFORMATION), 92);
  for (unsigned i : {0u, 1u, 2u, 4u, 6u})
    EXPECT_EQ(rig.master().getCost(i, i), FREE_SPACE) << i;
}

// costmap_2d's testZThreshold, for the layer's limit and for the source's.
TEST(ObstacleLayer, HeightLimits)
{
  {
    Rig rig(obstacleParams({}, {{"max_obstacle_height", D(5.0)}}), false, true);  // the layer's 2.0 applies
    rig.cloud({{0.0, 5.0, 0.4}, {1.0, 5.0, 2.2}}, poseAt(0, 0, MAX_Z));
    rig.update();
    EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 1);
    EXPECT_EQ(rig.master().getCost(0, 5), LETHAL_OBSTACLE);
  }
  {
    Rig rig(obstacleParams({{"max_obstacle_height", D(5.0)}}), false, true);  // the source's 2.0 applies
    rig.cloud({{0.0, 5.0, 0.4}, {1.0, 5.0, 2.2}}, poseAt(0, 0, MAX_Z));
    rig.update();
    EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 1);
  }
  {
    Rig rig(obstacleParams({}, {{"min_obstacle_height", D(0.5)}}), false, true);
    rig.cloud({{0.0, 5.0, 0.4}, {1.0, 5.0, 0.6}}, poseAt(0, 0, MAX_Z));
    rig.update();
    EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 1);
    EXPECT_EQ(rig.master().getCost(1, 5), LETHAL_OBSTACLE);
  }
}

// Obstacle ranges at 0.1 m: max and min are inclusive 3-D distances, points beyond are skipped (not cut).
TEST(ObstacleLayer, ObstacleRangesAtFineResolution)
{
  auto lethalAfter = [](double max_range, double min_range, XYZ p)
  {
    Rig rig(obstacleParams({}, {{"obstacle_max_range", D(max_range)}, {"obstacle_min_range", D(min_range)}}), false,
            false, false, 40, 0.1, -2.0, -2.0);
    rig.cloud({p}, poseAt(0, 0, 0));
    rig.update();
    return count(rig.master(), LETHAL_OBSTACLE);
  };
  EXPECT_EQ(lethalAfter(1.0, 0.0, {1.0, 0.0, 0.0}), 1);
  EXPECT_EQ(lethalAfter(2.5, 0.5, {0.35, 0.0, 0.0}), 0);
  EXPECT_EQ(lethalAfter(2.5, 0.5, {0.5, 0.0, 0.0}), 1);
  EXPECT_EQ(lethalAfter(0.72, 0.0, {0.79, 0.0, 0.0}), 0);
  EXPECT_EQ(lethalAfter(0.72, 0.0, {0.7, 0.0, 0.0}), 1);
  // The distance is 3-D: 0.6 m ahead but 0.8 m below the sensor is 1.0 m away.
  EXPECT_EQ(lethalAfter(0.9, 0.0, {0.6, 0.0, 0.0}), 1);
  Rig rig(obstacleParams({}, {{"obstacle_max_range", D(0.9)}}), false, false, false, 40, 0.1, -2.0, -2.0);
  rig.cloud({{0.6, 0.0, 0.0}}, poseAt(0, 0, 0.8));
  rig.update();
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 0);
}

TEST(ObstacleLayer, RaytraceRangesCutRays)
{
  // Origin (0.5, 5.5); a hit 8 m away with raytrace_max_range 3: as costmap_2d, 3 steps of the walk and
  // the cell where they stop, x = 0..3, cleared; not beyond.
  Rig rig(obstacleParams({}, {{"raytrace_max_range", D(3.0)}, {"marking", B(false)}}), false, true);
  rig.cloud({{8.5, 5.5, 0.5}}, poseAt(0.5, 5.5, 0.5));
  rig.update();
  for (unsigned x = 0; x <= 3; ++x)
    EXPECT_EQ(rig.master().getCost(x, 5), FREE_SPACE) << x;
  for (unsigned x = 4; x < 10; ++x)
    EXPECT_EQ(rig.master().getCost(x, 5), NO_INFORMATION) << x;
  EXPECT_EQ(count(rig.master(), FREE_SPACE), 4);

  // raytrace_min_range 2: the first two cells stay unknown.
  Rig near(obstacleParams({}, {{"raytrace_min_range", D(2.0)}, {"marking", B(false)}}), false, true);
  near.cloud({{8.5, 5.5, 0.5}}, poseAt(0.5, 5.5, 0.5));
  near.update();
  EXPECT_EQ(near.master().getCost(0, 5), NO_INFORMATION);
  EXPECT_EQ(near.master().getCost(1, 5), NO_INFORMATION);
  EXPECT_EQ(near.master().getCost(2, 5), FREE_SPACE);
  EXPECT_EQ(near.master().getCost(7, 5), FREE_SPACE);
  EXPECT_EQ(near.master().getCost(8, 5), FREE_SPACE);  // the reading's cell too (this source does not mark)
  EXPECT_EQ(near.master().getCost(9, 5), NO_INFORMATION);

  // A hit outside the grid still clears the part of its ray inside.
  Rig out(obstacleParams({}, {{"marking", B(false)}}), false, true);
  out.cloud({{25.5, 5.5, 0.5}}, poseAt(0.5, 5.5, 0.5));
  out.update();
  for (unsigned x = 0; x < 10; ++x)  // the border cell too, where the grid cuts the ray
    EXPECT_EQ(out.master().getCost(x, 5), FREE_SPACE) << x;
}

// costmap_2d's raytraceLine visits the end cell of a ray (one call after its loop), so a ray clears the
// cell it ends in, and the marking that follows marks it again if the reading marks. Two marks that
// stayed here for good (before, the end cell was never cleared):
// - an obstacle that the sensor now sees beyond obstacle_max_range but within raytrace_max_range:
//   costmap_2d forgets it (its cell is the ray's end);
// - a mark in the grid's border cell, where every ray leaving the grid ends (a rolling window's edge).
TEST(ObstacleLayer, ARayClearsTheCellItEndsInAsCostmap2dDoes)
{
  Rig rig(obstacleParams({{"footprint_clearing_enabled", B(false)}},
                         {{"obstacle_max_range", D(2.5)}, {"raytrace_max_range", D(3.0)}}),
          false, true);
  rig.cloud({{2.9, 5.5, 0.5}}, poseAt(0.5, 5.5, 0.5));  // 2.4 m: marks (2, 5)
  rig.update();
  ASSERT_EQ(rig.master().getCost(2, 5), LETHAL_OBSTACLE);
  rig.cloud({{2.9, 5.5, 0.5}}, poseAt(0.2, 5.5, 0.5));  // 2.7 m: beyond the obstacle range
  rig.update();
  EXPECT_EQ(rig.master().getCost(2, 5), FREE_SPACE);
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 0);

  Rig edge(obstacleParams({{"footprint_clearing_enabled", B(false)}}), false, true);
  edge.cloud({{9.5, 5.5, 0.5}}, poseAt(5.5, 5.5, 0.5));  // the border cell (9, 5)
  edge.update(5.5, 5.5);
  ASSERT_EQ(edge.master().getCost(9, 5), LETHAL_OBSTACLE);
  edge.cloud({{25.5, 5.5, 0.5}}, poseAt(5.5, 5.5, 0.5));  // the obstacle went: the beam leaves the grid
  edge.update(5.5, 5.5);
  EXPECT_EQ(edge.master().getCost(9, 5), FREE_SPACE);
  EXPECT_EQ(count(edge.master(), LETHAL_OBSTACLE), 0);
}

// A reading in the sensor's own cell: costmap_2d's ray to it has no length, and its bresenham still calls
// the action once (the cell is cleared, then marked, as marking comes after clearing). Any later ray
// starts in that cell and clears it, and a reading exactly at the sensor marks like any other.
TEST(ObstacleLayer, AReadingInTheSensorsOwnCellIsMarkedAndLaterRaysClearIt)
{
  Rig rig(obstacleParams({{"footprint_clearing_enabled", B(false)}}), false, true);
  rig.cloud({{5.8, 5.5, 0.5}}, poseAt(5.2, 5.5, 0.5));  // both in cell (5, 5)
  rig.update(5.2, 5.5);
  EXPECT_EQ(rig.master().getCost(5, 5), LETHAL_OBSTACLE);
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 1);
  EXPECT_EQ(count(rig.master(), FREE_SPACE), 0);        // the ray has no other cell
  rig.cloud({{8.5, 5.5, 0.5}}, poseAt(5.2, 5.5, 0.5));  // the obstacle went; a wall at (8, 5)
  rig.update(5.2, 5.5);
  EXPECT_EQ(rig.master().getCost(5, 5), FREE_SPACE);
  EXPECT_EQ(rig.master().getCost(8, 5), LETHAL_OBSTACLE);
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 1);

  Rig at(obstacleParams({{"footprint_clearing_enabled", B(false)}}), false, true);
  at.cloud({{3.5, 2.5, 0.5}}, poseAt(3.5, 2.5, 0.5));  // at the sensor itself: distance 0
  at.update(3.5, 2.5);
  EXPECT_EQ(at.master().getCost(3, 2), LETHAL_OBSTACLE);
  EXPECT_EQ(count(at.master(), LETHAL_OBSTACLE), 1);
}

// The layer's own height limits (Nav2's min_obstacle_height, both layers' max_obstacle_height) bound
// what is marked, inclusive at both ends, whatever the source allows; a reversed pair is refused.
TEST(ObstacleLayer, TheLayersHeightLimitsBoundWhatIsMarked)
{
  Rig rig(
      obstacleParams(
          {{"footprint_clearing_enabled", B(false)}, {"min_obstacle_height", D(0.25)}, {"max_obstacle_height", D(1.5)}},
          {{"min_obstacle_height", D(-5.0)}, {"max_obstacle_height", D(5.0)}}),
      false, true);
  rig.cloud({{2.5, 5.5, 0.24}, {3.5, 5.5, 0.25}, {4.5, 5.5, 1.0}, {6.5, 5.5, 1.5}, {7.5, 5.5, 1.51}, {8.5, 5.5, -1.0}},
            poseAt(0.5, 5.5, 0.5));
  rig.update();
  EXPECT_NE(rig.master().getCost(2, 5), LETHAL_OBSTACLE);  // below the layer's minimum
  EXPECT_EQ(rig.master().getCost(3, 5), LETHAL_OBSTACLE);  // at it
  EXPECT_EQ(rig.master().getCost(4, 5), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.master().getCost(6, 5), LETHAL_OBSTACLE);  // at the maximum
  EXPECT_NE(rig.master().getCost(7, 5), LETHAL_OBSTACLE);  // above it
  EXPECT_NE(rig.master().getCost(8, 5), LETHAL_OBSTACLE);
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 3);

  // Unset, the layer has no minimum (costmap_2d's): a hit below the ground that the source allows marks.
  Rig open(obstacleParams({{"footprint_clearing_enabled", B(false)}}, {{"min_obstacle_height", D(-5.0)}}), false, true);
  open.cloud({{3.5, 5.5, -1.0}}, poseAt(0.5, 5.5, 0.5));
  open.update();
  EXPECT_EQ(open.master().getCost(3, 5), LETHAL_OBSTACLE);

  EXPECT_THROW(Rig(obstacleParams({{"min_obstacle_height", D(1.0)}, {"max_obstacle_height", D(0.5)}}), false),
               std::invalid_argument);
}

TEST(ObstacleLayer, LaserScanMarksAndClearsAndInfClearsOnly)
{
  ParamValue p = paramMap({{"observation_sources", S("scan")}});
  p.set("scan", paramMap({{"data_type", S("LaserScan")},
                          {"clearing", B(true)},
                          {"inf_is_valid", B(true)},
                          {"obstacle_max_range", D(10.0)},
                          {"raytrace_max_range", D(10.0)}}));
  Rig rig(p, false, true);
  // Three beams at -90, 0, +90 degrees from (5.5, 5.5): right wall hit at 3 m, the other two see nothing.
  LaserScanData scan = makeScan(3, -1.5707964f, 1.5707964f, 3.0f, 0.1f, 4.0f);
  scan.ranges[0] = std::numeric_limits<float>::infinity();
  scan.ranges[2] = std::numeric_limits<float>::quiet_NaN();
  ASSERT_EQ(rig.ctx->publishScan("scan", scan, poseAt(5.5, 5.5, 0.3)), 1);
  rig.update(5.5, 5.5);
  EXPECT_EQ(rig.master().getCost(8, 5), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.master().getCost(6, 5), FREE_SPACE);
  EXPECT_EQ(rig.master().getCost(5, 3), FREE_SPACE);      // cleared by the inf beam (to 4 m: y = 1.5)
  EXPECT_EQ(rig.master().getCost(5, 1), FREE_SPACE);      // its end cell cleared too (costmap_2d), not marked
  EXPECT_EQ(rig.master().getCost(5, 0), NO_INFORMATION);  // beyond the 4 m
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 1);
  EXPECT_EQ(rig.master().getCost(5, 7), NO_INFORMATION);  // the NaN beam did nothing
}

TEST(ObstacleLayer, MalformedReadingsAreRejectedAndReported)
{
  Rig rig(obstacleParams(), false, true);
  PointCloud2Data c = makeCloud({{1, 1, 0.5}});
  c.data.resize(c.data.size() - 1);
  rig.ctx->publishCloud("cloud", c, poseAt(0, 0, 0));
  EXPECT_EQ(rig.layer->buffer(0).size(), 0u);
  EXPECT_EQ(rig.ctx->countReports("observation source 'cloud'"), 1);
  EXPECT_EQ(rig.ctx->countReports("data has"), 1);
  EXPECT_EQ(rig.layer->addPointCloud2(7, c, poseAt(0, 0, 0)), "no observation source 7");
  rig.update();
  EXPECT_EQ(count(rig.master(), NO_INFORMATION), 100);
}

TEST(ObstacleLayer, CombinationMethods)
{
  {  // max (default) takes the own cost over unknown
    Rig rig(obstacleParams({}, {{"clearing", B(false)}}), false, true);
    rig.cloud({{0.0, 0.0, MAX_Z / 2}}, poseAt(0, 0, MAX_Z / 2));
    rig.update();
    EXPECT_EQ(count(rig.master(), NO_INFORMATION), 99);
  }
  {  // 2: unknown master cells stay unknown
    Rig rig(obstacleParams({{"combination_method", I(2)}}, {{"clearing", B(false)}}), false, true);
    rig.cloud({{0.0, 0.0, MAX_Z / 2}}, poseAt(0, 0, MAX_Z / 2));
    rig.update();
    EXPECT_EQ(count(rig.master(), NO_INFORMATION), 100);
  }
  {  // 0: the cleared cells overwrite the static map's lethal ones
    Rig rig(obstacleParams({{"combination_method", I(0)}}), true, true);
    rig.cloud({{9.5, 0.5, 0.5}}, poseAt(0.5, 0.5, 0.5));
    rig.update();
    EXPECT_EQ(rig.master().getCost(7, 0), FREE_SPACE);
    EXPECT_EQ(rig.master().getCost(8, 0), FREE_SPACE);
    EXPECT_EQ(rig.master().getCost(9, 0), LETHAL_OBSTACLE);
    EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 18);  // 20 static, two overwritten with free
  }
}

TEST(ObstacleLayer, FootprintClearing)
{
  for (bool enabled : {true, false})
  {
    Rig rig(obstacleParams({{"footprint_clearing_enabled", B(enabled)}}, {{"clearing", B(false)}}), false, true);
    rig.lc.setFootprint({{-0.6, -0.6}, {0.6, -0.6}, {0.6, 0.6}, {-0.6, 0.6}});
    rig.cloud({{5.5, 5.5, 0.5}, {4.5, 4.5, 0.5}, {8.5, 8.5, 0.5}}, poseAt(2.5, 2.5, 0.5));
    rig.update(5.0, 5.0);
    EXPECT_EQ(rig.master().getCost(5, 5), enabled ? FREE_SPACE : LETHAL_OBSTACLE);
    EXPECT_EQ(rig.master().getCost(4, 4), enabled ? FREE_SPACE : LETHAL_OBSTACLE);
    EXPECT_EQ(rig.master().getCost(8, 8), LETHAL_OBSTACLE);
    EXPECT_EQ(count(rig.master(), FREE_SPACE), enabled ? 4 : 0);
  }
}

TEST(ObstacleLayer, RollingWindowKeepsObstaclesInPlace)
{
  ParamValue p = obstacleParams({}, {{"clearing", B(false)}, {"observation_persistence", D(0.5)}});
  Rig rig(p, false, true, true);
  rig.ctx->now_ns = 1'000'000'000;
  rig.cloud({{6.5, 5.5, 0.5}}, poseAt(5, 5, 0.5), 1'000'000'000);
  rig.update(5.0, 5.0);  // origin (0, 0)
  EXPECT_EQ(rig.master().getCost(6, 5), LETHAL_OBSTACLE);
  rig.ctx->now_ns = 3'000'000'000;  // the observation expired: only the grid remembers it
  rig.update(7.0, 4.0);             // origin (2, -1)
  EXPECT_EQ(rig.layer->buffer(0).size(), 0u);
  EXPECT_DOUBLE_EQ(rig.layer->costmap().getOriginX(), 2.0);
  EXPECT_DOUBLE_EQ(rig.layer->costmap().getOriginY(), -1.0);
  EXPECT_EQ(rig.layer->costmap().getCost(4, 6), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.master().getCost(4, 6), LETHAL_OBSTACLE);
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 1);
  rig.update(20.0, 4.0);  // far away: the cell left the window
  EXPECT_EQ(count(rig.layer->costmap(), LETHAL_OBSTACLE), 0);
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 0);
}

TEST(ObstacleLayer, PersistenceAndKeepDistance)
{
  Rig rig(obstacleParams(
              {}, {{"clearing", B(false)}, {"observation_persistence", D(1.0)}, {"observation_keep_distance", D(2.0)}}),
          false, true);
  rig.ctx->now_ns = 1'000'000'000;
  rig.cloud({{1.5, 1.5, 0.5}}, poseAt(0.5, 0.5, 0.5), 1'000'000'000);
  rig.ctx->now_ns = 1'500'000'000;
  rig.cloud({{2.5, 2.5, 0.5}}, poseAt(3.5, 0.5, 0.5), 1'500'000'000);
  EXPECT_EQ(rig.layer->buffer(0).size(), 2u);
  rig.ctx->now_ns = 1'800'000'000;
  rig.update(2.0, 0.5);
  EXPECT_EQ(rig.layer->buffer(0).size(), 2u);
  EXPECT_EQ(count(rig.master(), LETHAL_OBSTACLE), 2);
  rig.ctx->now_ns = 2'200'000'000;  // the first is 1.2 s old
  rig.update(2.0, 0.5);
  EXPECT_EQ(rig.layer->buffer(0).size(), 1u);
  rig.update(7.0, 0.5);  // 3.5 m from the second one's origin
  EXPECT_EQ(rig.layer->buffer(0).size(), 0u);
}

TEST(ObstacleLayer, LateSourceMakesTheLayerNotCurrentAndIsNamed)
{
  ParamValue p = paramMap({{"observation_sources", S("front_scan rear")}});
  p.set("front_scan", paramMap({{"data_type", S("LaserScan")}, {"expected_update_rate", D(0.5)}}));
  p.set("rear", paramMap({{"data_type", S("LaserScan")}}));
  Rig rig(p, false);
  rig.ctx->now_ns = 100'000'000;
  ASSERT_EQ(rig.ctx->publishScan("front_scan", makeScan(10, -1, 1, 1.0f), poseAt(5, 5, 0)), 1);
  rig.ctx->now_ns = 500'000'000;
  rig.update(5, 5);
  EXPECT_TRUE(rig.layer->isCurrent());
  EXPECT_TRUE(rig.lc.isCurrent());
  rig.ctx->now_ns = 1'000'000'000;  // 0.9 s since the last scan
  rig.update(5, 5);
  EXPECT_FALSE(rig.layer->isCurrent());
  EXPECT_FALSE(rig.lc.isCurrent());
  EXPECT_EQ(rig.ctx->countReports("'front_scan'"), 1);
  EXPECT_EQ(rig.ctx->countReports("'rear'"), 0);
  ASSERT_FALSE(rig.ctx->reports.empty());
  EXPECT_EQ(rig.ctx->reports.back().severity, Severity::Warn);
  EXPECT_NE(rig.ctx->reports.back().message.find("0.90 s"), std::string::npos) << rig.ctx->reports.back().message;
  rig.ctx->publishScan("front_scan", makeScan(10, -1, 1, 1.0f), poseAt(5, 5, 0));
  rig.update(5, 5);
  EXPECT_TRUE(rig.layer->isCurrent());
}

TEST(ObstacleLayer, ResetClearsGridAndBuffers)
{
  Rig rig(obstacleParams({}, {{"clearing", B(false)}}), false, true);
  rig.cloud({{3.5, 3.5, 0.5}}, poseAt(0.5, 0.5, 0.5));
  rig.update();
  ASSERT_EQ(count(rig.layer->costmap(), LETHAL_OBSTACLE), 1);
  rig.layer->reset();
  EXPECT_EQ(rig.layer->buffer(0).size(), 0u);
  EXPECT_EQ(count(rig.layer->costmap(), NO_INFORMATION), 100);
  rig.update();
  EXPECT_EQ(count(rig.layer->costmap(), LETHAL_OBSTACLE), 0);
  // Deactivated layers ignore readings.
  rig.layer->deactivate();
  rig.cloud({{3.5, 3.5, 0.5}}, poseAt(0.5, 0.5, 0.5));
  EXPECT_EQ(rig.layer->buffer(0).size(), 0u);
  rig.layer->activate();
  rig.cloud({{3.5, 3.5, 0.5}}, poseAt(0.5, 0.5, 0.5));
  EXPECT_EQ(rig.layer->buffer(0).size(), 1u);
}

TEST(ObstacleLayer, StaticObservationsPersist)
{
  Rig rig(obstacleParams(), false, true);
  Observation o;
  o.origin_x = 0.5;
  o.origin_y = 0.5;
  o.points = {{4.5f, 0.5f, 0.0f}};
  o.obstacle_max_range = o.raytrace_max_range = 100.0;
  rig.layer->addStaticObservation(o, true, true);
  rig.update();
  rig.update();
  EXPECT_EQ(rig.master().getCost(4, 0), LETHAL_OBSTACLE);
  EXPECT_EQ(count(rig.master(), FREE_SPACE), 4);
  rig.layer->clearStaticObservations(true, true);
  rig.layer->costmap().setCost(2, 0, LETHAL_OBSTACLE);
  rig.layer->addExtraBounds(0, 0, 10, 10);
  rig.update();
  EXPECT_EQ(rig.master().getCost(2, 0), LETHAL_OBSTACLE);
}

TEST(ObstacleLayer, ReadingsFromAnotherThread)
{
  Rig rig(obstacleParams(), false, true);
  // The producer delivers a fixed number of readings while the updates run; the updates go on until
  // it is done, so both sides really overlap whatever the scheduler does.
  std::atomic<bool> done{false};
  std::thread producer(
      [&]
      {
        const PointCloud2Data c = makeCloud({{3.0, 3.0, 0.0}, {6.0, 2.0, 0.0}, {2.0, 8.0, 0.0}});  // sensor frame
        for (int k = 0; k < 300; ++k)
          rig.ctx->publishCloud("cloud", c, poseAt(0.5, 0.5, 0.5));
        done = true;
      });
  int updates = 0;
  while (!done || updates < 50)
  {
    rig.update();
    ++updates;
  }
  producer.join();
  rig.update();
  EXPECT_EQ(rig.master().getCost(3, 3), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.master().getCost(6, 2), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.master().getCost(2, 8), LETHAL_OBSTACLE);
}

TEST(ObstacleLayer, ClearingRaysFollowTheBeamPropertyTest)
{
  // Random beams (seeded, so deterministic) from origins with sub-cell offsets, in every octant, with
  // readings nearer and farther than raytrace_max_range and beyond the grid.
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const double ranges[][2] = {{0.0, 0.45}, {0.0, 1.0}, {0.5, 2.35}, {1.2, 3.0}};  // {min, max} [m]
  int failures = 0, beams = 0;
  for (const auto& range : ranges)
  {
    ParamValue p = obstacleParams(
        {{"footprint_clearing_enabled", B(false)}},
        {{"marking", B(false)}, {"raytrace_min_range", D(range[0])}, {"raytrace_max_range", D(range[1])}});
    Rig rig(p, false, true, false, 80, 0.1, -4.0, -4.0);
    for (int k = 0; k < 150; ++k)
    {
      const double ox = -2.0 + 4.0 * uni(rng), oy = -2.0 + 4.0 * uni(rng);
      // Every eighth beam exactly along an octant boundary, the rest anywhere.
      const double angle = k % 8 == 0 ? (k / 8 % 8) * M_PI / 4 : 2 * M_PI * uni(rng);
      const double dist = k % 5 == 0 ? 30.0 : range[1] * (0.2 + 3.8 * uni(rng));
      const float lx = static_cast<float>(dist * std::cos(angle)), ly = static_cast<float>(dist * std::sin(angle));
      rig.layer->reset();
      ASSERT_EQ(rig.ctx->publishCloud("cloud", makeCloud({{lx, ly, 0.0}}), poseAt(ox, oy, 0.5)), 1);
      rig.update();
      const BeamCase b{ox, oy, static_cast<float>(ox + lx), static_cast<float>(oy + ly), range[0], range[1]};
      // The grid moves the origin to its cell's centre (<= sqrt(2)/2 cell) and Bresenham steps up to half
      // a cell beside the line between cell centres: 1.25 cells beside the beam at most.
      const std::string err = checkBeam(b, rig.layer->costmap(), FREE_SPACE, 1.25, true);
      ++beams;
      if (!err.empty() && ++failures <= 10)
        ADD_FAILURE() << "origin (" << ox << ", " << oy << ") angle " << angle << " dist " << dist << " range ["
                      << range[0] << ", " << range[1] << "]:" << err;
    }
  }
  EXPECT_EQ(failures, 0) << "of " << beams << " beams";
}

TEST(ObstacleLayer, ReadingStampedAheadOfNowIsRejectedNotAGhost)
{
  // A reading stamped 90 s ahead of the clock would count as fresh until the clock caught up: a ghost
  // obstacle re-marked every cycle, which clearing cannot remove. It is refused with a report naming
  // header.stamp and now.
  Rig rig(obstacleParams({{"footprint_clearing_enabled", B(false)}}, {{"observation_persistence", D(1.0)}}), false,
          true);
  rig.ctx->now_ns = 10'000'000'000;
  rig.cloud({{5.5, 5.5, 0.5}}, poseAt(5.5, 2.5, 0.5), 100'000'000'000);
  rig.update();
  EXPECT_EQ(rig.master().getCost(5, 5), NO_INFORMATION);
  EXPECT_EQ(rig.ctx->countReports("header.stamp 100.000 s"), 1);
  EXPECT_EQ(rig.ctx->countReports("now 10.000 s"), 1);
  // Up to half a second ahead (clock skew between hosts) is accepted, and expires like any other.
  rig.cloud({{5.5, 5.5, 0.5}}, poseAt(5.5, 2.5, 0.5), 10'400'000'000);
  rig.update();
  EXPECT_EQ(rig.master().getCost(5, 5), LETHAL_OBSTACLE);
  rig.ctx->now_ns = 11'500'000'000;  // 1.1 s after its stamp: expired, a crossing ray clears the cell
  rig.cloud({{8.5, 5.5, 0.5}}, poseAt(0.5, 5.5, 0.5), 11'500'000'000);
  rig.update();
  EXPECT_EQ(rig.master().getCost(5, 5), FREE_SPACE);
  // The worst stamp a sender can put there.
  rig.cloud({{2.5, 7.5, 0.5}}, poseAt(0.5, 5.5, 0.5), UINT64_MAX);
  rig.update();
  EXPECT_EQ(rig.master().getCost(2, 7), NO_INFORMATION);
  EXPECT_EQ(rig.layer->buffer(0).size(), 1u);
}

// A sensor whose stamps lag the clock by more than observation_persistence (a host clock behind, a slow
// driver): costmap_2d buffers each reading and purges it at once, counting it as an update, so the
// source reads current while nothing is ever marked. Here it is refused, said, and the source goes late.
TEST(ObstacleLayer, ReadingOlderThanPersistenceOnArrivalIsRefusedAndSaid)
{
  ParamValue p = obstacleParams({{"footprint_clearing_enabled", B(false)}},
                                {{"observation_persistence", D(1.0)}, {"expected_update_rate", D(1.0)}});
  Rig rig(p, false, true);
  rig.ctx->now_ns = 10'000'000'000;
  rig.cloud({{5.5, 5.5, 0.5}}, poseAt(5.5, 2.5, 0.5), 10'000'000'000);
  rig.update();
  ASSERT_EQ(rig.master().getCost(5, 5), LETHAL_OBSTACLE);
  ASSERT_TRUE(rig.layer->isCurrent());
  rig.ctx->now_ns = 10'500'000'000;
  rig.cloud({{7.5, 7.5, 0.5}}, poseAt(7.5, 2.5, 0.5), 8'000'000'000);  // 2.5 s old on arrival
  rig.update();
  EXPECT_EQ(rig.master().getCost(7, 7), NO_INFORMATION);
  EXPECT_EQ(rig.ctx->countReports("header.stamp 8.000 s is 2.500 s old at now 10.500 s"), 1);
  EXPECT_EQ(rig.ctx->countReports("observation_persistence (1 s)"), 1);
  rig.ctx->now_ns = 11'200'000'000;  // 1.2 s after the last reading it kept: late
  rig.update();
  EXPECT_FALSE(rig.layer->isCurrent());
  // Within persistence (0.9 s old) it is taken; a zero stamp (taken as now) always is.
  rig.cloud({{7.5, 7.5, 0.5}}, poseAt(7.5, 2.5, 0.5), 10'300'000'000);
  rig.cloud({{3.5, 7.5, 0.5}}, poseAt(3.5, 2.5, 0.5), 0);
  rig.update();
  EXPECT_EQ(rig.master().getCost(7, 7), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.master().getCost(3, 7), LETHAL_OBSTACLE);
  EXPECT_TRUE(rig.layer->isCurrent());
}

TEST(ObstacleLayer, ClockJumpBackDropsBufferedReadingsWithOneWarning)
{
  // A looping bag or a restarted simulator: /clock goes from 1000 s back to 5 s. The reading buffered at
  // 1000 s must not look future-stamped (fresh) for the next 995 s.
  ParamValue p = obstacleParams({{"footprint_clearing_enabled", B(false)}},
                                {{"observation_persistence", D(10.0)}, {"expected_update_rate", D(1.0)}});
  Rig rig(p, false, true);
  rig.ctx->now_ns = 1000'000'000'000;
  rig.cloud({{5.5, 5.5, 0.5}}, poseAt(5.5, 2.5, 0.5), 1000'000'000'000);
  rig.update();
  ASSERT_EQ(rig.master().getCost(5, 5), LETHAL_OBSTACLE);
  rig.ctx->now_ns = 5'000'000'000;
  rig.cloud({{8.5, 5.5, 0.5}}, poseAt(0.5, 5.5, 0.5), 5'000'000'000);  // its ray crosses (5, 5)
  rig.update();
  EXPECT_EQ(rig.master().getCost(5, 5), FREE_SPACE);
  EXPECT_EQ(rig.master().getCost(8, 5), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.layer->buffer(0).size(), 1u);
  EXPECT_TRUE(rig.layer->isCurrent());
  rig.ctx->now_ns = 5'500'000'000;
  rig.update();
  EXPECT_EQ(rig.ctx->countReports("jumped back"), 1);
  // The update-rate check runs on the new clock: silent for 1.5 s, the source is late.
  rig.ctx->now_ns = 6'500'000'000;
  rig.update();
  EXPECT_FALSE(rig.layer->isCurrent());
  // A jump back with no reading since: late from the jump on, not current forever nor stale forever.
  rig.ctx->now_ns = 2'000'000'000;
  rig.update();
  EXPECT_TRUE(rig.layer->isCurrent());
  rig.ctx->now_ns = 3'100'000'000;
  rig.update();
  EXPECT_FALSE(rig.layer->isCurrent());
  EXPECT_EQ(rig.ctx->countReports("jumped back"), 2);
}

TEST(ObstacleLayer, ExtremeRaytraceRanges)
{
  // The largest ranges the parameters accept: the ray runs to the grid's edge / clears nothing.
  Rig far(obstacleParams({{"footprint_clearing_enabled", B(false)}},
                         {{"marking", B(false)}, {"raytrace_max_range", D(limits::kMaxDistance)}}),
          false, true);
  far.cloud({{25.5, 5.5, 0.5}}, poseAt(0.5, 5.5, 0.5));
  far.update();
  for (unsigned x = 0; x < 10; ++x)  // the edge cell (the line's end cell) too
    EXPECT_EQ(far.master().getCost(x, 5), FREE_SPACE) << x;
  EXPECT_EQ(count(far.master(), FREE_SPACE), 10);
  Rig none(
      obstacleParams({{"footprint_clearing_enabled", B(false)}}, {{"marking", B(false)},
                                                                  {"raytrace_min_range", D(limits::kMaxDistance)},
                                                                  {"raytrace_max_range", D(limits::kMaxDistance)}}),
      false, true);
  none.cloud({{25.5, 5.5, 0.5}}, poseAt(0.5, 5.5, 0.5));
  none.update();
  EXPECT_EQ(count(none.master(), FREE_SPACE), 0);
}
