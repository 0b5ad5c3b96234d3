// The message-to-port dispatch, the sensors' tf gate and the receipts, fed in-memory messages and a
// hand-filled tf2::BufferCore: no master, no subscriber, no timer. Each case wires the pieces the way
// LayerPorts does (a gate whose ready callback is dispatchReading() and whose failed callback is
// reportDroppedReading()) and checks what reaches the layer's callback and what is logged.
#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <tf2/buffer_core.h>

#include <boost/make_shared.hpp>
#include <cmath>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "costmap_layers/ros/port_dispatch.hpp"
#include "costmap_layers/ros/port_receipts.hpp"
#include "costmap_layers/ros/tf_gate.hpp"

using costmap_layers::Severity;
using costmap_layers_ros::PortSource;
using costmap_layers_ros::TfChangeWake;
using costmap_layers_ros::TfGate;
using costmap_layers_ros::TfVerdict;

namespace
{
/// Every line the adapter logs, in order (the sink of a ThrottledLog with a fixed clock).
struct Lines
{
  std::vector<std::pair<Severity, std::string>> all;
  std::shared_ptr<costmap_layers_ros::ThrottledLog> log = std::make_shared<costmap_layers_ros::ThrottledLog>(
      5.0, [this](Severity s, const std::string& m) { all.emplace_back(s, m); }, [] { return 1.0; });
};

PortSource source(const std::string& topic, Lines& lines)
{
  return PortSource{"/costmap_node/layer", topic, lines.log};
}

geometry_msgs::TransformStamped transform(const std::string& parent, const std::string& child, double t, double x,
                                          double z = 0.0, double qz = 0.0, double qw = 1.0)
{
  geometry_msgs::TransformStamped m;
  m.header.frame_id = parent;
  m.header.stamp = ros::Time(t);
  m.child_frame_id = child;
  m.transform.translation.x = x;
  m.transform.translation.z = z;
  m.transform.rotation.z = qz;
  m.transform.rotation.w = qw;
  return m;
}
}  // namespace

// ---------------------------------------------------------------- non-sensor ports

TEST(PortDispatch, AGridReachesItsPortAsData)
{
  Lines lines;
  nav_msgs::OccupancyGrid msg;
  msg.header.frame_id = "map";
  msg.header.stamp = ros::Time(12, 500);
  msg.info.width = 2;
  msg.info.height = 1;
  msg.info.resolution = 0.25f;
  msg.info.origin.position.x = 1.5;
  msg.info.origin.position.y = -2.0;
  msg.info.origin.orientation.w = 1.0;
  msg.data = {0, 100};
  std::shared_ptr<const costmap_layers::OccupancyGridData> got;
  costmap_layers_ros::dispatch(
      msg, [&](const std::shared_ptr<const costmap_layers::OccupancyGridData>& g) { got = g; }, source("/mask", lines));
  ASSERT_TRUE(got);
  EXPECT_EQ(got->frame_id, "map");
  EXPECT_EQ(got->stamp_ns, 12000000500u);
  EXPECT_EQ(got->width, 2u);
  EXPECT_EQ(got->height, 1u);
  EXPECT_EQ(got->resolution, 0.25);
  EXPECT_EQ(got->origin_x, 1.5);
  EXPECT_EQ(got->origin_y, -2.0);
  EXPECT_EQ(got->origin_yaw, 0.0);
  EXPECT_EQ(got->data, (std::vector<int8_t>{0, 100}));
  EXPECT_TRUE(lines.all.empty());
}

