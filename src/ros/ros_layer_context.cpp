#include "costmap_layers/ros/ros_layer_context.hpp"

#include <map_msgs/OccupancyGridUpdate.h>
#include <message_filters/subscriber.h>
#include <nav_msgs/OccupancyGrid.h>
#include <std_srvs/SetBool.h>
#include <tf2/exceptions.h>
#include <tf2_ros/message_filter.h>

#include <cmath>
#include <cstdio>

#include "costmap_layers/MaxSpeed.h"
#include "costmap_layers/SpeedLimits.h"
#include "costmap_layers/ros/conversions.hpp"

namespace costmap_layers_ros
{
using costmap_layers::Severity;

void ThrottledLog::log(Severity severity, const std::string& key, const std::string& message)
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const ros::WallTime now = ros::WallTime::now();
    auto it = last_.find(key);
    if (it != last_.end() && (now - it->second).toSec() < period_) return;
    last_[key] = now;
  }
  switch (severity)
  {
    case Severity::Debug:
      ROS_DEBUG_STREAM(message);
      break;
    case Severity::Info:
      ROS_INFO_STREAM(message);
      break;
    case Severity::Warn:
      ROS_WARN_STREAM(message);
      break;
    case Severity::Error:
      ROS_ERROR_STREAM(message);
      break;
  }
}

RosLayerContext::RosLayerContext(ros::NodeHandle public_nh, ros::NodeHandle private_nh,
                                 costmap_layers::ParamValue params, std::string global_frame,
                                 double transform_tolerance, tf2_ros::Buffer& tf, std::shared_ptr<ThrottledLog> log)
    : public_nh_(std::move(public_nh)),
      private_nh_(std::move(private_nh)),
      params_(std::move(params)),
      global_frame_(std::move(global_frame)),
      transform_tolerance_(transform_tolerance),
      tf_(tf),
      log_(std::move(log))
{
}

void RosLayerContext::subscribeGrid(const std::string& topic, costmap_layers::GridKind, costmap_layers::GridCallback cb)
{
  const std::string owner = private_nh_.getNamespace();
  subscribers_.push_back(public_nh_.subscribe<nav_msgs::OccupancyGrid>(
      topic, 1,
      [cb, owner, topic, log = log_](const nav_msgs::OccupancyGrid::ConstPtr& msg)
      {
        try
        {
          cb(std::make_shared<const costmap_layers::OccupancyGridData>(fromMsg(*msg)));
        }
        catch (const std::exception& e)
        {
          log->log(Severity::Error, owner + topic, owner + ": dropped a grid on " + topic + ": " + e.what());
        }
      }));
}

void RosLayerContext::subscribeGridUpdates(const std::string& topic, costmap_layers::GridUpdateCallback cb)
{
  const std::string owner = private_nh_.getNamespace();
  subscribers_.push_back(public_nh_.subscribe<map_msgs::OccupancyGridUpdate>(
      topic, 10,
      [cb, owner, topic, log = log_](const map_msgs::OccupancyGridUpdate::ConstPtr& msg)
      {
        try
        {
          cb(std::make_shared<const costmap_layers::OccupancyGridUpdateData>(fromMsg(*msg)));
        }
        catch (const std::exception& e)
        {
          log->log(Severity::Error, owner + topic, owner + ": dropped a map update on " + topic + ": " + e.what());
        }
      }));
}

void RosLayerContext::subscribeSpeedLimits(const std::string& topic, costmap_layers::SpeedLimitsCallback cb)
{
  const std::string owner = private_nh_.getNamespace();
  subscribers_.push_back(public_nh_.subscribe<costmap_layers::SpeedLimits>(
      topic, 1,
      [cb, owner, topic, log = log_](const costmap_layers::SpeedLimits::ConstPtr& msg)
      {
        try
        {
          cb(std::make_shared<const costmap_layers::SpeedLimitsData>(fromMsg(*msg)));
        }
        catch (const std::exception& e)
        {
          log->log(Severity::Error, owner + topic, owner + ": dropped speed limits on " + topic + ": " + e.what());
        }
      }));
}

namespace
{
/// A message filter and the subscriber it reads, destroyed in that order.
template <class Msg>
struct FilteredInput
{
  // Readings waiting for tf: once this many newer ones wait too, the oldest is dropped (and reported).
  static constexpr uint32_t kQueue = 10;
  message_filters::Subscriber<Msg> subscriber;
  tf2_ros::MessageFilter<Msg> filter;
  FilteredInput(ros::NodeHandle& nh, const std::string& topic, tf2_ros::Buffer& tf, const std::string& target)
      : subscriber(nh, topic, 5), filter(subscriber, tf, target, kQueue, nh)
  {
  }
};
}  // namespace

