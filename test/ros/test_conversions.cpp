// The ROS adapter's conversions without a master: messages to core data and back, quaternions to a
// planar yaw (the checks of every pose read from a message), XmlRpc parameter trees.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include "costmap_layers/core/grid/costmap_2d.hpp"
#include "costmap_layers/core/layers/sensor_parsing.hpp"
#include "costmap_layers/ros/conversions.hpp"
#include "sensor_test_helpers.hpp"

using namespace costmap_layers_ros;

namespace
{
geometry_msgs::Quaternion quat(double x, double y, double z, double w)
{
  geometry_msgs::Quaternion q;
  q.x = x, q.y = y, q.z = z, q.w = w;
  return q;
}

/// The message text of the std::invalid_argument fn throws ("" when it throws nothing).
template <class Fn>
std::string thrown(Fn fn)
{
  return costmap_layers_test::thrownMessage<std::invalid_argument>(fn);
}

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();
}  // namespace

TEST(PlanarYaw, UnitQuaternionsAboutZ)
{
  for (double yaw : {0.0, 0.3, -1.2, M_PI / 2, 3.0, -3.0})
  {
    bool normalised = true;
    EXPECT_NEAR(planarYaw(quat(0, 0, std::sin(yaw / 2), std::cos(yaw / 2)), kMaxGridTilt, "q", &normalised), yaw,
                1e-12);
    EXPECT_FALSE(normalised);
  }
}

// The outside attack: (0, 0, 1, 1) was placed at 116.6 degrees; normalised it is 90.
TEST(PlanarYaw, NonUnitQuaternionsAreNormalised)
{
  bool normalised = false;
  EXPECT_NEAR(planarYaw(quat(0, 0, 1, 1), kMaxGridTilt, "q", &normalised), M_PI / 2, 1e-12);
  EXPECT_TRUE(normalised);
  EXPECT_NEAR(planarYaw(quat(0, 0, 0, 7), kMaxGridTilt, "q", &normalised), 0.0, 1e-12);
  EXPECT_TRUE(normalised);
  EXPECT_NEAR(planarYaw(quat(0, 0, -1e-3, 1e-3), kMaxGridTilt, "q"), -M_PI / 2, 1e-9);
}

TEST(PlanarYaw, UnusableQuaternionsAreRefusedNamingTheField)
{
  const std::string zero = thrown([] { planarYaw(quat(0, 0, 0, 0), kMaxGridTilt, "info.origin.orientation"); });
  EXPECT_NE(zero.find("info.origin.orientation (0, 0, 0, 0)"), std::string::npos) << zero;
  EXPECT_NE(zero.find("zero length"), std::string::npos) << zero;
  EXPECT_NE(thrown([] { planarYaw(quat(0, 0, 1e-9, 0), kMaxGridTilt, "q"); }).find("zero length"), std::string::npos);
  for (double bad : {kNaN, kInf, -kInf})
  {
    for (int k = 0; k < 4; ++k)
    {
      double c[4] = {0, 0, 0, 1};
      c[k] = bad;
      const std::string e = thrown([&] { planarYaw(quat(c[0], c[1], c[2], c[3]), kMaxGridTilt, "q"); });
      EXPECT_NE(e.find("not finite"), std::string::npos) << k << ": " << e;
    }
  }
}

TEST(PlanarYaw, TiltBeyondTheLimitIsRefused)
{
  // A roll of r about x: (sin(r/2), 0, 0, cos(r/2)); the tilt of the plane is r.
  const auto roll = [](double r) { return quat(std::sin(r / 2), 0, 0, std::cos(r / 2)); };
  const auto pitch = [](double p) { return quat(0, std::sin(p / 2), 0, std::cos(p / 2)); };
  EXPECT_NO_THROW(planarYaw(roll(0.005), kMaxGridTilt, "q"));
  EXPECT_NE(thrown([&] { planarYaw(roll(0.02), kMaxGridTilt, "q"); }).find("tilts the plane"), std::string::npos);
  EXPECT_NE(thrown([&] { planarYaw(pitch(-0.02), kMaxGridTilt, "q"); }).find("tilts the plane"), std::string::npos);
  // A robot on a 30 degree ramp is a pose; on its side it is not.
  EXPECT_NEAR(planarYaw(pitch(M_PI / 6), kMaxPoseTilt, "q"), 0.0, 1e-12);
  EXPECT_NE(thrown([&] { planarYaw(roll(M_PI / 2), kMaxPoseTilt, "q"); }).find("tilts the plane"), std::string::npos);
  // Upside down (a rotation of pi about x): a tilt of pi.
  EXPECT_NE(thrown([] { planarYaw(quat(1, 0, 0, 0), kMaxPoseTilt, "q"); }).find("tilts"), std::string::npos);
}