TEST(PortDispatch, AGridWithANonUnitQuaternionIsDeliveredWithAWarning)
{
  Lines lines;
  nav_msgs::OccupancyGrid msg;
  msg.header.frame_id = "map";
  msg.info.width = msg.info.height = 1;
  msg.info.resolution = 1.0f;
  msg.info.origin.orientation.w = 2.0;  // yaw 0, length 2
  msg.data = {50};
  int calls = 0;
  costmap_layers_ros::dispatch(
      msg, [&](const std::shared_ptr<const costmap_layers::OccupancyGridData>&) { ++calls; }, source("/mask", lines));
  EXPECT_EQ(calls, 1);
  ASSERT_EQ(lines.all.size(), 1u);
  EXPECT_EQ(lines.all[0].first, Severity::Warn);
  EXPECT_EQ(lines.all[0].second,
            "/costmap_node/layer: grid on /mask: info.origin.orientation (0, 0, 0, 2) is not of unit length: "
            "normalised (yaw 0 rad) [/costmap_node/layer/mask/info.origin.orientation]");
}

TEST(PortDispatch, AGridThatCannotBeConvertedIsDroppedAndNamed)
{
  Lines lines;
  nav_msgs::OccupancyGrid msg;  // a zero quaternion: no orientation
  int calls = 0;
  costmap_layers_ros::dispatch(
      msg, [&](const std::shared_ptr<const costmap_layers::OccupancyGridData>&) { ++calls; }, source("/mask", lines));
  EXPECT_EQ(calls, 0);
  ASSERT_EQ(lines.all.size(), 1u);
  EXPECT_EQ(lines.all[0].first, Severity::Error);
  EXPECT_EQ(lines.all[0].second,
            "/costmap_node/layer: dropped a grid on /mask: info.origin.orientation (0, 0, 0, 0) has zero length: no "
            "orientation [/costmap_node/layer/mask]");
}

TEST(PortDispatch, AGridUpdateReachesItsPort)
{
  Lines lines;
  map_msgs::OccupancyGridUpdate msg;
  msg.header.frame_id = "map";
  msg.header.stamp = ros::Time(3, 0);
  msg.x = 3;
  msg.y = 4;
  msg.width = 2;
  msg.height = 2;
  msg.data = {1, 2, 3, -1};
  std::shared_ptr<const costmap_layers::OccupancyGridUpdateData> got;
  costmap_layers_ros::dispatch(
      msg, [&](const std::shared_ptr<const costmap_layers::OccupancyGridUpdateData>& u) { got = u; },
      source("/map_updates", lines));
  ASSERT_TRUE(got);
  EXPECT_EQ(got->frame_id, "map");
  EXPECT_EQ(got->stamp_ns, 3000000000u);
  EXPECT_EQ(got->x, 3);
  EXPECT_EQ(got->y, 4);
  EXPECT_EQ(got->width, 2u);
  EXPECT_EQ(got->height, 2u);
  EXPECT_EQ(got->data, (std::vector<int8_t>{1, 2, 3, -1}));
  EXPECT_TRUE(lines.all.empty());
}

TEST(PortDispatch, SpeedLimitsReachTheirPort)
{
  Lines lines;
  costmap_layers::SpeedLimits msg;
  msg.header.frame_id = "map";
  costmap_layers::SpeedLimit a, b;
  a.area_id = 1;
  a.max_speed = 0.5;
  b.area_id = 7;
  b.max_speed = 1.25;
  msg.limits = {a, b};
  std::shared_ptr<const costmap_layers::SpeedLimitsData> got;
  costmap_layers_ros::dispatch(
      msg, [&](const std::shared_ptr<const costmap_layers::SpeedLimitsData>& d) { got = d; },
      source("/speed_limits", lines));
  ASSERT_TRUE(got);
  ASSERT_EQ(got->limits.size(), 2u);
  EXPECT_EQ(got->limits[0].area_id, 1u);
  EXPECT_EQ(got->limits[0].max_speed, 0.5);
  EXPECT_EQ(got->limits[1].area_id, 7u);
  EXPECT_EQ(got->limits[1].max_speed, 1.25);
  EXPECT_TRUE(lines.all.empty());
}

