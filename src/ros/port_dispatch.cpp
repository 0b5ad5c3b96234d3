#include "costmap_layers/ros/port_dispatch.hpp"

#include <exception>
#include <type_traits>

#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/ros/conversions.hpp"
#include "costmap_layers/ros/tf_gate.hpp"

namespace costmap_layers_ros
{
using costmap_layers::Severity;

namespace
{
/// A message converted by fromMsg() and handed over as is (the layer validates it); a conversion or
/// callback that throws is logged (keyed by the layer and topic) and dropped. `what` names it in the log.
template <class Msg, class Callback>
void convertAndDeliver(const Msg& msg, const Callback& cb, const PortSource& src, const char* what)
{
  try
  {
    using Data = typename std::decay_t<decltype(fromMsg(msg))>;
    cb(std::make_shared<const Data>(fromMsg(msg)));
  }
  catch (const std::exception& e)
  {
    src.log->log(Severity::Error, src.owner + src.topic,
                 src.owner + ": dropped " + what + " on " + src.topic + ": " + e.what());
  }
}

/// `converted` is what fromMsg() takes: the message, or its pointer to borrow from it.
template <class Msg, class Reading, class Converted = Msg>
void placeAndDeliver(const Msg& msg, tf2::BufferCore& tf, const std::string& global, const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<Reading>& cb, const PortSource& src,
                     const Converted* converted = nullptr)
{
  try
  {
    costmap_layers::SensorPose pose;
    const std::string& frame = msg.header.frame_id;
    pose.to_global = fromMsg(tf.lookupTransform(global, frame, msg.header.stamp).transform);
    const std::string origin_frame = sensor_frame.empty() ? frame : sensor_frame;
    // The gate let it through once tf could place both frames at the stamp: no waiting here.
    const auto origin = tf.lookupTransform(global, origin_frame, msg.header.stamp);
    pose.origin_x = origin.transform.translation.x;
    pose.origin_y = origin.transform.translation.y;
    pose.origin_z = origin.transform.translation.z;
    if constexpr (std::is_same_v<Converted, Msg>)
      cb(std::make_shared<const Reading>(fromMsg(msg)), pose);
    else
      cb(std::make_shared<const Reading>(fromMsg(*converted)), pose);
  }
  catch (const std::exception& e)
  {
    src.log->log(Severity::Warn, src.owner + src.topic + "/tf",
                 src.owner + ": dropped a reading on " + src.topic + " (frame " +
                     costmap_layers::shownText(msg.header.frame_id) + "): " + costmap_layers::shownText(e.what(), 400));
  }
}
}  // namespace

void dispatch(const nav_msgs::OccupancyGrid& msg, const costmap_layers::GridCallback& cb, const PortSource& src)
{
  try
  {
    std::string note;
    auto grid = std::make_shared<const costmap_layers::OccupancyGridData>(fromMsg(msg, &note));
    if (!note.empty())
      src.log->log(Severity::Warn, src.owner + src.topic + "/info.origin.orientation",
                   src.owner + ": grid on " + src.topic + ": " + note);
    cb(grid);
  }
  catch (const std::exception& e)
  {
    src.log->log(Severity::Error, src.owner + src.topic,
                 src.owner + ": dropped a grid on " + src.topic + ": " + e.what());
  }
}

void dispatch(const map_msgs::OccupancyGridUpdate& msg, const costmap_layers::GridUpdateCallback& cb,
              const PortSource& src)
{
  convertAndDeliver(msg, cb, src, "a map update");
}

void dispatch(const costmap_layers::SpeedLimits& msg, const costmap_layers::SpeedLimitsCallback& cb,
              const PortSource& src)
{
  convertAndDeliver(msg, cb, src, "speed limits");
}

void dispatch(const costmap_layers::CostmapFilterInfo& msg, const costmap_layers::FilterInfoCallback& cb,
              const PortSource& src)
{
  convertAndDeliver(msg, cb, src, "a filter info");
}

void dispatch(const nav_msgs::Path& msg, const costmap_layers::PathCallback& cb, const PortSource& src)
{
  convertAndDeliver(msg, cb, src, "a path");
}

void dispatch(const nav_msgs::Odometry& msg, const costmap_layers::OdometryCallback& cb, const PortSource& src)
{
  convertAndDeliver(msg, cb, src, "odometry");
}

void dispatchReading(const sensor_msgs::LaserScan& msg, tf2::BufferCore& tf, const std::string& global,
                     const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<costmap_layers::LaserScanData>& cb, const PortSource& src)
{
  placeAndDeliver(msg, tf, global, sensor_frame, cb, src);
}

void dispatchReading(const sensor_msgs::PointCloud2& msg, tf2::BufferCore& tf, const std::string& global,
                     const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<costmap_layers::PointCloud2Data>& cb, const PortSource& src)
{
  placeAndDeliver(msg, tf, global, sensor_frame, cb, src);
}

void dispatchReading(const sensor_msgs::PointCloud& msg, tf2::BufferCore& tf, const std::string& global,
                     const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<costmap_layers::PointCloud2Data>& cb, const PortSource& src)
{
  placeAndDeliver(msg, tf, global, sensor_frame, cb, src);
}

void dispatchReading(const sensor_msgs::LaserScanConstPtr& msg, tf2::BufferCore& tf, const std::string& global,
                     const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<costmap_layers::LaserScanData>& cb, const PortSource& src)
{
  if (msg) placeAndDeliver(*msg, tf, global, sensor_frame, cb, src);
}

void dispatchReading(const sensor_msgs::PointCloud2ConstPtr& msg, tf2::BufferCore& tf, const std::string& global,
                     const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<costmap_layers::PointCloud2Data>& cb, const PortSource& src)
{
  if (msg) placeAndDeliver(*msg, tf, global, sensor_frame, cb, src, &msg);
}

void dispatchReading(const sensor_msgs::PointCloudConstPtr& msg, tf2::BufferCore& tf, const std::string& global,
                     const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<costmap_layers::PointCloud2Data>& cb, const PortSource& src)
{
  if (msg) placeAndDeliver(*msg, tf, global, sensor_frame, cb, src);
}

void dispatchReading(const sensor_msgs::RangeConstPtr& msg, tf2::BufferCore& tf, const std::string& global,
                     const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<costmap_layers::RangeData>& cb, const PortSource& src)
{
  if (msg) placeAndDeliver(*msg, tf, global, sensor_frame, cb, src);
}

void dispatchReading(const sensor_msgs::Range& msg, tf2::BufferCore& tf, const std::string& global,
                     const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<costmap_layers::RangeData>& cb, const PortSource& src)
{
  placeAndDeliver(msg, tf, global, sensor_frame, cb, src);
}

void reportDroppedReading(const std::string& frame_id, const ros::Time& stamp, TfVerdict verdict, const ros::Time& now,
                          const std::string& global, const std::string& sensor_frame, const PortSource& src)
{
  const GateFailure f = gateFailure(src.owner, src.topic, global, sensor_frame, frame_id, stamp, now, verdict);
  src.log->log(Severity::Warn, f.key, f.message);
}
}  // namespace costmap_layers_ros
