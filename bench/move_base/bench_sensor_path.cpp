// What a robot pays for its sensors, from the ROS message to the marked grid (issue 38): a 720-beam
// LaserScan (10 m) into the obstacle layer and an organised PointCloud2 (160x125 = 20k points, and
// 640x480) into the obstacle or voxel layer of a rolling 6x6 m local costmap at 0.05 m, with a
// move_base-like update (updateMap: origin, updateBounds, updateCosts) after every 4 scans (40 Hz scans,
// 10 Hz cycle) or after every cloud.
//
// This package's side goes the way costmap_node feeds a layer: dispatchReading() (the two tf look-ups,
// fromMsg(), the layer's input port: parse, project, buffer), then LayeredCostmap::updateMap. Built
// where costmap_2d is found, costmap_2d's ObstacleLayer / VoxelLayer get the same messages in the same
// process through their public laserScanCallback / pointCloud2Callback (what their tf message filter
// calls) and costmap_2d's LayeredCostmap::updateMap; both sides read the same tf buffer. Neither side's tf
// gate (ours: TfGate, costmap_2d: tf2_ros::MessageFilter) is timed. The two sides and a memcpy of the
// grid are timed in turn in every iteration, their order swapped every iteration (the machines are
// shared: compare the ratios taken side by side).
//
// Counters: *_msg_us per message, *_cycle_us per update, *_cpu_ms_per_s the CPU one second of sensor data
// costs (messages at their rate, 10 updates), ratio_* ours / costmap_2d's, lethal_agree_pct the lethal
// cells both master grids share among those either has (they must mark alike).
// The costmap_2d side needs a ROS master (its layers read their parameters from it): scripts/bench.sh
// starts one. Without a master (or without costmap_2d) only this package's side runs.
#include <benchmark/benchmark.h>
#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/buffer.h>
#include <boost/make_shared.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "../bench_stats.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/layers/obstacle_layer.hpp"
#include "costmap_layers/core/layers/voxel_layer.hpp"
#include "costmap_layers/ros/port_dispatch.hpp"
#include "fake_context.hpp"
#include "sensor_test_helpers.hpp"

#ifdef COSTMAP_LAYERS_BENCH_COSTMAP_2D
#include <costmap_2d/layered_costmap.h>
#include <costmap_2d/obstacle_layer.h>
#include <costmap_2d/voxel_layer.h>
#endif

