#include "costmap_layers/ros/voxel_output.hpp"

#include <sensor_msgs/point_cloud2_iterator.h>

#include <algorithm>
#include <vector>

namespace costmap_layers_ros
{
using costmap_layers::VoxelGridData;
using costmap_layers::VoxelPoint;
using costmap_layers::VoxelStatus;

costmap_layers::VoxelMap toVoxelGridMsg(const VoxelGridData& grid, const std::string& frame, const ros::Time& stamp)
{
  costmap_layers::VoxelMap msg;
  msg.header.frame_id = frame;
  msg.header.stamp = stamp;
  msg.data = grid.data;
  msg.origin.x = static_cast<float>(grid.origin_x);
  msg.origin.y = static_cast<float>(grid.origin_y);
  msg.origin.z = static_cast<float>(grid.origin_z);
  msg.resolutions.x = grid.resolution;
  msg.resolutions.y = grid.resolution;
  msg.resolutions.z = grid.z_resolution;
  msg.size_x = grid.size_x;
  msg.size_y = grid.size_y;
  msg.size_z = grid.size_z;
  return msg;
}

std::size_t toVoxelMarker(const VoxelGridData& grid, const std::string& frame, const ros::Time& stamp,
                          const std::string& ns, visualization_msgs::Marker& marker)
{
  std::vector<VoxelPoint> points;
  const std::size_t total = costmap_layers::voxelCentres(grid, VoxelStatus::Marked, points);
  marker.header.frame_id = frame;
  marker.header.stamp = stamp;
  marker.ns = ns;
  marker.id = 0;
  marker.type = visualization_msgs::Marker::CUBE_LIST;
  marker.action = visualization_msgs::Marker::ADD;
  marker.pose.orientation.w = 1.0;
  marker.scale.x = grid.resolution;
  marker.scale.y = grid.resolution;
  marker.scale.z = grid.z_resolution;
  marker.color.a = 1.0f;
  marker.frame_locked = false;
  marker.points.resize(points.size());
  marker.colors.resize(points.size());
  // Height reads as colour: blue at the lowest level, through green, to red at the top.
  const float top = grid.size_z > 1 ? static_cast<float>(grid.size_z - 1) : 1.f;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    marker.points[i].x = points[i].x;
    marker.points[i].y = points[i].y;
    marker.points[i].z = points[i].z;
    const float t = static_cast<float>(points[i].level) / top;
    std_msgs::ColorRGBA& c = marker.colors[i];
    c.r = std::clamp(2.f * t - 1.f, 0.f, 1.f);
    c.g = 1.f - std::abs(2.f * t - 1.f);
    c.b = std::clamp(1.f - 2.f * t, 0.f, 1.f);
    c.a = 1.f;
  }
  return total - points.size();
}

std::size_t toVoxelCloud(const VoxelGridData& grid, const std::string& frame, const ros::Time& stamp,
                         sensor_msgs::PointCloud2& cloud)
{
  std::vector<VoxelPoint> points;
  const std::size_t total = costmap_layers::voxelCentres(grid, VoxelStatus::Marked, points);
  cloud.header.frame_id = frame;
  cloud.header.stamp = stamp;
  sensor_msgs::PointCloud2Modifier modifier(cloud);
  modifier.setPointCloud2FieldsByString(1, "xyz");
  modifier.resize(points.size());
  cloud.height = 1;
  cloud.width = static_cast<uint32_t>(points.size());
  cloud.is_dense = true;
  sensor_msgs::PointCloud2Iterator<float> x(cloud, "x"), y(cloud, "y"), z(cloud, "z");
  for (const VoxelPoint& p : points)
  {
    *x = p.x;
    *y = p.y;
    *z = p.z;
    ++x, ++y, ++z;
  }
  return total - points.size();
}
}  // namespace costmap_layers_ros
