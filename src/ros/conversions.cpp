#include "costmap_layers/ros/conversions.hpp"

#include <tf2/LinearMath/Quaternion.h>
#include <tf2/utils.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "costmap_layers/core/costmap/publish_schedule.hpp"
#include "costmap_layers/core/layers/sensor_parsing.hpp"
#include "costmap_layers/core/rules/cost_translation.hpp"

namespace costmap_layers_ros
{
using costmap_layers::ParamValue;

double planarYaw(const geometry_msgs::Quaternion& q, double max_tilt, const std::string& field, bool* normalised)
{
  const auto value = [&]
  {
    std::ostringstream s;
    s << field << " (" << q.x << ", " << q.y << ", " << q.z << ", " << q.w << ")";
    return s.str();
  };
  if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z) || !std::isfinite(q.w))
    throw std::invalid_argument(value() + " is not finite");
  const double n = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (!(n > 1e-6)) throw std::invalid_argument(value() + " has zero length: no orientation");
  const tf2::Quaternion u(q.x / n, q.y / n, q.z / n, q.w / n);
  // The angle between the rotated z axis and z: its cosine is 1 - 2 (x^2 + y^2) for a unit quaternion.
  const double tilt = std::acos(std::clamp(1.0 - 2.0 * (u.x() * u.x() + u.y() * u.y()), -1.0, 1.0));
  if (tilt > max_tilt)
  {
    std::ostringstream s;
    s << value() << " tilts the plane by " << tilt << " rad (roll/pitch), more than the " << max_tilt
      << " rad a 2-D costmap can represent";
    throw std::invalid_argument(s.str());
  }
  if (normalised) *normalised = std::fabs(n - 1.0) > 1e-6;
  return tf2::getYaw(u);
}

costmap_layers::OccupancyGridData fromMsg(const nav_msgs::OccupancyGrid& msg, std::string* note)
{
  costmap_layers::OccupancyGridData g;
  g.frame_id = msg.header.frame_id;
  g.stamp_ns = msg.header.stamp.toNSec();
  g.width = msg.info.width;
  g.height = msg.info.height;
  g.resolution = msg.info.resolution;
  g.origin_x = msg.info.origin.position.x;
  g.origin_y = msg.info.origin.position.y;
  bool normalised = false;
  g.origin_yaw = planarYaw(msg.info.origin.orientation, kMaxGridTilt, "info.origin.orientation", &normalised);
  if (normalised && note)
  {
    const auto& q = msg.info.origin.orientation;
    std::ostringstream s;
    s << "info.origin.orientation (" << q.x << ", " << q.y << ", " << q.z << ", " << q.w
      << ") is not of unit length: normalised (yaw " << g.origin_yaw << " rad)";
    *note = s.str();
  }
  g.data.assign(msg.data.begin(), msg.data.end());
  return g;
}

costmap_layers::SpeedLimitsData fromMsg(const costmap_layers::SpeedLimits& msg)
{
  costmap_layers::SpeedLimitsData d;
  d.frame_id = msg.header.frame_id;
  d.stamp_ns = msg.header.stamp.toNSec();
  d.limits.reserve(msg.limits.size());
  for (const auto& l : msg.limits)
    d.limits.push_back({l.area_id, l.max_speed});
  return d;
}

costmap_layers::FilterInfoData fromMsg(const costmap_layers::CostmapFilterInfo& msg)
{
  costmap_layers::FilterInfoData d;
  d.frame_id = msg.header.frame_id;
  d.stamp_ns = msg.header.stamp.toNSec();
  d.type = msg.type;
  d.filter_mask_topic = msg.filter_mask_topic;
  d.base = msg.base;
  d.multiplier = msg.multiplier;
  return d;
}

costmap_layers::OccupancyGridUpdateData fromMsg(const map_msgs::OccupancyGridUpdate& msg)
{
  costmap_layers::OccupancyGridUpdateData u;
  u.frame_id = msg.header.frame_id;
  u.stamp_ns = msg.header.stamp.toNSec();
  u.x = msg.x;
  u.y = msg.y;
  u.width = msg.width;
  u.height = msg.height;
  u.data.assign(msg.data.begin(), msg.data.end());
  return u;
}

