// The world scripts/bench_move_base_cpu.sh runs move_base in (issue 38): a robot driving a 1.5 m circle
// at 0.3 m/s in Willow Garage's map, a 720-beam LaserScan (10 m) at 40 Hz and an organised 160x125
// PointCloud2 (6 m) at 15 Hz seeing the map's walls (2.5 m high), the floor, three boxes that are not in
// the map and one that moves. Publishes tf map -> odom (fixed, as a localiser would) and odom ->
// base_link with every sensor message at that message's stamp, /odom, and the sensor mounts on
// /tf_static.
//
// The map comes from /map (latched, mask_server). Occupied cells are walls; unknown cells are walls too
// when they belong to a blob of at least ~unknown_blob_cells cells (willow's unmapped rooms), while the
// single grey specks in its halls stay transparent.
//
// Rays are traced cell by cell through the map grid (a 2-D DDA along the ray's ground track, the z of
// the ray checked where it enters a wall cell), so that a sensor message costs this process
// well under a millisecond per 1000 rays: the machine must not be busy with the world while move_base
// is measured.
//
// Parameters (~): center_x, center_y [m] the circle's centre in the map (default: a hall of willow),
// paused (bool, read twice a second): the world's clock stops (the robot and the moving box stand
// still) while messages go on with new stamps, so that two move_base instances can be compared on a
// still scene.
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <thread>
#include <vector>

namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kWallHeight = 2.5;                                // [m]
constexpr double kRadius = 1.5, kSpeed = 0.3;                      // the circle [m], the robot's speed [m/s]
constexpr double kScanPeriod = 1.0 / 40, kCloudPeriod = 1.0 / 15;  // [s]
constexpr int kBeams = 720;
constexpr double kScanRange = 10.0, kCloudRange = 6.0;  // [m]
constexpr unsigned kCloudWidth = 160, kCloudHeight = 125;
// The mounts on base_link, as in bench_sensor_path: a laser 0.1 m ahead at 0.2 m, a camera 0.15 m
// ahead at 0.45 m pitched 0.2 rad down (its frame x forward, z up), fields of view 1.0 x 0.78 rad.
constexpr double kLaser[3] = {0.1, 0.0, 0.2};
constexpr double kCamera[3] = {0.15, 0.0, 0.45};
constexpr double kCameraPitch = 0.2, kHfov = 1.0, kVfov = 0.78;
// map -> odom: where odometry started, as a localiser would publish it.
constexpr double kOdomX = 38.0, kOdomY = 30.0, kOdomYaw = 0.1;

struct Box
{
  double x0, y0, x1, y1, z1;  // in the circle's frame (its centre at 0, 0); from the floor to z1
};

struct Pose
{
  double x, y, yaw;
};

/// The map's walls as a grid of bytes (1 = wall).
struct Walls
{
  std::vector<uint8_t> solid;
  int w = 0, h = 0;
  double res = 0.1, ox = 0, oy = 0;

  bool at(int i, int j) const { return i < 0 || j < 0 || i >= w || j >= h || solid[j * w + i] != 0; }

