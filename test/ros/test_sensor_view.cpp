// A received PointCloud2 reaches the layer without its points being copied (issue 38): fromMsg() of the
// message pointer borrows the message's bytes and keeps the message alive, and reads as the copy does.
#include <gtest/gtest.h>

#include <boost/make_shared.hpp>

#include <cstring>
#include <vector>

#include "costmap_layers/core/layers/sensor_parsing.hpp"
#include "costmap_layers/ros/conversions.hpp"

namespace
{
sensor_msgs::PointCloud2Ptr cloudOf(const std::vector<float>& xyz)
{
  auto m = boost::make_shared<sensor_msgs::PointCloud2>();
  m->header.frame_id = "camera";
  m->height = 1;
  m->width = static_cast<uint32_t>(xyz.size() / 3);
  for (const char* name : {"x", "y", "z"})
  {
    sensor_msgs::PointField f;
    f.name = name;
    f.offset = static_cast<uint32_t>(4 * m->fields.size());
    f.datatype = sensor_msgs::PointField::FLOAT32;
    f.count = 1;
    m->fields.push_back(f);
  }
  m->point_step = 12;
  m->row_step = 12 * m->width;
  m->data.resize(4 * xyz.size());
  std::memcpy(m->data.data(), xyz.data(), m->data.size());
  return m;
}

TEST(SensorView, AReceivedCloudIsBorrowedAndKeptAlive)
{
  sensor_msgs::PointCloud2Ptr msg = cloudOf({1.0f, 2.0f, 3.0f, NAN, 0.0f, 0.0f, -4.5f, 0.25f, 8.0f});
  const uint8_t* bytes = msg->data.data();
  costmap_layers::PointCloud2Data view = costmap_layers_ros::fromMsg(sensor_msgs::PointCloud2ConstPtr(msg));
  msg.reset();  // the reading alone keeps the message now
  EXPECT_TRUE(view.data.empty());
  EXPECT_EQ(view.bytes(), bytes);
  EXPECT_EQ(view.byteCount(), 36u);
  EXPECT_EQ(view.frame_id, "camera");
  std::vector<costmap_layers::Point3f> points;
  const costmap_layers::ParseResult r = costmap_layers::pointCloud2ToPoints(view, points);
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.dropped, 1u);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0].x, 1.0f);
  EXPECT_EQ(points[0].y, 2.0f);
  EXPECT_EQ(points[0].z, 3.0f);
  EXPECT_EQ(points[1].x, -4.5f);
  EXPECT_EQ(points[1].y, 0.25f);
  EXPECT_EQ(points[1].z, 8.0f);
}

TEST(SensorView, AShortBorrowedCloudIsRefusedAsACopiedOne)
{
  sensor_msgs::PointCloud2Ptr msg = cloudOf({1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f});
  msg->data.resize(23);  // one byte short of two points
  const costmap_layers::PointCloud2Data view = costmap_layers_ros::fromMsg(sensor_msgs::PointCloud2ConstPtr(msg));
  const std::string expected = "PointCloud2 data has 23 bytes, row_step * height needs 24";
  EXPECT_EQ(costmap_layers::validatePointCloud2(view), expected);
  EXPECT_EQ(costmap_layers::validatePointCloud2(costmap_layers_ros::fromMsg(*msg)), expected);
}
}  // namespace