TEST(Conversions, GridOriginFromItsQuaternion)
{
  nav_msgs::OccupancyGrid m;
  m.header.frame_id = "map";
  m.header.stamp = ros::Time(12, 5);
  m.info.width = 2;
  m.info.height = 1;
  m.info.resolution = 0.25f;
  m.info.origin.position.x = -3.0;
  m.info.origin.position.y = 4.5;
  m.info.origin.orientation = quat(0, 0, 1, 1);
  m.data = {-1, 100};
  std::string note;
  const auto g = fromMsg(m, &note);
  EXPECT_EQ(g.frame_id, "map");
  EXPECT_EQ(g.stamp_ns, 12'000'000'005ull);
  EXPECT_EQ(g.width, 2u);
  EXPECT_EQ(g.height, 1u);
  EXPECT_DOUBLE_EQ(g.resolution, 0.25);
  EXPECT_DOUBLE_EQ(g.origin_x, -3.0);
  EXPECT_DOUBLE_EQ(g.origin_y, 4.5);
  EXPECT_NEAR(g.origin_yaw, M_PI / 2, 1e-12);
  EXPECT_EQ(g.data, (std::vector<int8_t>{-1, 100}));
  EXPECT_NE(note.find("normalised"), std::string::npos) << note;
  m.info.origin.orientation = quat(0, 0, 0, 0);
  EXPECT_NE(thrown([&] { fromMsg(m); }).find("info.origin.orientation"), std::string::npos);
  m.info.origin.orientation = quat(0, 0, 0, 1);
  note.clear();
  fromMsg(m, &note);
  EXPECT_EQ(note, "");
}

TEST(Conversions, SensorTransformsAreCheckedToo)
{
  geometry_msgs::Transform t;
  t.rotation = quat(0, 0, 0, 2);
  t.translation.x = 1.0;
  EXPECT_NO_THROW(fromMsg(t));
  t.rotation = quat(0, 0, 0, 0);
  EXPECT_THROW(fromMsg(t), std::invalid_argument);
  t.rotation = quat(0, 0, 0, 1);
  t.translation.y = kNaN;
  EXPECT_THROW(fromMsg(t), std::invalid_argument);
}

// Costs out as costmap_2d publishes them, and update windows that never leave the grid.
TEST(Conversions, CostmapToMessages)
{
  costmap_layers::Costmap2D grid(4, 3, 0.5, 1.0, -2.0);
  const uint8_t costs[5] = {0, 1, 253, 254, 255};
  const int8_t expected[5] = {0, 1, 99, 100, -1};
  for (int k = 0; k < 5; ++k)
    grid.setCost(static_cast<unsigned>(k % 4), static_cast<unsigned>(k / 4), costs[k]);
  nav_msgs::OccupancyGrid m;
  toOccupancyGrid(grid, "odom", ros::Time(3), m);
  EXPECT_EQ(m.header.frame_id, "odom");
  EXPECT_EQ(m.info.width, 4u);
  EXPECT_EQ(m.info.height, 3u);
  EXPECT_FLOAT_EQ(m.info.resolution, 0.5f);
  EXPECT_DOUBLE_EQ(m.info.origin.position.x, 1.0);
  EXPECT_DOUBLE_EQ(m.info.origin.position.y, -2.0);
  ASSERT_EQ(m.data.size(), 12u);
  for (int k = 0; k < 5; ++k)
    EXPECT_EQ(m.data[static_cast<size_t>(k)], expected[k]) << k;
  // The round trip through fromMsg keeps the geometry.
  const auto back = fromMsg(m);
  EXPECT_EQ(back.width, 4u);
  EXPECT_DOUBLE_EQ(back.origin_yaw, 0.0);

  map_msgs::OccupancyGridUpdate u;
  ASSERT_TRUE(toOccupancyGridUpdate(grid, costmap_layers::CellWindow{-5, 1, 100, 100}, "odom", ros::Time(3), u));
  EXPECT_EQ(u.x, 0);
  EXPECT_EQ(u.y, 1);
  EXPECT_EQ(u.width, 4u);
  EXPECT_EQ(u.height, 2u);
  ASSERT_EQ(u.data.size(), 8u);
  EXPECT_EQ(u.data[0], -1);  // cell (0, 1) holds the fifth cost, 255
  EXPECT_FALSE(toOccupancyGridUpdate(grid, costmap_layers::CellWindow{4, 0, 9, 3}, "odom", ros::Time(3), u));
}

TEST(Conversions, XmlRpcTrees)
{
  XmlRpc::XmlRpcValue v;
  v["radius"] = 0.5;
  v["count"] = 3;
  v["on"] = true;
  v["name"] = std::string("keepout");
  v["list"][0] = 1;
  v["list"][1] = std::string("two");
  v["nested"]["deeper"]["x"] = -1.5;
  const costmap_layers::ParamValue p = fromXmlRpc(v);
  ASSERT_TRUE(p.isMap());
  EXPECT_DOUBLE_EQ(p.find("radius")->asDouble(), 0.5);
  EXPECT_EQ(p.find("count")->asInt(), 3);
  EXPECT_TRUE(p.find("on")->asBool());
  EXPECT_EQ(p.find("name")->asString(), "keepout");
  ASSERT_TRUE(p.find("list")->isList());
  ASSERT_EQ(p.find("list")->asList().size(), 2u);
  EXPECT_EQ(p.find("list")->asList()[1].asString(), "two");
  EXPECT_DOUBLE_EQ(p.find("nested")->find("deeper")->find("x")->asDouble(), -1.5);
}

// Property: for random rotations about z, scaled by any positive length, planarYaw gives the heading of
// the rotated x axis (computed here from the rotation matrix, not with tf2); random tilts beyond the
// limit are refused.
TEST(PlanarYaw, RandomQuaternionsAgreeWithTheRotatedXAxis)
{
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), scale(1e-3, 1e3), small(-0.004, 0.004);
  for (int k = 0; k < 2000; ++k)
  {
    const double yaw = angle(rng), roll = small(rng), pitch = small(rng), n = scale(rng);
    // q = Rz(yaw) Ry(pitch) Rx(roll)
    const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2), cp = std::cos(pitch / 2), sp = std::sin(pitch / 2),
                 cr = std::cos(roll / 2), sr = std::sin(roll / 2);
    const double w = cy * cp * cr + sy * sp * sr, x = cy * cp * sr - sy * sp * cr, y = cy * sp * cr + sy * cp * sr,
                 z = sy * cp * cr - cy * sp * sr;
    // The rotated x axis: first column of the rotation matrix.
    const double r00 = 1 - 2 * (y * y + z * z), r10 = 2 * (x * y + w * z);
    const double expected = std::atan2(r10, r00);
    const double got = planarYaw(quat(n * x, n * y, n * z, n * w), kMaxGridTilt, "q");
    EXPECT_NEAR(std::remainder(got - expected, 2 * M_PI), 0.0, 1e-9) << k;
  }
  for (int k = 0; k < 200; ++k)
  {
    const double tilt = 0.02 + 1.0 * std::abs(small(rng)) * 100, yaw = angle(rng);
    const double axis = angle(rng);  // a horizontal axis at this heading
    const double s = std::sin(tilt / 2);
    const double ax = std::cos(axis) * s, ay = std::sin(axis) * s;
    // A tilt about a horizontal axis, then a yaw: the plane is tilted by `tilt`.
    const double cz = std::cos(yaw / 2), sz = std::sin(yaw / 2), ct = std::cos(tilt / 2);
    const double w = cz * ct, x = cz * ax - sz * ay, y = cz * ay + sz * ax, z = sz * ct;
    EXPECT_THROW(planarYaw(quat(x, y, z, w), kMaxGridTilt, "q"), std::invalid_argument) << k;
  }
}