  void build(const nav_msgs::OccupancyGrid& map, int min_blob)
  {
    w = static_cast<int>(map.info.width);
    h = static_cast<int>(map.info.height);
    res = map.info.resolution;
    ox = map.info.origin.position.x;
    oy = map.info.origin.position.y;
    solid.assign(static_cast<std::size_t>(w) * h, 0);
    for (std::size_t k = 0; k < solid.size(); ++k)
      solid[k] = map.data[k] >= 65 ? 1 : 0;
    // Unknown cells: 8-connected blobs of at least min_blob cells are walls.
    std::vector<uint8_t> seen(solid.size(), 0);
    std::vector<int> stack, blob;
    for (int start = 0; start < w * h; ++start)
    {
      if (map.data[start] != -1 || seen[start]) continue;
      blob.clear();
      stack.assign(1, start);
      seen[start] = 1;
      while (!stack.empty())
      {
        const int c = stack.back();
        stack.pop_back();
        blob.push_back(c);
        const int ci = c % w, cj = c / w;
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di)
          {
            const int ni = ci + di, nj = cj + dj;
            if (ni < 0 || nj < 0 || ni >= w || nj >= h) continue;
            const int n = nj * w + ni;
            if (map.data[n] == -1 && !seen[n])
            {
              seen[n] = 1;
              stack.push_back(n);
            }
          }
      }
      if (static_cast<int>(blob.size()) >= min_blob)
        for (int c : blob)
          solid[c] = 1;
    }
  }

  /// Distance along the unit ray (o, d) to the first wall it meets below kWallHeight, at most `limit`.
  double trace(const double o[3], const double d[3], double limit) const
  {
    const double gx = (o[0] - ox) / res, gy = (o[1] - oy) / res;
    int i = static_cast<int>(std::floor(gx)), j = static_cast<int>(std::floor(gy));
    const double inf = std::numeric_limits<double>::infinity();
    const int si = d[0] > 0 ? 1 : -1, sj = d[1] > 0 ? 1 : -1;
    // Parameter t (metres along the ray) at the next x and y cell borders, and per cell.
    const double dti = d[0] != 0 ? res / std::abs(d[0]) : inf, dtj = d[1] != 0 ? res / std::abs(d[1]) : inf;
    double ti = d[0] != 0 ? ((si > 0 ? (i + 1 - gx) : (gx - i)) * res) / std::abs(d[0]) : inf;
    double tj = d[1] != 0 ? ((sj > 0 ? (j + 1 - gy) : (gy - j)) * res) / std::abs(d[1]) : inf;
    double t = 0.0;
    if (at(i, j)) return 0.0;
    while (t < limit)
    {
      if (ti < tj)
      {
        t = ti;
        ti += dti;
        i += si;
      }
      else
      {
        t = tj;
        tj += dtj;
        j += sj;
      }
      if (t >= limit) break;
      const double z = o[2] + t * d[2];
      if (z > kWallHeight && d[2] >= 0) return inf;  // over every wall, and rising
      if (at(i, j) && z >= 0.0 && z <= kWallHeight) return t;
    }
    return inf;
  }
};

class World
{
public:
  World() : pnh_("~")
  {
    pnh_.param("center_x", cx_, 39.4);
    pnh_.param("center_y", cy_, 31.2);
    pnh_.param("unknown_blob_cells", min_blob_, 30);
    scan_pub_ = nh_.advertise<sensor_msgs::LaserScan>("scan", 5);
    cloud_pub_ = nh_.advertise<sensor_msgs::PointCloud2>("cloud", 5);
    odom_pub_ = nh_.advertise<nav_msgs::Odometry>("odom", 5);
    tf_pub_ = nh_.advertise<tf2_msgs::TFMessage>("/tf", 100);
    tf2_msgs::TFMessage mounts;
    mounts.transforms.push_back(
        transform("base_link", "laser", ros::Time::now(), kLaser[0], kLaser[1], kLaser[2], 0, 0));
    mounts.transforms.push_back(
        transform("base_link", "camera", ros::Time::now(), kCamera[0], kCamera[1], kCamera[2], kCameraPitch, 0));
    static_tf_.sendTransform(mounts.transforms);
    scan_.header.frame_id = "laser";
    scan_.angle_increment = static_cast<float>(2.0 * kPi / kBeams);
    scan_.angle_min = static_cast<float>(-kPi);
    scan_.angle_max = scan_.angle_min + (kBeams - 1) * scan_.angle_increment;
    scan_.range_min = 0.05f;
    scan_.range_max = static_cast<float>(kScanRange);
    scan_.scan_time = static_cast<float>(kScanPeriod);
    scan_.ranges.resize(kBeams);
    cloud_.header.frame_id = "camera";
    cloud_.width = kCloudWidth;
    cloud_.height = kCloudHeight;
    const char* names[4] = {"x", "y", "z", "rgb"};
    for (int k = 0; k < 4; ++k)
    {
      sensor_msgs::PointField f;
      f.name = names[k];
      f.offset = 4 * k;
      f.datatype = sensor_msgs::PointField::FLOAT32;
      f.count = 1;
      cloud_.fields.push_back(f);
    }
    cloud_.point_step = 16;
    cloud_.row_step = 16 * kCloudWidth;
    cloud_.is_dense = false;
    cloud_.data.resize(static_cast<std::size_t>(cloud_.row_step) * kCloudHeight);
    // The pixels' rays in the camera frame, once.
    for (unsigned v = 0; v < kCloudHeight; ++v)
      for (unsigned u = 0; u < kCloudWidth; ++u)
      {
        double c[3] = {1.0, -std::tan((u + 0.5 - kCloudWidth / 2.0) * kHfov / kCloudWidth),
                       -std::tan((v + 0.5 - kCloudHeight / 2.0) * kVfov / kCloudHeight)};
        const double n = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        for (double& x : c)
          pixel_rays_.push_back(x / n);
      }
  }

