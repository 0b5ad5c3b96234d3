// A VoxelLayer's voxel snapshot as the messages LayerPorts publishes: the grid with costmap_2d's
// VoxelGrid fields, the marked voxels as a cube list coloured by level, and as a cloud. Expected values
// are worked out by hand from the snapshot below.
#include <gtest/gtest.h>

#include <sensor_msgs/point_cloud2_iterator.h>

#include "costmap_layers/ros/voxel_output.hpp"

using costmap_layers::VoxelGridData;
using namespace costmap_layers_ros;

namespace
{
/// 3 x 2 columns of 4 levels at 0.5 m x 0.25 m from (10, -2, 0.1): column (1, 0) marked at level 0,
/// column (2, 1) at level 3, column (0, 0) unknown at level 1 (not drawn).
VoxelGridData sample()
{
  VoxelGridData g;
  g.size_x = 3;
  g.size_y = 2;
  g.size_z = 4;
  g.origin_x = 10.0;
  g.origin_y = -2.0;
  g.origin_z = 0.1;
  g.resolution = 0.5;
  g.z_resolution = 0.25;
  g.data.assign(6, 0u);
  g.data[0] = 1u << 1;
  g.data[1] = (1u << 16) | 1u;
  g.data[5] = (1u << 19) | (1u << 3);
  return g;
}
}  // namespace

TEST(VoxelOutput, GridMessageCarriesTheFieldsOfCostmap2dsVoxelGrid)
{
  const auto msg = toVoxelGridMsg(sample(), "odom", ros::Time(12, 5));
  EXPECT_EQ(msg.header.frame_id, "odom");
  EXPECT_EQ(msg.header.stamp, ros::Time(12, 5));
  EXPECT_EQ(msg.size_x, 3u);
  EXPECT_EQ(msg.size_y, 2u);
  EXPECT_EQ(msg.size_z, 4u);
  EXPECT_FLOAT_EQ(msg.origin.x, 10.f);
  EXPECT_FLOAT_EQ(msg.origin.y, -2.f);
  EXPECT_FLOAT_EQ(msg.origin.z, 0.1f);
  EXPECT_DOUBLE_EQ(msg.resolutions.x, 0.5);
  EXPECT_DOUBLE_EQ(msg.resolutions.y, 0.5);
  EXPECT_DOUBLE_EQ(msg.resolutions.z, 0.25);
  EXPECT_EQ(msg.data, (std::vector<uint32_t>{2u, 0x10001u, 0u, 0u, 0u, 0x80008u}));
}

TEST(VoxelOutput, MarkerIsACubeListOfTheMarkedVoxelsColouredByLevel)
{
  visualization_msgs::Marker m;
  EXPECT_EQ(toVoxelMarker(sample(), "odom", ros::Time(3, 0), "voxel_layer", m), 0u);
  EXPECT_EQ(m.type, visualization_msgs::Marker::CUBE_LIST);
  EXPECT_EQ(m.action, visualization_msgs::Marker::ADD);
  EXPECT_EQ(m.ns, "voxel_layer");
  EXPECT_EQ(m.header.frame_id, "odom");
  EXPECT_DOUBLE_EQ(m.pose.orientation.w, 1.0);
  EXPECT_DOUBLE_EQ(m.scale.x, 0.5);
  EXPECT_DOUBLE_EQ(m.scale.z, 0.25);
  ASSERT_EQ(m.points.size(), 2u);
  ASSERT_EQ(m.colors.size(), 2u);
  // Column (1, 0) level 0: (10 + 1.5 * 0.5, -2 + 0.5 * 0.5, 0.1 + 0.5 * 0.25); blue, the lowest level.
  EXPECT_NEAR(m.points[0].x, 10.75, 1e-6);
  EXPECT_NEAR(m.points[0].y, -1.75, 1e-6);
  EXPECT_NEAR(m.points[0].z, 0.225, 1e-6);
  EXPECT_FLOAT_EQ(m.colors[0].b, 1.f);
  EXPECT_FLOAT_EQ(m.colors[0].r, 0.f);
  // Column (2, 1) level 3, the top: (11.25, -1.25, 0.1 + 3.5 * 0.25); red.
  EXPECT_NEAR(m.points[1].x, 11.25, 1e-6);
  EXPECT_NEAR(m.points[1].y, -1.25, 1e-6);
  EXPECT_NEAR(m.points[1].z, 0.975, 1e-6);
  EXPECT_FLOAT_EQ(m.colors[1].r, 1.f);
  EXPECT_FLOAT_EQ(m.colors[1].b, 0.f);
  EXPECT_FLOAT_EQ(m.colors[1].a, 1.f);
}

TEST(VoxelOutput, CloudHoldsTheMarkedVoxelsCentres)
{
  sensor_msgs::PointCloud2 c;
  EXPECT_EQ(toVoxelCloud(sample(), "odom", ros::Time(3, 0), c), 0u);
  EXPECT_EQ(c.header.frame_id, "odom");
  EXPECT_EQ(c.height, 1u);
  ASSERT_EQ(c.width, 2u);
  sensor_msgs::PointCloud2ConstIterator<float> x(c, "x"), y(c, "y"), z(c, "z");
  EXPECT_FLOAT_EQ(*x, 10.75f);
  EXPECT_FLOAT_EQ(*y, -1.75f);
  EXPECT_FLOAT_EQ(*z, 0.225f);
  ++x, ++y, ++z;
  EXPECT_FLOAT_EQ(*x, 11.25f);
  EXPECT_FLOAT_EQ(*z, 0.975f);
}

TEST(VoxelOutput, AGridWithNothingMarkedGivesEmptyMessages)
{
  VoxelGridData g = sample();
  g.data.assign(6, 0u);
  visualization_msgs::Marker m;
  sensor_msgs::PointCloud2 c;
  EXPECT_EQ(toVoxelMarker(g, "map", ros::Time(1, 0), "v", m), 0u);
  EXPECT_TRUE(m.points.empty());
  EXPECT_EQ(toVoxelCloud(g, "map", ros::Time(1, 0), c), 0u);
  EXPECT_EQ(c.width, 0u);
}

TEST(VoxelOutput, AtMostKMaxVoxelPointsAreDrawnAndTheRestCounted)
{
  // 1024 x 1024 columns with levels 0 and 1 marked: 2^21 voxels, twice what a message draws.
  VoxelGridData g;
  g.size_x = g.size_y = 1024;
  g.size_z = 2;
  g.resolution = g.z_resolution = 0.1;
  g.data.assign(std::size_t{1024} * 1024, (3u << 16) | 3u);
  visualization_msgs::Marker m;
  EXPECT_EQ(toVoxelMarker(g, "map", ros::Time(1, 0), "v", m), std::size_t{1} << 20);
  EXPECT_EQ(m.points.size(), costmap_layers::kMaxVoxelPoints);
  sensor_msgs::PointCloud2 c;
  EXPECT_EQ(toVoxelCloud(g, "map", ros::Time(1, 0), c), std::size_t{1} << 20);
  EXPECT_EQ(c.width, costmap_layers::kMaxVoxelPoints);
}