template <class Msg, class Reading>
void RosLayerContext::subscribeSensor(const std::string& topic, const std::string& sensor_frame,
                                      costmap_layers::SensorCallback<Reading> cb)
{
  auto input = std::make_shared<FilteredInput<Msg>>(public_nh_, topic, tf_, global_frame_);
  const std::string owner = private_nh_.getNamespace();
  const std::string global = global_frame_;
  tf2_ros::Buffer& tf = tf_;
  auto log = log_;
  input->filter.registerCallback(
      [=, &tf](const typename Msg::ConstPtr& msg)
      {
        try
        {
          costmap_layers::SensorPose pose;
          const std::string& frame = msg->header.frame_id;
          pose.to_global = fromMsg(tf.lookupTransform(global, frame, msg->header.stamp).transform);
          const std::string origin_frame = sensor_frame.empty() ? frame : sensor_frame;
          const auto origin = tf.lookupTransform(global, origin_frame, msg->header.stamp, ros::Duration(0.1));
          pose.origin_x = origin.transform.translation.x;
          pose.origin_y = origin.transform.translation.y;
          pose.origin_z = origin.transform.translation.z;
          cb(std::make_shared<const Reading>(fromMsg(*msg)), pose);
        }
        catch (const std::exception& e)
        {
          log->log(Severity::Warn, owner + topic + "/tf",
                   owner + ": dropped a reading on " + topic + " (frame " + msg->header.frame_id + "): " + e.what());
        }
      });
  input->filter.registerFailureCallback(
      [=](const typename Msg::ConstPtr& msg, tf2_ros::filter_failure_reasons::FilterFailureReason reason)
      {
        // Each reason is its own throttled report, so that a stale stamp does not hide a wrong frame.
        std::string key = owner + topic + "/tf/", why;
        const ros::Time stamp = msg->header.stamp;
        const double behind = (ros::Time::now() - stamp).toSec();
        char when[96];
        std::snprintf(when, sizeof(when), "header.stamp %.3f s (%.3f s %s now)", stamp.toSec(), std::fabs(behind),
                      behind >= 0.0 ? "before" : "after");
        switch (reason)
        {
          case tf2_ros::filter_failure_reasons::EmptyFrameID:
            key += "frame_id";
            why = "header.frame_id is empty";
            break;
          case tf2_ros::filter_failure_reasons::OutTheBack:
            key += "stamp";
            why = std::string(when) + " is older than every transform tf keeps";
            break;
          default:
            key += "wait";
            why = std::string("no transform at ") + when + " arrived while " +
                  std::to_string(FilteredInput<Msg>::kQueue) + " newer readings waited";
            break;
        }
        log->log(Severity::Warn, key,
                 owner + ": dropped a reading on " + topic + ": cannot transform frame '" + msg->header.frame_id +
                     "' into '" + global + "': " + why);
      });
  sensor_inputs_.push_back(input);
}

void RosLayerContext::subscribeLaserScan(const std::string& topic, const std::string& sensor_frame,
                                         costmap_layers::SensorCallback<costmap_layers::LaserScanData> cb)
{
  subscribeSensor<sensor_msgs::LaserScan>(topic, sensor_frame, std::move(cb));
}

void RosLayerContext::subscribePointCloud2(const std::string& topic, const std::string& sensor_frame,
                                           costmap_layers::SensorCallback<costmap_layers::PointCloud2Data> cb)
{
  subscribeSensor<sensor_msgs::PointCloud2>(topic, sensor_frame, std::move(cb));
}

void RosLayerContext::subscribeRange(const std::string& topic,
                                     costmap_layers::SensorCallback<costmap_layers::RangeData> cb)
{
  subscribeSensor<sensor_msgs::Range>(topic, "", std::move(cb));
}

costmap_layers::MaxSpeedPublisher RosLayerContext::advertiseMaxSpeed(const std::string& topic)
{
  publishers_.push_back(public_nh_.advertise<costmap_layers::MaxSpeed>(topic, 1, true));
  ros::Publisher pub = publishers_.back();
  const std::string frame = global_frame_;
  return [pub, frame](double max_speed)
  {
    costmap_layers::MaxSpeed msg;
    msg.header.frame_id = frame;
    msg.header.stamp = ros::Time::now();
    msg.max_speed = max_speed;
    pub.publish(msg);
  };
}

void RosLayerContext::advertiseToggle(std::function<void(bool)> cb)
{
  services_.push_back(private_nh_.advertiseService<std_srvs::SetBool::Request, std_srvs::SetBool::Response>(
      "toggle",
      [cb](std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res)
      {
        cb(req.data);
        res.success = true;
        res.message = req.data ? "enabled" : "disabled";
        return true;
      }));
}

std::optional<costmap_layers::Transform2D> RosLayerContext::lookupTransform(const std::string& target_frame,
                                                                            const std::string& source_frame,
                                                                            std::string* error)
{
  return lookupTransform2D(tf_, target_frame, source_frame, transform_tolerance_, error);
}

std::optional<costmap_layers::Transform2D> lookupTransform2D(const tf2_ros::Buffer& tf, const std::string& target_frame,
                                                             const std::string& source_frame, double tolerance,
                                                             std::string* error)
{
  try
  {
    const geometry_msgs::TransformStamped t = tf.lookupTransform(target_frame, source_frame, ros::Time(0));
    // A zero stamp means only static transforms: those never go stale.
    if (!t.header.stamp.isZero() && (ros::Time::now() - t.header.stamp).toSec() > tolerance && tolerance > 0.0)
    {
      if (error)
        *error = "transform " + source_frame + " -> " + target_frame + " is " +
                 std::to_string((ros::Time::now() - t.header.stamp).toSec()) + " s old (transform_tolerance " +
                 std::to_string(tolerance) + " s)";
      return std::nullopt;
    }
    const auto& q = t.transform.rotation;
    costmap_layers::Transform2D out;
    out.x = t.transform.translation.x;
    out.y = t.transform.translation.y;
    out.yaw = std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
    return out;
  }
  catch (const tf2::TransformException& e)
  {
    if (error) *error = e.what();
    return std::nullopt;
  }
}

void RosLayerContext::report(Severity severity, const std::string& key, const std::string& message)
{
  log_->log(severity, private_nh_.getNamespace() + "/" + key, message);
}
}  // namespace costmap_layers_ros
