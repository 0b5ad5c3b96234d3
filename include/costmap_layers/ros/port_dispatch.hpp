// From a received message to a layer's input port: convert it (conversions.hpp), hand the typed data to
// the port's callback, and log and drop what cannot be converted. Apart from the subscriptions
// (LayerPorts makes those and calls these from their callbacks), so that a test can feed in-memory
// messages and a hand-filled tf2::BufferCore. Nothing here throws: a message either reaches the
// callback or is dropped with a throttled report.
#pragma once

#include <map_msgs/OccupancyGridUpdate.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <ros/time.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/Range.h>
#include <tf2/buffer_core.h>

#include <memory>
#include <string>

#include "costmap_layers/CostmapFilterInfo.h"
#include "costmap_layers/SpeedLimits.h"
#include "costmap_layers/core/costmap/layer_io.hpp"
#include "costmap_layers/ros/ros_layer_context.hpp"
#include "costmap_layers/ros/tf_verdict.hpp"

namespace costmap_layers_ros
{
/// Who reads a port, for the reports: the layer's namespace (owner, e.g. "/costmap_node/keepout"), the
/// topic as the layer names it, and the layer's log. Keys are "<owner><topic>" plus a suffix.
struct PortSource
{
  std::string owner;
  std::string topic;
  std::shared_ptr<ThrottledLog> log;
};

/// A grid (map or mask). A quaternion that had to be normalised is delivered with a warning under
/// "<owner><topic>/info.origin.orientation"; a grid that cannot be converted (or whose callback throws)
/// is logged as an error under "<owner><topic>" and dropped.
void dispatch(const nav_msgs::OccupancyGrid& msg, const costmap_layers::GridCallback& cb, const PortSource& src);
/// A map update; failures as for a grid ("dropped a map update").
void dispatch(const map_msgs::OccupancyGridUpdate& msg, const costmap_layers::GridUpdateCallback& cb,
              const PortSource& src);
/// Speed limits; failures as for a grid ("dropped speed limits").
void dispatch(const costmap_layers::SpeedLimits& msg, const costmap_layers::SpeedLimitsCallback& cb,
              const PortSource& src);
/// A filter info; failures as for a grid ("dropped a filter info").
void dispatch(const costmap_layers::CostmapFilterInfo& msg, const costmap_layers::FilterInfoCallback& cb,
              const PortSource& src);
/// A path; failures as for a grid ("dropped a path").
void dispatch(const nav_msgs::Path& msg, const costmap_layers::PathCallback& cb, const PortSource& src);
/// Odometry; failures as for a grid ("dropped odometry").
void dispatch(const nav_msgs::Odometry& msg, const costmap_layers::OdometryCallback& cb, const PortSource& src);

/// A sensor reading the tf gate let through (gateVerdict() was Ready): its pose in `global` at its stamp
/// (the transform of its frame, and the origin of `sensor_frame`, or of its own frame when that is
/// empty) and the reading go to the callback. A look-up or conversion that throws is logged as a warning
/// under "<owner><topic>/tf" and the reading dropped. No look-up waits: the gate checked tf first.
void dispatchReading(const sensor_msgs::LaserScan& msg, tf2::BufferCore& tf, const std::string& global,
                     const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<costmap_layers::LaserScanData>& cb, const PortSource& src);
void dispatchReading(const sensor_msgs::PointCloud2& msg, tf2::BufferCore& tf, const std::string& global,
                     const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<costmap_layers::PointCloud2Data>& cb, const PortSource& src);
/// As received (what LayerPorts calls): the same, a PointCloud2's points borrowed from the message
/// rather than copied.
void dispatchReading(const sensor_msgs::LaserScanConstPtr& msg, tf2::BufferCore& tf, const std::string& global,
                     const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<costmap_layers::LaserScanData>& cb, const PortSource& src);
void dispatchReading(const sensor_msgs::PointCloud2ConstPtr& msg, tf2::BufferCore& tf, const std::string& global,
                     const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<costmap_layers::PointCloud2Data>& cb, const PortSource& src);
void dispatchReading(const sensor_msgs::PointCloudConstPtr& msg, tf2::BufferCore& tf, const std::string& global,
                     const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<costmap_layers::PointCloud2Data>& cb, const PortSource& src);
void dispatchReading(const sensor_msgs::RangeConstPtr& msg, tf2::BufferCore& tf, const std::string& global,
                     const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<costmap_layers::RangeData>& cb, const PortSource& src);
/// The older PointCloud, delivered as a PointCloud2Data of its points.
void dispatchReading(const sensor_msgs::PointCloud& msg, tf2::BufferCore& tf, const std::string& global,
                     const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<costmap_layers::PointCloud2Data>& cb, const PortSource& src);
void dispatchReading(const sensor_msgs::Range& msg, tf2::BufferCore& tf, const std::string& global,
                     const std::string& sensor_frame,
                     const costmap_layers::SensorCallback<costmap_layers::RangeData>& cb, const PortSource& src);

/// Logs (a warning, throttled per reason) a reading in `frame_id` stamped `stamp` that the tf gate
/// dropped with `verdict` at time `now` (see gateFailure() in tf_gate.hpp).
void reportDroppedReading(const std::string& frame_id, const ros::Time& stamp, TfVerdict verdict, const ros::Time& now,
                          const std::string& global, const std::string& sensor_frame, const PortSource& src);
}  // namespace costmap_layers_ros