costmap_layers::PathData fromMsg(const nav_msgs::Path& msg)
{
  costmap_layers::PathData d;
  d.frame_id = msg.header.frame_id;
  d.stamp_ns = msg.header.stamp.toNSec();
  // A sender may put millions of poses here: copy no more than the core can refuse the path by.
  const std::size_t n = std::min(msg.poses.size(), costmap_layers::limits::kMaxPathPoses + 1);
  d.message_poses = msg.poses.size();
  d.poses.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    d.poses.push_back({msg.poses[i].pose.position.x, msg.poses[i].pose.position.y});
  return d;
}

costmap_layers::OdometryData fromMsg(const nav_msgs::Odometry& msg)
{
  costmap_layers::OdometryData d;
  d.frame_id = msg.header.frame_id;
  d.child_frame_id = msg.child_frame_id;
  d.stamp_ns = msg.header.stamp.toNSec();
  d.linear_x = msg.twist.twist.linear.x;
  d.linear_y = msg.twist.twist.linear.y;
  d.angular_z = msg.twist.twist.angular.z;
  return d;
}

costmap_layers::LaserScanData fromMsg(const sensor_msgs::LaserScan& msg)
{
  costmap_layers::LaserScanData d;
  d.frame_id = msg.header.frame_id;
  d.stamp_ns = msg.header.stamp.toNSec();
  d.angle_min = msg.angle_min;
  d.angle_max = msg.angle_max;
  d.angle_increment = msg.angle_increment;
  d.time_increment = msg.time_increment;
  d.scan_time = msg.scan_time;
  d.range_min = msg.range_min;
  d.range_max = msg.range_max;
  d.ranges = msg.ranges;
  d.intensities = msg.intensities;
  return d;
}

costmap_layers::PointCloud2Data fromMsg(const sensor_msgs::PointCloud2& msg)
{
  costmap_layers::PointCloud2Data d;
  d.frame_id = msg.header.frame_id;
  d.stamp_ns = msg.header.stamp.toNSec();
  d.height = msg.height;
  d.width = msg.width;
  for (const auto& f : msg.fields)
    d.fields.push_back({f.name, f.offset, f.datatype, f.count});
  d.is_bigendian = msg.is_bigendian;
  d.point_step = msg.point_step;
  d.row_step = msg.row_step;
  d.data = msg.data;
  d.is_dense = msg.is_dense;
  return d;
}

costmap_layers::PointCloud2Data fromMsg(const sensor_msgs::PointCloud2ConstPtr& msg)
{
  costmap_layers::PointCloud2Data d;
  if (!msg) throw std::invalid_argument("no PointCloud2 message");
  d.frame_id = msg->header.frame_id;
  d.stamp_ns = msg->header.stamp.toNSec();
  d.height = msg->height;
  d.width = msg->width;
  d.fields.reserve(msg->fields.size());
  for (const auto& f : msg->fields)
    d.fields.push_back({f.name, f.offset, f.datatype, f.count});
  d.is_bigendian = msg->is_bigendian;
  d.point_step = msg->point_step;
  d.row_step = msg->row_step;
  d.is_dense = msg->is_dense;
  d.view = msg->data.data();
  d.view_size = msg->data.size();
  d.keep = std::shared_ptr<const void>(msg.get(), [msg](const void*) {});
  return d;
}

costmap_layers::PointCloud2Data fromMsg(const sensor_msgs::PointCloud& msg)
{
  costmap_layers::PointCloud2Data d;
  d.frame_id = msg.header.frame_id;
  d.stamp_ns = msg.header.stamp.toNSec();
  d.height = 1;
  d.width = static_cast<uint32_t>(msg.points.size());  // a message holds at most 2^32 points of any size
  for (const char* name : {"x", "y", "z"})
    d.fields.push_back({name, static_cast<uint32_t>(4 * d.fields.size()), costmap_layers::PointFieldData::FLOAT32, 1});
  d.point_step = 12;
  d.row_step = 12 * d.width;
  d.data.resize(static_cast<std::size_t>(12) * msg.points.size());
  uint8_t* out = d.data.data();
  for (const auto& p : msg.points)
  {
    const float xyz[3] = {p.x, p.y, p.z};
    std::memcpy(out, xyz, sizeof xyz);
    out += sizeof xyz;
  }
  d.is_bigendian = costmap_layers::hostIsBigEndian();  // the floats were written in this machine's order
  d.is_dense = false;                                  // NaN points are possible: the parser skips them
  return d;
}