// sensor_msgs/PointCloud (costmap_2d's default data_type) becomes a PointCloud2 of x, y, z that the
// core's cloud parser reads back point for point; NaN points stay for the parser to skip, and an
// empty cloud is a valid empty one.
TEST(Conversions, OlderPointCloudReadsAsItsPoints)
{
  sensor_msgs::PointCloud msg;
  msg.header.frame_id = "camera";
  msg.header.stamp = ros::Time(12, 345);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float xyz[][3] = {{1.0f, 2.0f, 0.5f}, {-3.25f, 1e-3f, 7.0f}, {nan, 0.0f, 0.0f}, {4e6f, -4e6f, 2.0f}};
  for (const auto& p : xyz)
  {
    geometry_msgs::Point32 q;
    q.x = p[0];
    q.y = p[1];
    q.z = p[2];
    msg.points.push_back(q);
  }
  sensor_msgs::ChannelFloat32 intensity;  // channels are left out
  intensity.name = "intensity";
  intensity.values.assign(4, 1.0f);
  msg.channels.push_back(intensity);
  const costmap_layers::PointCloud2Data cloud = costmap_layers_ros::fromMsg(msg);
  EXPECT_EQ(cloud.frame_id, "camera");
  EXPECT_EQ(cloud.stamp_ns, 12'000'000'345u);
  EXPECT_EQ(costmap_layers::validatePointCloud2(cloud), "");
  std::vector<costmap_layers::Point3f> points;
  const costmap_layers::ParseResult r = costmap_layers::pointCloud2ToPoints(cloud, points);
  ASSERT_EQ(points.size(), 3u) << "the NaN point is skipped";
  EXPECT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.dropped, 1u);
  const int kept[] = {0, 1, 3};
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_EQ(points[k].x, xyz[kept[k]][0]);
    EXPECT_EQ(points[k].y, xyz[kept[k]][1]);
    EXPECT_EQ(points[k].z, xyz[kept[k]][2]);
  }
  const costmap_layers::PointCloud2Data empty = costmap_layers_ros::fromMsg(sensor_msgs::PointCloud());
  EXPECT_EQ(costmap_layers::validatePointCloud2(empty), "");
  points.clear();
  costmap_layers::pointCloud2ToPoints(empty, points);
  EXPECT_TRUE(points.empty());
}

// The worst a sender can put in a nav_msgs/Path: far more poses than a path may have. The conversion
// copies no more than the core needs to refuse it, and the refusal names the message's true count.
TEST(Conversions, AHugePathIsCutBeforeTheCopyAndRefusedByItsTrueSize)
{
  nav_msgs::Path msg;
  msg.header.frame_id = "map";
  const std::size_t limit = costmap_layers::limits::kMaxPathPoses;
  msg.poses.resize(limit + 1000);
  const costmap_layers::PathData d = costmap_layers_ros::fromMsg(msg);
  EXPECT_EQ(d.poses.size(), limit + 1);
  EXPECT_EQ(d.message_poses, limit + 1000);
  const costmap_layers::InputError e = costmap_layers::validatePath(d);
  ASSERT_FALSE(e.ok());
  EXPECT_EQ(e.field, "poses");
  EXPECT_NE(e.message.find(std::to_string(limit + 1000)), std::string::npos) << e.message;
  // At the limit: copied whole and accepted.
  msg.poses.resize(limit);
  const costmap_layers::PathData at = costmap_layers_ros::fromMsg(msg);
  EXPECT_EQ(at.poses.size(), limit);
  EXPECT_TRUE(costmap_layers::validatePath(at).ok());
}