namespace
{
namespace cl = costmap_layers;
using costmap_layers_test::B;
using costmap_layers_test::D;
using costmap_layers_test::FakeContext;
using costmap_layers_test::I;
using costmap_layers_test::paramMap;
using costmap_layers_test::S;
constexpr double kPi = 3.14159265358979323846;
constexpr unsigned kCells = 120;  // 6 m at 0.05 m
constexpr double kResolution = 0.05;
constexpr double kScanRate = 40.0, kCloudRate = 15.0, kCycleRate = 10.0;  // [Hz]
const char* const kGlobal = "odom";

// ---- The world: a room of 8 x 6 m, five boxes not in any map and one moving box (the last); the robot
// drives a 1.5 m circle at 0.3 m/s.
struct Box
{
  double x0, y0, x1, y1, z1;
};

std::vector<Box> boxesAt(double t)
{
  const double mx = -1.0 + 1.5 * std::sin(0.5 * t);
  return {{2.0, 1.0, 2.4, 1.4, 0.5}, {-2.5, -2.0, -2.0, -1.6, 1.0}, {0.5, -2.4, 1.1, -2.0, 0.3},
          {0.5, 1.8, 0.9, 2.2, 0.4}, {-2.6, 0.3, -2.3, 0.7, 0.8},   {mx - 0.15, 2.0, mx + 0.15, 2.3, 0.6}};
}

/// Distance along the unit ray (o, d) to the room's walls (2.5 m high), the floor or a box; inf for none.
double castRay(const std::vector<Box>& boxes, const double o[3], const double d[3])
{
  double best = std::numeric_limits<double>::infinity();
  const double lo[2] = {-4.0, -3.0}, hi[2] = {4.0, 3.0};
  for (int a = 0; a < 2; ++a)
  {
    if (d[a] == 0.0) continue;
    const double t = ((d[a] > 0 ? hi[a] : lo[a]) - o[a]) / d[a];
    const double z = o[2] + t * d[2];
    if (t > 0 && z >= 0.0 && z <= 2.5) best = std::min(best, t);
  }
  if (d[2] < 0) best = std::min(best, -o[2] / d[2]);
  for (const Box& b : boxes)
  {
    const double blo[3] = {b.x0, b.y0, 0.0}, bhi[3] = {b.x1, b.y1, b.z1};
    double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3 && t0 <= t1; ++a)
    {
      if (d[a] == 0.0)
      {
        if (o[a] < blo[a] || o[a] > bhi[a]) t0 = t1 + 1.0;
        continue;
      }
      double ta = (blo[a] - o[a]) / d[a], tb = (bhi[a] - o[a]) / d[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    if (t0 <= t1 && t0 > 0) best = std::min(best, t0);
  }
  return best;
}

struct RobotPose
{
  double x, y, yaw;
};

RobotPose robotAt(double t)
{
  const double a = 0.2 * t;  // 0.3 m/s on a 1.5 m circle
  return {-0.5 + 1.5 * std::cos(a), 1.5 * std::sin(a), a + kPi / 2};
}

// The mounts (static): a laser 0.1 m ahead at 0.2 m, a camera 0.15 m ahead at 0.45 m pitched 0.2 rad down.
constexpr double kLaser[3] = {0.1, 0.0, 0.2};
constexpr double kCamera[3] = {0.15, 0.0, 0.45};
constexpr double kCameraPitch = 0.2;

sensor_msgs::LaserScanPtr makeScan(double t, const ros::Time& stamp)
{
  auto m = boost::make_shared<sensor_msgs::LaserScan>();
  m->header.frame_id = "laser";
  m->header.stamp = stamp;
  m->angle_increment = static_cast<float>(2.0 * kPi / 720);
  m->angle_min = static_cast<float>(-kPi);
  m->angle_max = m->angle_min + 719 * m->angle_increment;
  m->range_min = 0.05f;
  m->range_max = 10.0f;
  m->scan_time = 1.0f / 40;
  const RobotPose r = robotAt(t);
  const auto boxes = boxesAt(t);
  const double o[3] = {r.x + kLaser[0] * std::cos(r.yaw), r.y + kLaser[0] * std::sin(r.yaw), kLaser[2]};
  m->ranges.resize(720);
  for (int k = 0; k < 720; ++k)
  {
    const double a = r.yaw + m->angle_min + k * static_cast<double>(m->angle_increment);
    const double d[3] = {std::cos(a), std::sin(a), 0.0};
    const double range = castRay(boxes, o, d);
    m->ranges[k] = range < 10.0 ? static_cast<float>(range) : std::numeric_limits<float>::infinity();
  }
  return m;
}

/// An organised depth cloud, x y z float32 plus an rgb word (point_step 16), in the camera's frame (x
/// forward, z up); pixels with no return within 6 m are NaN as a depth camera sends them.
sensor_msgs::PointCloud2Ptr makeCloud(double t, const ros::Time& stamp, unsigned width, unsigned height)
{
  auto m = boost::make_shared<sensor_msgs::PointCloud2>();
  m->header.frame_id = "camera";
  m->header.stamp = stamp;
  m->width = width;
  m->height = height;
  const char* names[4] = {"x", "y", "z", "rgb"};
  for (int k = 0; k < 4; ++k)
  {
    sensor_msgs::PointField f;
    f.name = names[k];
    f.offset = 4 * k;
    f.datatype = sensor_msgs::PointField::FLOAT32;
    f.count = 1;
    m->fields.push_back(f);
  }
  m->point_step = 16;
  m->row_step = 16 * width;
  m->is_dense = false;
  m->data.resize(static_cast<std::size_t>(m->row_step) * height);
  const RobotPose r = robotAt(t);
  const auto boxes = boxesAt(t);
  const double cy = std::cos(r.yaw), sy = std::sin(r.yaw), cp = std::cos(kCameraPitch), sp = std::sin(kCameraPitch);
  const double o[3] = {r.x + kCamera[0] * cy, r.y + kCamera[0] * sy, kCamera[2]};
  const double hfov = 1.0, vfov = 0.78;
  for (unsigned v = 0; v < height; ++v)
    for (unsigned u = 0; u < width; ++u)
    {
      // The pixel's ray in the camera frame, then pitched down and turned to the robot's heading.
      double c[3] = {1.0, -std::tan((u + 0.5 - width / 2.0) * hfov / width),
                     -std::tan((v + 0.5 - height / 2.0) * vfov / height)};
      const double n = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
      for (double& x : c)
        x /= n;
      const double px = cp * c[0] + sp * c[2], pz = -sp * c[0] + cp * c[2];
      const double d[3] = {cy * px - sy * c[1], sy * px + cy * c[1], pz};
      const double range = castRay(boxes, o, d);
      float xyz[4] = {NAN, NAN, NAN, 0.0f};
      if (range < 6.0)
        for (int k = 0; k < 3; ++k)
          xyz[k] = static_cast<float>(range * c[k]);
      std::memcpy(m->data.data() + static_cast<std::size_t>(v) * m->row_step + 16 * u, xyz, 16);
    }
  return m;
}

geometry_msgs::TransformStamped transformMsg(const std::string& parent, const std::string& child,
                                             const ros::Time& stamp, double x, double y, double z, double roll_pitch,
                                             double yaw)
{
  geometry_msgs::TransformStamped t;
  t.header.frame_id = parent;
  t.header.stamp = stamp;
  t.child_frame_id = child;
  t.transform.translation.x = x;
  t.transform.translation.y = y;
  t.transform.translation.z = z;
  // yaw about z then pitch about y (only one of them is non-zero here)
  const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2), cp = std::cos(roll_pitch / 2),
               sp = std::sin(roll_pitch / 2);
  t.transform.rotation.w = cy * cp;
  t.transform.rotation.x = -sy * sp;
  t.transform.rotation.y = cy * sp;
  t.transform.rotation.z = sy * cp;
  return t;
}

/// The tf tree both sides read: odom -> base_link moving with the robot (set at every message's stamp),
/// base_link -> laser and base_link -> camera static.
struct World
{
  tf2_ros::Buffer tf{ros::Duration(10.0)};
  ros::Time t0{1000, 0};
  World()
  {
    // costmap_2d's ObservationBuffer looks transforms up with a timeout; everything is in tf beforehand.
    tf.setUsingDedicatedThread(true);
    tf.setTransform(transformMsg("base_link", "laser", t0, kLaser[0], kLaser[1], kLaser[2], 0, 0), "bench", true);
    tf.setTransform(transformMsg("base_link", "camera", t0, kCamera[0], kCamera[1], kCamera[2], kCameraPitch, 0),
                    "bench", true);
  }
  /// The robot's pose at `recorded` [s] (when the message was recorded) into tf at time t [s] after t0;
  /// returns the stamp. A replay that starts over makes the robot jump back to its first pose.
  ros::Time at(double t, double recorded)
  {
    const ros::Time stamp = t0 + ros::Duration(t);
    const RobotPose r = robotAt(recorded);
    tf.setTransform(transformMsg(kGlobal, "base_link", stamp, r.x, r.y, 0, 0, r.yaw), "bench", false);
    return stamp;
  }
};

const cl::Footprint kFootprint = {{-0.22, -0.22}, {0.22, -0.22}, {0.22, 0.22}, {-0.22, 0.22}};

// ---- This package's side, as costmap_node runs it.
cl::ParamValue sourceParams(bool scan)
{
  cl::ParamValue s = paramMap({{"topic", S(scan ? "scan" : "cloud")},
                               {"data_type", S(scan ? "LaserScan" : "PointCloud2")},
                               {"clearing", B(true)},
                               {"marking", B(true)},
                               {"obstacle_range", D(2.5)},
                               {"raytrace_range", D(3.0)},
                               {"min_obstacle_height", D(scan ? 0.0 : 0.05)},
                               {"max_obstacle_height", D(2.0)}});
  return s;
}

struct Ours
{
  cl::LayeredCostmap lc{kGlobal, true, false};
  std::shared_ptr<FakeContext> ctx;
  std::shared_ptr<cl::ObstacleLayer> layer;
  costmap_layers_ros::PortSource src{"/bench_sensor_path/ours", "sensor",
                                     std::make_shared<costmap_layers_ros::ThrottledLog>()};

