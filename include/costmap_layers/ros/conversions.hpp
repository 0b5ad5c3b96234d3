// Conversions between messages and the core's plain types: the only place that knows both.
#pragma once

#include <geometry_msgs/Quaternion.h>
#include <geometry_msgs/TransformStamped.h>
#include <map_msgs/OccupancyGridUpdate.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/Range.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include "costmap_layers/CostmapFilterInfo.h"
#include "costmap_layers/SpeedLimits.h"
#include "costmap_layers/core/config/param_value.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/data/grid_data.hpp"
#include "costmap_layers/core/data/path_data.hpp"
#include "costmap_layers/core/data/sensor_data.hpp"
#include "costmap_layers/core/grid/costmap_2d.hpp"

namespace costmap_layers_ros
{
/// The most a grid's origin may be tilted out of the plane [rad]: a 2-D grid cannot represent more.
constexpr double kMaxGridTilt = 0.01;
/// The most a robot or sensor pose used in the plane may be tilted [rad] (a robot on a ramp is fine).
constexpr double kMaxPoseTilt = 1.0471975511965976;  // 60 degrees

/// The heading of a quaternion as a planar pose uses it (tf2::getYaw of the normalised quaternion).
/// Throws std::invalid_argument naming `field` and the value when a component is not finite, the
/// length is (near) zero, or the rotation tilts the plane by more than max_tilt [rad]. A quaternion
/// of non-unit length is normalised first; *normalised (if given) says whether that was needed.
double planarYaw(const geometry_msgs::Quaternion& q, double max_tilt, const std::string& field,
                 bool* normalised = nullptr);

/// Copies the grid; the yaw of the origin comes from its quaternion (planarYaw with kMaxGridTilt,
/// which throws for an unusable one; *note says when it had to be normalised). Does not validate the rest.
costmap_layers::OccupancyGridData fromMsg(const nav_msgs::OccupancyGrid& msg, std::string* note = nullptr);
costmap_layers::SpeedLimitsData fromMsg(const costmap_layers::SpeedLimits& msg);
/// The fields as they are (base and multiplier widened from float32); the filter checks them.
costmap_layers::FilterInfoData fromMsg(const costmap_layers::CostmapFilterInfo& msg);
costmap_layers::OccupancyGridUpdateData fromMsg(const map_msgs::OccupancyGridUpdate& msg);
/// The positions of the poses, in the path's header frame (each pose's own header is not used, as in
/// Nav2); the core validates them.
costmap_layers::PathData fromMsg(const nav_msgs::Path& msg);
/// The twist as it is; the core validates it.
costmap_layers::OdometryData fromMsg(const nav_msgs::Odometry& msg);
/// Sensor messages: plain copies; the core validates them.
costmap_layers::LaserScanData fromMsg(const sensor_msgs::LaserScan& msg);
costmap_layers::PointCloud2Data fromMsg(const sensor_msgs::PointCloud2& msg);
/// The same without copying the points: the result borrows msg's bytes and keeps msg alive.
costmap_layers::PointCloud2Data fromMsg(const sensor_msgs::PointCloud2ConstPtr& msg);
/// The older sensor_msgs/PointCloud as a PointCloud2 of its points (fields x, y, z, FLOAT32, one row),
/// as costmap_2d converts it; its channels are not used by any layer and are left out.
costmap_layers::PointCloud2Data fromMsg(const sensor_msgs::PointCloud& msg);
costmap_layers::RangeData fromMsg(const sensor_msgs::Range& msg);
costmap_layers::Transform3D fromMsg(const geometry_msgs::Transform& msg);

/// The whole costmap as an OccupancyGrid (costs translated as costmap_2d does).
void toOccupancyGrid(const costmap_layers::Costmap2D& costmap, const std::string& frame, const ros::Time& stamp,
                     nav_msgs::OccupancyGrid& msg);
/// The window of the costmap as an OccupancyGridUpdate, clipped to the grid first.
/// @return false (msg untouched) when nothing of the window lies on the grid.
bool toOccupancyGridUpdate(const costmap_layers::Costmap2D& costmap, const costmap_layers::CellWindow& window,
                           const std::string& frame, const ros::Time& stamp, map_msgs::OccupancyGridUpdate& msg);

/// The parameter tree under an XmlRpc value (structs keep their keys, arrays their order).
costmap_layers::ParamValue fromXmlRpc(XmlRpc::XmlRpcValue& value);
}  // namespace costmap_layers_ros