TEST(PortDispatch, AFilterInfoReachesItsPort)
{
  Lines lines;
  costmap_layers::CostmapFilterInfo msg;
  msg.header.frame_id = "map";
  msg.type = 1;
  msg.filter_mask_topic = "/speed_mask";
  msg.base = 100.0f;
  msg.multiplier = -0.5f;
  std::shared_ptr<const costmap_layers::FilterInfoData> got;
  costmap_layers_ros::dispatch(
      msg, [&](const std::shared_ptr<const costmap_layers::FilterInfoData>& d) { got = d; },
      source("/costmap_filter_info", lines));
  ASSERT_TRUE(got);
  EXPECT_EQ(got->type, 1);
  EXPECT_EQ(got->filter_mask_topic, "/speed_mask");
  EXPECT_EQ(got->base, 100.0);
  EXPECT_EQ(got->multiplier, -0.5);
  EXPECT_TRUE(lines.all.empty());
}

TEST(PortDispatch, APathAndOdometryReachTheirPorts)
{
  Lines lines;
  nav_msgs::Path path;
  path.header.frame_id = "odom";
  path.poses.resize(2);
  path.poses[0].pose.position.x = 1.0;
  path.poses[1].pose.position.y = -3.5;
  std::shared_ptr<const costmap_layers::PathData> got_path;
  costmap_layers_ros::dispatch(
      path, [&](const std::shared_ptr<const costmap_layers::PathData>& d) { got_path = d; }, source("/plan", lines));
  ASSERT_TRUE(got_path);
  EXPECT_EQ(got_path->frame_id, "odom");
  ASSERT_EQ(got_path->poses.size(), 2u);
  EXPECT_EQ(got_path->poses[0].x, 1.0);
  EXPECT_EQ(got_path->poses[1].y, -3.5);

  nav_msgs::Odometry odom;
  odom.header.frame_id = "odom";
  odom.child_frame_id = "base_link";
  odom.twist.twist.linear.x = 0.75;
  odom.twist.twist.angular.z = -0.25;
  std::shared_ptr<const costmap_layers::OdometryData> got_odom;
  costmap_layers_ros::dispatch(
      odom, [&](const std::shared_ptr<const costmap_layers::OdometryData>& d) { got_odom = d; },
      source("/odom", lines));
  ASSERT_TRUE(got_odom);
  EXPECT_EQ(got_odom->child_frame_id, "base_link");
  EXPECT_EQ(got_odom->linear_x, 0.75);
  EXPECT_EQ(got_odom->angular_z, -0.25);
  EXPECT_TRUE(lines.all.empty());
}

// A layer's handler that throws must not escape into roscpp's spinner: the message is dropped and named.
TEST(PortDispatch, ACallbackThatThrowsIsLoggedNotPropagated)
{
  Lines lines;
  costmap_layers::SpeedLimits msg;
  const auto refuse = [](const std::shared_ptr<const costmap_layers::SpeedLimitsData>&)
  { throw std::runtime_error("refused by the layer"); };
  EXPECT_NO_THROW(costmap_layers_ros::dispatch(msg, refuse, source("/speed_limits", lines)));
  ASSERT_EQ(lines.all.size(), 1u);
  EXPECT_EQ(lines.all[0].first, Severity::Error);
  EXPECT_EQ(lines.all[0].second,
            "/costmap_node/layer: dropped speed limits on /speed_limits: refused by the layer "
            "[/costmap_node/layer/speed_limits]");
  costmap_layers::CostmapFilterInfo info;
  EXPECT_NO_THROW(costmap_layers_ros::dispatch(
      info, [](const std::shared_ptr<const costmap_layers::FilterInfoData>&) { throw std::runtime_error("no"); },
      source("/info", lines)));
  ASSERT_EQ(lines.all.size(), 2u);
  EXPECT_EQ(lines.all[1].second, "/costmap_node/layer: dropped a filter info on /info: no [/costmap_node/layer/info]");
}

// ---------------------------------------------------------------- sensors through the tf gate