  void run()
  {
    const auto map = ros::topic::waitForMessage<nav_msgs::OccupancyGrid>("map", nh_);
    if (!map) return;
    walls_.build(*map, min_blob_);
    ROS_INFO("cpu_world: map %dx%d at %.3f m; circle around (%.2f, %.2f)", walls_.w, walls_.h, walls_.res, cx_, cy_);
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();
    long scans = 0, clouds = 0;
    double world_t = 0.0, last_wall = 0.0, next_param = 0.0;
    bool paused = false;
    while (ros::ok())
    {
      const double next_scan = scans * kScanPeriod, next_cloud = clouds * kCloudPeriod;
      const double next = std::min(next_scan, next_cloud);
      std::this_thread::sleep_until(start +
                                    std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(next)));
      const double wall = std::chrono::duration<double>(Clock::now() - start).count();
      if (wall >= next_param)
      {
        pnh_.getParamCached("paused", paused);
        next_param = wall + 0.5;
      }
      if (!paused) world_t += wall - last_wall;
      last_wall = wall;
      const ros::Time stamp = ros::Time::now();
      const Pose robot = robotAt(world_t);
      publishPose(robot, stamp);
      if (next_scan <= next_cloud)
      {
        publishScan(robot, world_t, stamp);
        ++scans;
      }
      else
      {
        publishCloud(robot, world_t, stamp);
        ++clouds;
      }
      ros::spinOnce();
    }
  }