  Ours(bool scan, bool voxel)
  {
    lc.resizeMap(kCells, kCells, kResolution, 0, 0);
    cl::ParamValue p = paramMap({{"observation_sources", S(scan ? "scan" : "cloud")}});
    if (voxel)
    {
      p.set("z_voxels", I(16));
      p.set("z_resolution", D(0.1));
      p.set("origin_z", D(0.0));
      p.set("unknown_threshold", I(15));
      p.set("mark_threshold", I(0));
    }
    p.set(scan ? "scan" : "cloud", sourceParams(scan));
    ctx = std::make_shared<FakeContext>(p, kGlobal);
    layer = voxel ? std::make_shared<cl::VoxelLayer>() : std::make_shared<cl::ObstacleLayer>();
    layer->initialize(&lc, "obstacles", ctx);
    lc.addPlugin(layer);
    lc.setFootprint(kFootprint);
  }
  /// As LayerPorts hands a received message on (past its tf gate).
  template <class Ptr>
  void deliver(const Ptr& msg, tf2::BufferCore& tf)
  {
    ctx->now_ns = msg->header.stamp.toNSec();
    const cl::InputPort& in = layer->inputs().front();
    if constexpr (std::is_same_v<Ptr, sensor_msgs::LaserScanConstPtr>)
      costmap_layers_ros::dispatchReading(msg, tf, kGlobal, "", in.on_scan, src);
    else
      costmap_layers_ros::dispatchReading(msg, tf, kGlobal, "", in.on_cloud, src);
  }
  void update(const RobotPose& r) { lc.updateMap(r.x, r.y, r.yaw); }
  const uint8_t* grid() const { return lc.getCostmap().data(); }
  double originX() const { return lc.getCostmap().getOriginX(); }
  double originY() const { return lc.getCostmap().getOriginY(); }
};

// ---- costmap_2d's side, in the same process.
#ifdef COSTMAP_LAYERS_BENCH_COSTMAP_2D
/// The buffers a layer made for its sources (what its message filters hand to the callbacks).
template <class Base>
struct Exposed : Base
{
  const boost::shared_ptr<costmap_2d::ObservationBuffer>& buffer() const { return this->observation_buffers_.front(); }
};

struct Theirs
{
  costmap_2d::LayeredCostmap lc{kGlobal, true, false};
  boost::shared_ptr<costmap_2d::ObstacleLayer> layer;
  boost::shared_ptr<costmap_2d::ObservationBuffer> buffer;