namespace
{
/// map -> base_link at 100 s (x 1.0) and 110 s (x 2.0); base_link -> laser static, 0.2 m ahead, 0.3 m up,
/// turned 90 degrees left. tf keeps 10 s. The clock reads 110.5 s.
struct SensorRig
{
  tf2::BufferCore buffer{ros::Duration(10.0)};
  Lines lines;
  double now = 110.5;
  std::vector<std::pair<std::shared_ptr<const costmap_layers::LaserScanData>, costmap_layers::SensorPose>> scans;

  SensorRig()
  {
    buffer.setTransform(transform("map", "base_link", 100.0, 1.0), "test");
    buffer.setTransform(transform("map", "base_link", 110.0, 2.0), "test");
    buffer.setTransform(transform("base_link", "laser", 0.0, 0.2, 0.3, std::sqrt(0.5), std::sqrt(0.5)), "test", true);
  }

  /// A gate wired as LayerPorts wires it, for scans on /scan whose origin is sensor_frame.
  std::unique_ptr<TfGate<sensor_msgs::LaserScan>> gate(const std::string& sensor_frame = "")
  {
    const PortSource src = source("/scan", lines);
    const costmap_layers::SensorCallback<costmap_layers::LaserScanData> cb =
        [this](const std::shared_ptr<const costmap_layers::LaserScanData>& r, const costmap_layers::SensorPose& p)
    { scans.emplace_back(r, p); };
    return std::make_unique<TfGate<sensor_msgs::LaserScan>>(
        buffer, "map", sensor_frame,
        [this, sensor_frame, src, cb](const sensor_msgs::LaserScan::ConstPtr& m)
        { costmap_layers_ros::dispatchReading(*m, buffer, "map", sensor_frame, cb, src); },
        [this, sensor_frame, src](const sensor_msgs::LaserScan::ConstPtr& m, TfVerdict v)
        {
          costmap_layers_ros::reportDroppedReading(m->header.frame_id, m->header.stamp, v, ros::Time(now), "map",
                                                   sensor_frame, src);
        },
        [this] { return ros::Time(now); });
  }
};

sensor_msgs::LaserScan::ConstPtr scan(const std::string& frame, double stamp)
{
  auto m = boost::make_shared<sensor_msgs::LaserScan>();
  m->header.frame_id = frame;
  m->header.stamp = ros::Time(stamp);
  m->angle_min = -0.5f;
  m->angle_max = 0.5f;
  m->angle_increment = 1.0f;
  m->range_min = 0.1f;
  m->range_max = 4.0f;
  m->ranges = {1.0f, 2.5f};
  return m;
}
}  // namespace

TEST(TfGate, AReadingTfCanPlaceIsDeliveredWithItsPose)
{
  SensorRig r;
  auto gate = r.gate();
  gate->arrive(scan("laser", 105.0));
  ASSERT_EQ(r.scans.size(), 1u);
  const auto& [reading, pose] = r.scans[0];
  EXPECT_EQ(reading->frame_id, "laser");
  EXPECT_EQ(reading->stamp_ns, 105000000000u);
  EXPECT_EQ(reading->ranges, (std::vector<float>{1.0f, 2.5f}));
  // base_link at 105 s lies halfway: x 1.5; the laser 0.2 m ahead of it and 0.3 m up, turned 90 degrees.
  EXPECT_NEAR(pose.to_global.t[0], 1.7, 1e-9);
  EXPECT_NEAR(pose.to_global.t[1], 0.0, 1e-9);
  EXPECT_NEAR(pose.to_global.t[2], 0.3, 1e-9);
  EXPECT_NEAR(pose.to_global.r[0], 0.0, 1e-9);
  EXPECT_NEAR(pose.to_global.r[1], -1.0, 1e-9);
  EXPECT_NEAR(pose.to_global.r[3], 1.0, 1e-9);
  EXPECT_NEAR(pose.to_global.r[8], 1.0, 1e-9);
  EXPECT_NEAR(pose.origin_x, 1.7, 1e-9);
  EXPECT_NEAR(pose.origin_y, 0.0, 1e-9);
  EXPECT_NEAR(pose.origin_z, 0.3, 1e-9);
  EXPECT_EQ(gate->waiting(), 0u);
  EXPECT_TRUE(r.lines.all.empty());
}