private:
  Pose robotAt(double t) const
  {
    const double a = kSpeed / kRadius * t;
    return {cx_ + kRadius * std::cos(a), cy_ + kRadius * std::sin(a), a + kPi / 2};
  }

  /// The boxes in the map frame: three still, the last one going to and fro along y = 2.4 m.
  std::vector<Box> boxesAt(double t) const
  {
    const double mx = 1.8 * std::sin(0.25 * t);
    std::vector<Box> b = {{-0.2, -0.2, 0.2, 0.2, 0.5},
                          {1.75, 1.35, 2.25, 1.85, 1.0},
                          {-1.6, -2.2, -1.2, -1.8, 0.3},
                          {mx - 0.15, 2.25, mx + 0.15, 2.55, 0.6}};
    for (Box& x : b)
    {
      x.x0 += cx_;
      x.x1 += cx_;
      x.y0 += cy_;
      x.y1 += cy_;
    }
    return b;
  }

  /// Distance along the unit ray (o, d): walls, floor, boxes; inf for nothing within `limit`.
  double cast(const std::vector<Box>& boxes, const double o[3], const double d[3], double limit) const
  {
    double best = limit;
    if (d[2] < 0) best = std::min(best, -o[2] / d[2]);
    for (const Box& b : boxes)
    {
      const double lo[3] = {b.x0, b.y0, 0.0}, hi[3] = {b.x1, b.y1, b.z1};
      double t0 = 0.0, t1 = best;
      for (int a = 0; a < 3 && t0 <= t1; ++a)
      {
        if (d[a] == 0.0)
        {
          if (o[a] < lo[a] || o[a] > hi[a]) t0 = t1 + 1.0;
          continue;
        }
        double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
      }
      if (t0 <= t1 && t0 > 0) best = t0;
    }
    best = std::min(best, walls_.trace(o, d, best));
    return best < limit ? best : std::numeric_limits<double>::infinity();
  }

  static geometry_msgs::TransformStamped transform(const std::string& parent, const std::string& child,
                                                   const ros::Time& stamp, double x, double y, double z, double pitch,
                                                   double yaw)
  {
    geometry_msgs::TransformStamped t;
    t.header.frame_id = parent;
    t.header.stamp = stamp;
    t.child_frame_id = child;
    t.transform.translation.x = x;
    t.transform.translation.y = y;
    t.transform.translation.z = z;
    // yaw about z, then pitch about y
    const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2), cp = std::cos(pitch / 2), sp = std::sin(pitch / 2);
    t.transform.rotation.w = cy * cp;
    t.transform.rotation.x = -sy * sp;
    t.transform.rotation.y = cy * sp;
    t.transform.rotation.z = sy * cp;
    return t;
  }

  void publishPose(const Pose& r, const ros::Time& stamp)
  {
    // odom -> base_link: the robot's map pose seen from the odom frame.
    const double c = std::cos(kOdomYaw), s = std::sin(kOdomYaw);
    const double dx = r.x - kOdomX, dy = r.y - kOdomY;
    const double x = c * dx + s * dy, y = -s * dx + c * dy, yaw = r.yaw - kOdomYaw;
    tf2_msgs::TFMessage tf;
    tf.transforms.push_back(transform("map", "odom", stamp, kOdomX, kOdomY, 0, 0, kOdomYaw));
    tf.transforms.push_back(transform("odom", "base_link", stamp, x, y, 0, 0, yaw));
    tf_pub_.publish(tf);
    nav_msgs::Odometry odom;
    odom.header.stamp = stamp;
    odom.header.frame_id = "odom";
    odom.child_frame_id = "base_link";
    odom.pose.pose.position.x = x;
    odom.pose.pose.position.y = y;
    odom.pose.pose.orientation = tf.transforms.back().transform.rotation;
    odom.twist.twist.linear.x = kSpeed;
    odom.twist.twist.angular.z = kSpeed / kRadius;
    odom_pub_.publish(odom);
  }

  void publishScan(const Pose& r, double t, const ros::Time& stamp)
  {
    const auto boxes = boxesAt(t);
    const double o[3] = {r.x + kLaser[0] * std::cos(r.yaw), r.y + kLaser[0] * std::sin(r.yaw), kLaser[2]};
    for (int k = 0; k < kBeams; ++k)
    {
      const double a = r.yaw + scan_.angle_min + k * static_cast<double>(scan_.angle_increment);
      const double d[3] = {std::cos(a), std::sin(a), 0.0};
      scan_.ranges[k] = static_cast<float>(cast(boxes, o, d, kScanRange));
    }
    scan_.header.stamp = stamp;
    ++scan_.header.seq;
    scan_pub_.publish(scan_);
  }

  void publishCloud(const Pose& r, double t, const ros::Time& stamp)
  {
    const auto boxes = boxesAt(t);
    const double cy = std::cos(r.yaw), sy = std::sin(r.yaw), cp = std::cos(kCameraPitch), sp = std::sin(kCameraPitch);
    const double o[3] = {r.x + kCamera[0] * cy, r.y + kCamera[0] * sy, kCamera[2]};
    for (std::size_t p = 0; p < static_cast<std::size_t>(kCloudWidth) * kCloudHeight; ++p)
    {
      const double* c = &pixel_rays_[3 * p];
      const double px = cp * c[0] + sp * c[2], pz = -sp * c[0] + cp * c[2];
      const double d[3] = {cy * px - sy * c[1], sy * px + cy * c[1], pz};
      const double range = cast(boxes, o, d, kCloudRange);
      float xyz[4] = {NAN, NAN, NAN, 0.0f};
      if (std::isfinite(range))
        for (int k = 0; k < 3; ++k)
          xyz[k] = static_cast<float>(range * c[k]);
      std::memcpy(cloud_.data.data() + 16 * p, xyz, 16);
    }
    cloud_.header.stamp = stamp;
    ++cloud_.header.seq;
    cloud_pub_.publish(cloud_);
  }

  ros::NodeHandle nh_, pnh_;
  ros::Publisher scan_pub_, cloud_pub_, odom_pub_, tf_pub_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
  double cx_ = 0, cy_ = 0;
  int min_blob_ = 30;
  Walls walls_;
  sensor_msgs::LaserScan scan_;
  sensor_msgs::PointCloud2 cloud_;
  std::vector<double> pixel_rays_;
};
}  // namespace

int main(int argc, char** argv)
{
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // the script waits for the line saying the map is in
  ros::init(argc, argv, "cpu_world");
  World world;
  world.run();
  return 0;
}