costmap_layers::RangeData fromMsg(const sensor_msgs::Range& msg)
{
  costmap_layers::RangeData d;
  d.frame_id = msg.header.frame_id;
  d.stamp_ns = msg.header.stamp.toNSec();
  d.radiation_type = msg.radiation_type;
  d.field_of_view = msg.field_of_view;
  d.min_range = msg.min_range;
  d.max_range = msg.max_range;
  d.range = msg.range;
  return d;
}

costmap_layers::Transform3D fromMsg(const geometry_msgs::Transform& msg)
{
  const auto& q = msg.rotation;
  const auto& t = msg.translation;
  if (!std::isfinite(t.x) || !std::isfinite(t.y) || !std::isfinite(t.z))
    throw std::invalid_argument("transform translation is not finite");
  // Sensors may be mounted at any angle: only the length is checked here (any tilt is a 3-D pose).
  planarYaw(q, M_PI, "transform rotation");
  const double s = 1.0 / std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  return costmap_layers::Transform3D::fromQuaternion(t.x, t.y, t.z, q.x * s, q.y * s, q.z * s, q.w * s);
}

void toOccupancyGrid(const costmap_layers::Costmap2D& costmap, const std::string& frame, const ros::Time& stamp,
                     nav_msgs::OccupancyGrid& msg)
{
  msg.header.frame_id = frame;
  msg.header.stamp = stamp;
  msg.info.map_load_time = stamp;
  msg.info.resolution = static_cast<float>(costmap.getResolution());
  msg.info.width = costmap.getSizeInCellsX();
  msg.info.height = costmap.getSizeInCellsY();
  msg.info.origin.position.x = costmap.getOriginX();
  msg.info.origin.position.y = costmap.getOriginY();
  msg.info.origin.position.z = 0.0;
  msg.info.origin.orientation.w = 1.0;
  const auto& table = costmap_layers::costTranslationTable();
  msg.data.resize(costmap.cellCount());
  const uint8_t* cells = costmap.data();
  for (std::size_t k = 0; k < msg.data.size(); ++k)
    msg.data[k] = table[cells[k]];
}

bool toOccupancyGridUpdate(const costmap_layers::Costmap2D& costmap, const costmap_layers::CellWindow& requested,
                           const std::string& frame, const ros::Time& stamp, map_msgs::OccupancyGridUpdate& msg)
{
  // Never read past the grid, whatever window was asked for.
  const costmap_layers::CellWindow window =
      costmap_layers::clipWindow(requested, costmap.getSizeInCellsX(), costmap.getSizeInCellsY());
  if (window.empty()) return false;
  msg.header.frame_id = frame;
  msg.header.stamp = stamp;
  msg.x = window.x0;
  msg.y = window.y0;
  msg.width = static_cast<uint32_t>(window.xn - window.x0);
  msg.height = static_cast<uint32_t>(window.yn - window.y0);
  const auto& table = costmap_layers::costTranslationTable();
  msg.data.resize(static_cast<std::size_t>(msg.width) * msg.height);
  std::size_t k = 0;
  for (int j = window.y0; j < window.yn; ++j)
  {
    const uint8_t* row = costmap.data() + costmap.getIndex(static_cast<unsigned>(window.x0), static_cast<unsigned>(j));
    for (uint32_t i = 0; i < msg.width; ++i)
      msg.data[k++] = table[row[i]];
  }
  return true;
}

ParamValue fromXmlRpc(XmlRpc::XmlRpcValue& value)
{
  switch (value.getType())
  {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return ParamValue::makeBool(static_cast<bool>(value));
    case XmlRpc::XmlRpcValue::TypeInt:
      return ParamValue::makeInt(static_cast<int>(value));
    case XmlRpc::XmlRpcValue::TypeDouble:
      return ParamValue::makeDouble(static_cast<double>(value));
    case XmlRpc::XmlRpcValue::TypeString:
      return ParamValue::makeString(static_cast<std::string>(value));
    case XmlRpc::XmlRpcValue::TypeArray:
    {
      ParamValue list = ParamValue::makeList();
      for (int i = 0; i < value.size(); ++i)
        list.push(fromXmlRpc(value[i]));
      return list;
    }
    case XmlRpc::XmlRpcValue::TypeStruct:
    {
      ParamValue map = ParamValue::makeMap();
      for (auto it = value.begin(); it != value.end(); ++it)
        map.set(it->first, fromXmlRpc(it->second));
      return map;
    }
    default:
      return ParamValue{};
  }
}
}  // namespace costmap_layers_ros