TEST(TfGate, AReadingWaitsForAnAbsentTransformThenGoesOnRetry)
{
  SensorRig r;
  auto gate = r.gate();
  gate->arrive(scan("camera", 105.0));  // base_link -> camera not known yet
  EXPECT_TRUE(r.scans.empty());
  EXPECT_EQ(gate->waiting(), 1u);
  gate->arrive(nullptr);  // a retry without it changes nothing
  EXPECT_TRUE(r.scans.empty());
  EXPECT_EQ(gate->waiting(), 1u);
  r.buffer.setTransform(transform("base_link", "camera", 0.0, -0.1), "test", true);
  gate->arrive(nullptr);
  ASSERT_EQ(r.scans.size(), 1u);
  EXPECT_NEAR(r.scans[0].second.origin_x, 1.4, 1e-9);
  EXPECT_EQ(gate->waiting(), 0u);
  EXPECT_TRUE(r.lines.all.empty());
}

// A reading that waits for tf does not hold back a newer one tf can place; once it can be placed, it goes
// before whatever arrives with the retry.
TEST(TfGate, AWaitingReadingGoesFirstOnceTfCanPlaceIt)
{
  SensorRig r;
  auto gate = r.gate();
  gate->arrive(scan("camera", 104.0));  // waits: no camera frame yet
  gate->arrive(scan("laser", 106.0));   // placed at once
  ASSERT_EQ(r.scans.size(), 1u);
  EXPECT_EQ(r.scans[0].first->stamp_ns, 106000000000u);
  r.buffer.setTransform(transform("base_link", "camera", 0.0, 0.0), "test", true);
  gate->arrive(scan("laser", 107.0));
  ASSERT_EQ(r.scans.size(), 3u);
  EXPECT_EQ(r.scans[1].first->stamp_ns, 104000000000u);  // the waiting one first
  EXPECT_EQ(r.scans[2].first->stamp_ns, 107000000000u);
}

TEST(TfGate, AReadingOlderThanTfKeepsIsDroppedAndNamed)
{
  SensorRig r;
  auto gate = r.gate();
  gate->arrive(scan("laser", 50.0));
  EXPECT_TRUE(r.scans.empty());
  EXPECT_EQ(gate->waiting(), 0u);
  ASSERT_EQ(r.lines.all.size(), 1u);
  EXPECT_EQ(r.lines.all[0].first, Severity::Warn);
  EXPECT_EQ(r.lines.all[0].second,
            "/costmap_node/layer: dropped a reading on /scan: cannot transform frame 'laser' into 'map': "
            "header.stamp 50.000 s (60.500 s before now) is older than every transform tf keeps "
            "[/costmap_node/layer/scan/tf/stamp]");
}

TEST(TfGate, AReadingFromTheFutureIsDroppedAndNamed)
{
  SensorRig r;
  auto gate = r.gate();
  gate->arrive(scan("laser", 111.5));  // 1 s ahead of the clock; 0.5 s are allowed
  EXPECT_TRUE(r.scans.empty());
  ASSERT_EQ(r.lines.all.size(), 1u);
  EXPECT_EQ(r.lines.all[0].second,
            "/costmap_node/layer: dropped a reading on /scan: cannot transform frame 'laser' into 'map': "
            "header.stamp 111.500 s (1.000 s after now) is more than 0.5 s ahead of the clock (a wrong sensor "
            "clock, or the clock jumped back) [/costmap_node/layer/scan/tf/future]");
}

