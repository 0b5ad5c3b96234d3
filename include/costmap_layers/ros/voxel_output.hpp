// A VoxelLayer's voxel snapshot as messages: the grid itself (costmap_layers/VoxelMap), its marked
// voxels as an RViz cube list, and as a cloud of their centres. Only LayerPorts and tests include this.
#pragma once

#include <ros/time.h>
#include <sensor_msgs/PointCloud2.h>
#include <visualization_msgs/Marker.h>

#include <string>

#include "costmap_layers/VoxelMap.h"
#include "costmap_layers/core/data/voxel_grid_data.hpp"

namespace costmap_layers_ros
{
costmap_layers::VoxelMap toVoxelGridMsg(const costmap_layers::VoxelGridData& grid, const std::string& frame,
                                        const ros::Time& stamp);
/// A CUBE_LIST of the marked voxels (one cube per voxel, coloured by level from blue at the bottom to
/// red at the top), namespace `ns`. @return how many marked voxels were left out (more than
/// kMaxVoxelPoints).
std::size_t toVoxelMarker(const costmap_layers::VoxelGridData& grid, const std::string& frame, const ros::Time& stamp,
                          const std::string& ns, visualization_msgs::Marker& marker);
/// A PointCloud2 (fields x, y, z as FLOAT32) of the marked voxels' centres. @return how many were left out.
std::size_t toVoxelCloud(const costmap_layers::VoxelGridData& grid, const std::string& frame, const ros::Time& stamp,
                         sensor_msgs::PointCloud2& cloud);
}  // namespace costmap_layers_ros