  Theirs(tf2_ros::Buffer& tf, bool scan, bool voxel, const std::string& name)
  {
    lc.resizeMap(kCells, kCells, kResolution, 0, 0);
    ros::NodeHandle nh("~/" + name);
    const std::string source = scan ? "scan" : "cloud";
    nh.setParam("observation_sources", source);
    // A topic nobody publishes: the messages come through the callbacks only.
    nh.setParam(source + "/topic", "/bench_sensor_path/unused_" + name);
    nh.setParam(source + "/data_type", scan ? "LaserScan" : "PointCloud2");
    nh.setParam(source + "/clearing", true);
    nh.setParam(source + "/marking", true);
    nh.setParam(source + "/obstacle_range", 2.5);
    nh.setParam(source + "/raytrace_range", 3.0);
    nh.setParam(source + "/min_obstacle_height", scan ? 0.0 : 0.05);
    nh.setParam(source + "/max_obstacle_height", 2.0);
    nh.setParam("max_obstacle_height", 2.0);
    if (voxel)
    {
      nh.setParam("z_voxels", 16);
      nh.setParam("z_resolution", 0.1);
      nh.setParam("origin_z", 0.0);
      nh.setParam("unknown_threshold", 15);
      nh.setParam("mark_threshold", 0);
      auto l = boost::make_shared<Exposed<costmap_2d::VoxelLayer>>();
      l->initialize(&lc, name, &tf);
      buffer = l->buffer();
      layer = l;
    }
    else
    {
      auto l = boost::make_shared<Exposed<costmap_2d::ObstacleLayer>>();
      l->initialize(&lc, name, &tf);
      buffer = l->buffer();
      layer = l;
    }
    lc.addPlugin(layer);
    std::vector<geometry_msgs::Point> fp;
    for (const auto& v : kFootprint)
    {
      geometry_msgs::Point p;
      p.x = v.x();
      p.y = v.y();
      fp.push_back(p);
    }
    lc.setFootprint(fp);
  }
  void deliver(const sensor_msgs::LaserScanConstPtr& msg) { layer->laserScanCallback(msg, buffer); }
  void deliver(const sensor_msgs::PointCloud2ConstPtr& msg) { layer->pointCloud2Callback(msg, buffer); }
  void update(const RobotPose& r) { lc.updateMap(r.x, r.y, r.yaw); }
  const uint8_t* grid() { return lc.getCostmap()->getCharMap(); }
  double originX() { return lc.getCostmap()->getOriginX(); }
  double originY() { return lc.getCostmap()->getOriginY(); }
};
bool g_with_costmap_2d = false;
#endif

using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

/// Time sums of one side over a benchmark run.
struct Tally
{
  double msg = 0, update = 0;
};

/// Messages made before the timing, and when on the circle each was recorded [s].
template <class Ptr>
struct Recording
{
  std::vector<Ptr> messages;
  std::vector<double> times;
};

template <class Side, class Ptr>
void deliverTimed(Side& side, const Ptr& msg, tf2::BufferCore& tf, double& sum)
{
  const auto a = Clock::now();
  if constexpr (std::is_same_v<Side, Ours>)
    side.deliver(msg, tf);
  else
    side.deliver(msg);
  benchmark::ClobberMemory();
  sum += seconds(a, Clock::now());
}

template <class Side>
void updateTimed(Side& side, const RobotPose& r, double& sum)
{
  const auto a = Clock::now();
  side.update(r);
  benchmark::ClobberMemory();
  sum += seconds(a, Clock::now());
}

/// Runs the messages (`per_cycle` of them, then one update) through both sides, side by side.
template <class Ptr>
void runPath(benchmark::State& state, const std::vector<Ptr>& messages, const std::vector<double>& times,
             double message_rate, int per_cycle, bool scan, bool voxel)
{
  World world;
  Ours ours(scan, voxel);
#ifdef COSTMAP_LAYERS_BENCH_COSTMAP_2D
  static int instance = 0;
  std::unique_ptr<Theirs> theirs;
  if (g_with_costmap_2d) theirs = std::make_unique<Theirs>(world.tf, scan, voxel, "c2d_" + std::to_string(instance++));
#endif
  std::vector<uint8_t> from(kCells * kCells, 1), to(from.size(), 2);
  Tally a, b;
  double t_memcpy = 0;
  std::size_t next = 0;
  double t = 0.0, last = 0.0;
  for (auto _ : state)
  {
    const double before = a.msg + a.update;
    for (int k = 0; k < per_cycle; ++k)
    {
      // The recorded message, restamped to now and placed in tf (not timed: manual time).
      t += 1.0 / message_rate;
      const std::size_t i = next++ % messages.size();
      messages[i]->header.stamp = world.at(t, times[i]);
      last = times[i];
      const bool ours_first = (next & 1) == 0;
      const typename Ptr::element_type::ConstPtr msg = messages[i];
      if (ours_first) deliverTimed(ours, msg, world.tf, a.msg);
#ifdef COSTMAP_LAYERS_BENCH_COSTMAP_2D
      if (theirs) deliverTimed(*theirs, msg, world.tf, b.msg);
#endif
      if (!ours_first) deliverTimed(ours, msg, world.tf, a.msg);
    }
    const RobotPose r = robotAt(last);
    updateTimed(ours, r, a.update);
#ifdef COSTMAP_LAYERS_BENCH_COSTMAP_2D
    if (theirs) updateTimed(*theirs, r, b.update);
#endif
    const auto m0 = Clock::now();
    std::memcpy(to.data(), from.data(), to.size());
    benchmark::DoNotOptimize(to.data());
    benchmark::ClobberMemory();
    t_memcpy += seconds(m0, Clock::now());
    state.SetIterationTime(a.msg + a.update - before);
  }
  const double n = static_cast<double>(state.iterations());
  const double msgs = n * per_cycle;
  state.counters["ours_msg_us"] = a.msg / msgs * 1e6;
  state.counters["ours_cycle_us"] = a.update / n * 1e6;
  const double ours_cpu = (a.msg / msgs * message_rate + a.update / n * kCycleRate) * 1e3;
  state.counters["ours_cpu_ms_per_s"] = ours_cpu;
  state.counters["memcpy_us"] = t_memcpy / n * 1e6;
  state.counters["ours_msg_x_memcpy"] = (a.msg / msgs) / (t_memcpy / n);
  int lethal_ours = 0;
  for (std::size_t k = 0; k < kCells * kCells; ++k)
    lethal_ours += ours.grid()[k] == cl::LETHAL_OBSTACLE;
  state.counters["ours_lethal"] = lethal_ours;
  if (lethal_ours == 0) state.SkipWithError("this package's layer marked nothing");
#ifdef COSTMAP_LAYERS_BENCH_COSTMAP_2D
  if (theirs)
  {
    state.counters["c2d_msg_us"] = b.msg / msgs * 1e6;
    state.counters["c2d_cycle_us"] = b.update / n * 1e6;
    const double c2d_cpu = (b.msg / msgs * message_rate + b.update / n * kCycleRate) * 1e3;
    state.counters["c2d_cpu_ms_per_s"] = c2d_cpu;
    state.counters["ratio_msg"] = a.msg / b.msg;
    state.counters["ratio_cycle"] = a.update / b.update;
    state.counters["ratio_cpu"] = ours_cpu / c2d_cpu;
    // costmap_2d's window is half a cell shorter (its getSizeInMetersX()): the origins may lie a cell
    // apart. Compared where the two windows overlap, cell by world cell.
    const long dx = std::lround((ours.originX() - theirs->originX()) / kResolution);
    const long dy = std::lround((ours.originY() - theirs->originY()) / kResolution);
    int both = 0, either = 0;
    for (long j = 0; j < static_cast<long>(kCells); ++j)
      for (long i = 0; i < static_cast<long>(kCells); ++i)
      {
        const long ti = i + dx, tj = j + dy;
        if (ti < 0 || tj < 0 || ti >= static_cast<long>(kCells) || tj >= static_cast<long>(kCells)) continue;
        const bool x = ours.grid()[j * kCells + i] == cl::LETHAL_OBSTACLE;
        const bool y = theirs->grid()[tj * kCells + ti] == cl::LETHAL_OBSTACLE;
        both += x && y;
        either += x || y;
      }
    state.counters["lethal_agree_pct"] = either > 0 ? 100.0 * both / either : -1.0;
  }
#endif
}

Recording<sensor_msgs::LaserScanPtr> recordScans()
{
  Recording<sensor_msgs::LaserScanPtr> r;
  for (int k = 0; k < 400; ++k)  // 10 s of the circle at 40 Hz
  {
    r.times.push_back(k / kScanRate);
    r.messages.push_back(makeScan(r.times.back(), ros::Time(0)));
  }
  return r;
}

/// `count` clouds spread over 10 s of the circle (a replay at 15 Hz skips between them).
Recording<sensor_msgs::PointCloud2Ptr> recordClouds(unsigned w, unsigned h, int count)
{
  Recording<sensor_msgs::PointCloud2Ptr> r;
  for (int k = 0; k < count; ++k)
  {
    r.times.push_back(10.0 * k / count);
    r.messages.push_back(makeCloud(r.times.back(), ros::Time(0), w, h));
  }
  return r;
}

/// A 720-beam scan at 40 Hz into the obstacle layer, an update every 4 scans (10 Hz).
void BM_ScanToObstacleLayer(benchmark::State& state)
{
  static const auto scans = recordScans();
  runPath(state, scans.messages, scans.times, kScanRate, 4, true, false);
  state.SetLabel("720-beam LaserScan, 40 Hz, update 10 Hz");
}
COSTMAP_BENCH(BM_ScanToObstacleLayer)->UseManualTime()->Unit(benchmark::kMicrosecond);

/// An organised cloud at 15 Hz, an update after each (arg 0: 160x125 = 20k points, 1: 640x480; arg 1:
/// obstacle layer 0, voxel layer 1).
void BM_CloudToLayer(benchmark::State& state)
{
  const bool big = state.range(0) == 1, voxel = state.range(1) == 1;
  static const auto small_clouds = recordClouds(160, 125, 64);
  static const auto big_clouds = recordClouds(640, 480, 8);
  const auto& clouds = big ? big_clouds : small_clouds;
  runPath(state, clouds.messages, clouds.times, kCloudRate, 1, false, voxel);
  state.SetLabel(std::string(big ? "640x480" : "160x125") + " PointCloud2, 15 Hz, " +
                 (voxel ? "voxel layer" : "obstacle layer"));
}
COSTMAP_BENCH(BM_CloudToLayer)
    ->Args({0, 0})
    ->Args({0, 1})
    ->Args({1, 0})
    ->Args({1, 1})
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "bench_sensor_path", ros::init_options::AnonymousName | ros::init_options::NoSigintHandler);
#ifdef COSTMAP_LAYERS_BENCH_COSTMAP_2D
  g_with_costmap_2d = ros::master::check();
  if (!g_with_costmap_2d)
    std::fprintf(stderr,
                 "bench_sensor_path: no ROS master at %s: this package's side only (scripts/bench.sh starts one)\n",
                 ros::master::getURI().c_str());
  else
    ros::start();
#else
  std::fprintf(stderr, "bench_sensor_path: built without costmap_2d: this package's side only\n");
#endif
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