TEST(TfGate, AReadingWithoutAFrameIsDroppedAndNamed)
{
  SensorRig r;
  auto gate = r.gate();
  gate->arrive(scan("", 105.0));
  EXPECT_TRUE(r.scans.empty());
  ASSERT_EQ(r.lines.all.size(), 1u);
  EXPECT_EQ(r.lines.all[0].second,
            "/costmap_node/layer: dropped a reading on /scan: cannot transform frame '' into 'map': "
            "header.frame_id is empty [/costmap_node/layer/scan/tf/frame_id]");
}

TEST(TfGate, TheOldestWaitingReadingIsPushedOutPastTenWaiting)
{
  SensorRig r;
  auto gate = r.gate();
  for (int k = 0; k < 11; ++k)
    gate->arrive(scan("camera", 100.0 + k));
  EXPECT_TRUE(r.scans.empty());
  EXPECT_EQ(gate->waiting(), 10u);
  ASSERT_EQ(r.lines.all.size(), 1u);
  EXPECT_EQ(r.lines.all[0].second,
            "/costmap_node/layer: dropped a reading on /scan: cannot transform frame 'camera' into 'map': "
            "no transform at header.stamp 100.000 s (10.500 s before now) arrived while 10 newer readings waited "
            "[/costmap_node/layer/scan/tf/wait]");
}

// A reading whose origin is another frame (sensor_frame) goes only once tf can place both.
TEST(TfGate, ASensorFrameIsWaitedForAndGivesTheOrigin)
{
  SensorRig r;
  auto gate = r.gate("mast");
  gate->arrive(scan("base_link", 105.0));
  EXPECT_TRUE(r.scans.empty());
  EXPECT_EQ(gate->waiting(), 1u);
  r.buffer.setTransform(transform("base_link", "mast", 0.0, -0.4, 1.2), "test", true);
  gate->arrive(nullptr);
  ASSERT_EQ(r.scans.size(), 1u);
  const costmap_layers::SensorPose& pose = r.scans[0].second;
  EXPECT_NEAR(pose.to_global.t[0], 1.5, 1e-9);  // the reading's own frame: base_link
  EXPECT_NEAR(pose.to_global.t[2], 0.0, 1e-9);
  EXPECT_NEAR(pose.origin_x, 1.1, 1e-9);  // the mast: 0.4 m behind, 1.2 m up
  EXPECT_NEAR(pose.origin_z, 1.2, 1e-9);
}

TEST(TfGate, ACloudGoesThroughTheSameGate)
{
  SensorRig r;
  std::vector<costmap_layers::SensorPose> poses;
  std::vector<uint32_t> widths;
  const PortSource src = source("/cloud", r.lines);
  const costmap_layers::SensorCallback<costmap_layers::PointCloud2Data> cb =
      [&](const std::shared_ptr<const costmap_layers::PointCloud2Data>& c, const costmap_layers::SensorPose& p)
  {
    widths.push_back(c->width);
    poses.push_back(p);
  };
  TfGate<sensor_msgs::PointCloud2> gate(
      r.buffer, "map", "",
      [&](const sensor_msgs::PointCloud2::ConstPtr& m)
      { costmap_layers_ros::dispatchReading(*m, r.buffer, "map", "", cb, src); },
      [&](const sensor_msgs::PointCloud2::ConstPtr& m, TfVerdict v) {
        costmap_layers_ros::reportDroppedReading(m->header.frame_id, m->header.stamp, v, ros::Time(110.5), "map", "",
                                                 src);
      },
      [] { return ros::Time(110.5); });
  auto cloud = boost::make_shared<sensor_msgs::PointCloud2>();
  cloud->header.frame_id = "base_link";
  cloud->header.stamp = ros::Time(110.0);
  cloud->width = 3;
  cloud->height = 1;
  gate.arrive(cloud);
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_EQ(widths[0], 3u);
  EXPECT_NEAR(poses[0].origin_x, 2.0, 1e-9);
  auto old = boost::make_shared<sensor_msgs::PointCloud2>(*cloud);
  old->header.stamp = ros::Time(99.0);  // 11 s before the newest transform, tf keeps 10 s
  gate.arrive(old);
  EXPECT_EQ(poses.size(), 1u);
  ASSERT_EQ(r.lines.all.size(), 1u);
  EXPECT_EQ(r.lines.all[0].second,
            "/costmap_node/layer: dropped a reading on /cloud: cannot transform frame 'base_link' into 'map': "
            "header.stamp 99.000 s (11.500 s before now) is older than every transform tf keeps "
            "[/costmap_node/layer/cloud/tf/stamp]");
}

// ---------------------------------------------------------------- retried when tf changes

// LayerPorts retries a gate from tf's transforms-changed signal, as below: a reading that waits goes as
// soon as tf gets the transform it waited for, with no retry of its own and no timer.
TEST(TfChangeWake, AWaitingReadingGoesWhenTfGetsItsTransform)
{
  SensorRig r;
  auto gate = r.gate();
  int retries = 0;
  TfChangeWake wake(r.buffer,
                    [&]
                    {
                      ++retries;
                      gate->arrive(nullptr);
                    });
  gate->arrive(scan("camera", 105.0));  // base_link -> camera not known yet
  EXPECT_EQ(gate->waiting(), 1u);
  r.buffer.setTransform(transform("base_link", "sonar", 0.0, 0.1), "test", true);  // not the one it waits for
  EXPECT_EQ(retries, 1);
  EXPECT_TRUE(r.scans.empty());
  EXPECT_EQ(gate->waiting(), 1u);
  r.buffer.setTransform(transform("base_link", "camera", 0.0, -0.1), "test", true);
  EXPECT_EQ(retries, 2);
  ASSERT_EQ(r.scans.size(), 1u);
  EXPECT_EQ(r.scans[0].first->stamp_ns, 105000000000u);
  EXPECT_NEAR(r.scans[0].second.origin_x, 1.4, 1e-9);  // base_link at 105 s: x 1.5; the camera 0.1 m behind
  EXPECT_EQ(gate->waiting(), 0u);
  EXPECT_TRUE(r.lines.all.empty());
}

// A waiting reading that tf's newer transforms leave behind its cache is dropped and named when tf
// changes, without another reading or a timer.
TEST(TfChangeWake, AReadingTfLeavesBehindIsDroppedWhenTfChanges)
{
  SensorRig r;
  auto gate = r.gate();
  TfChangeWake wake(r.buffer, [&] { gate->arrive(nullptr); });
  gate->arrive(scan("camera", 100.5));  // no camera frame yet
  EXPECT_EQ(gate->waiting(), 1u);
  r.buffer.setTransform(transform("map", "base_link", 112.0, 3.0), "test");  // still no camera: it waits
  EXPECT_EQ(gate->waiting(), 1u);
  // The camera's transforms arrive, but from 111 s on: 100.5 s is more than the 10 s tf keeps before the
  // newest time both frames share.
  r.buffer.setTransform(transform("base_link", "camera", 111.0, -0.1), "test");
  EXPECT_TRUE(r.scans.empty());
  EXPECT_EQ(gate->waiting(), 0u);
  ASSERT_EQ(r.lines.all.size(), 1u);
  EXPECT_NE(r.lines.all[0].second.find("is older than every transform tf keeps"), std::string::npos)
      << r.lines.all[0].second;
}

TEST(TfChangeWake, NoRetryAfterItEnds)
{
  tf2::BufferCore buffer{ros::Duration(10.0)};
  int retries = 0;
  {
    TfChangeWake wake(buffer, [&] { ++retries; });
    buffer.setTransform(transform("map", "base_link", 100.0, 1.0), "test");
    EXPECT_EQ(retries, 1);
  }
  buffer.setTransform(transform("map", "base_link", 101.0, 1.0), "test");
  EXPECT_EQ(retries, 1);
}

// The wake may end while tf's thread is inside a retry (a layer unloaded while tf arrives): the
// destructor waits for that retry to finish, so the gate and the layer behind it are not freed under it.
TEST(TfChangeWake, EndingWaitsForARetryUnderWay)
{
  tf2::BufferCore buffer{ros::Duration(10.0)};
  std::mutex m;
  std::condition_variable cv;
  bool entered = false, release = false;
  std::vector<std::string> order;  // guarded by m
  auto wake = std::make_unique<TfChangeWake>(buffer,
                                             [&]
                                             {
                                               std::unique_lock<std::mutex> lock(m);
                                               entered = true;
                                               cv.notify_all();
                                               cv.wait(lock, [&] { return release; });
                                               order.push_back("retry ended");
                                             });
  std::thread tf_thread([&] { buffer.setTransform(transform("map", "base_link", 100.0, 1.0), "test"); });
  {
    std::unique_lock<std::mutex> lock(m);
    cv.wait(lock, [&] { return entered; });
  }
  std::thread unloader(
      [&]
      {
        wake.reset();
        std::lock_guard<std::mutex> lock(m);
        order.push_back("wake ended");
      });
  {
    std::lock_guard<std::mutex> lock(m);
    EXPECT_TRUE(order.empty());  // the destructor cannot have returned: the retry has not
    release = true;
  }
  cv.notify_all();
  tf_thread.join();
  unloader.join();
  EXPECT_EQ(order, (std::vector<std::string>{"retry ended", "wake ended"}));
}

// Called without the gate (or after tf lost the frame), the look-up fails: a warning, nothing delivered.
TEST(PortDispatch, AReadingTfCannotPlaceIsDroppedWithAWarning)
{
  SensorRig r;
  int calls = 0;
  const costmap_layers::SensorCallback<costmap_layers::LaserScanData> cb =
      [&](const std::shared_ptr<const costmap_layers::LaserScanData>&, const costmap_layers::SensorPose&) { ++calls; };
  costmap_layers_ros::dispatchReading(*scan("ghost", 105.0), r.buffer, "map", "", cb, source("/scan", r.lines));
  EXPECT_EQ(calls, 0);
  ASSERT_EQ(r.lines.all.size(), 1u);
  EXPECT_EQ(r.lines.all[0].first, Severity::Warn);
  const std::string& line = r.lines.all[0].second;
  EXPECT_EQ(line.rfind("/costmap_node/layer: dropped a reading on /scan (frame ghost): ", 0), 0u) << line;
  EXPECT_NE(line.find("ghost"), std::string::npos);
  EXPECT_EQ(line.substr(line.size() - 30), " [/costmap_node/layer/scan/tf]");
}

// ---------------------------------------------------------------- receipts

TEST(PortReceipts, TheTextSaysHowManyAndHowLongAgo)
{
  EXPECT_EQ(costmap_layers_ros::receiptText(0, 0.0, 5.0), "nothing yet");
  EXPECT_EQ(costmap_layers_ros::receiptText(3, 10.0, 12.5), "3 message(s), last 2.50 s ago");
  // An arrival stamped after "now" (another thread noted it in between) reads 0, never negative.
  EXPECT_EQ(costmap_layers_ros::receiptText(1, 13.0, 12.0), "1 message(s), last 0.00 s ago");
}

TEST(PortReceipts, NoteCountsAndStampsOnTheSteadyClock)
{
  costmap_layers_ros::PortReceipts r;
  EXPECT_EQ(r.count.load(), 0u);
  EXPECT_EQ(r.last.load(), 0.0);
  const double before = ros::SteadyTime::now().toSec();
  r.note();
  r.note();
  EXPECT_EQ(r.count.load(), 2u);
  EXPECT_GE(r.last.load(), before);
}
