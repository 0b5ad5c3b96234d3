#include "costmap_layers/ros/ros_layer_context.hpp"

#include <tf2/exceptions.h>

#include <cmath>
#include <mutex>

#include "costmap_layers/ros/conversions.hpp"
#include "costmap_layers/ros/tf_verdict.hpp"

namespace costmap_layers_ros
{
using costmap_layers::Severity;

namespace
{
void logToRosconsole(Severity severity, const std::string& message)
{
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
}  // namespace

ThrottledLog::ThrottledLog(double period, Sink sink, Clock clock)
    : period_(period),
      sink_(sink ? std::move(sink) : Sink(logToRosconsole)),
      clock_(clock ? std::move(clock) : Clock([] { return ros::SteadyTime::now().toSec(); }))
{
}

void ThrottledLog::log(Severity severity, const std::string& key, const std::string& message)
{
  static const std::string kOverflow = "<throttle table full>";
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const double now = clock_();
    // A key stays throttled for one period; a clock that went back ends its period.
    const auto quiet = [&](double since) { return now >= since && now - since < period_; };
    const std::string* slot = &key;
    if (last_.size() >= kMaxKeys && last_.find(key) == last_.end())
    {
      for (auto k = last_.begin(); k != last_.end();)
        k = quiet(k->second) ? std::next(k) : last_.erase(k);
      if (last_.size() >= kMaxKeys) slot = &kOverflow;  // the table holds at most kMaxKeys + 1 keys
    }
    const auto it = last_.find(*slot);
    if (it != last_.end() && quiet(it->second)) return;
    last_[*slot] = now;
  }
  // The line ends with its stable key: what scripts and tests match on, whatever the wording.
  sink_(severity, message + " [" + key + "]");
}

std::size_t ThrottledLog::keyCount() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return last_.size();
}

RosLayerContext::RosLayerContext(ros::NodeHandle private_nh, costmap_layers::ParamValue params,
                                 std::string global_frame, double transform_tolerance, tf2_ros::Buffer& tf,
                                 std::shared_ptr<ThrottledLog> log)
    : private_nh_(std::move(private_nh)),
      params_(std::move(params)),
      global_frame_(std::move(global_frame)),
      transform_tolerance_(transform_tolerance),
      tf_(tf),
      log_(std::move(log))
{
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
    const double age = secondsBetween(ros::Time::now(), t.header.stamp);
    if (!t.header.stamp.isZero() && age > tolerance && tolerance > 0.0)
    {
      if (error)
        *error = "transform " + source_frame + " -> " + target_frame + " is " + std::to_string(age) +
                 " s old (transform_tolerance " + std::to_string(tolerance) + " s)";
      return std::nullopt;
    }
    costmap_layers::Transform2D out;
    out.x = t.transform.translation.x;
    out.y = t.transform.translation.y;
    if (!std::isfinite(out.x) || !std::isfinite(out.y))
    {
      if (error) *error = "transform " + source_frame + " -> " + target_frame + " has a non-finite translation";
      return std::nullopt;
    }
    try
    {
      out.yaw = planarYaw(t.transform.rotation, kMaxPoseTilt, "transform " + source_frame + " -> " + target_frame);
    }
    catch (const std::invalid_argument& e)
    {
      if (error) *error = e.what();
      return std::nullopt;
    }
    return out;
  }
  catch (const tf2::TransformException& e)
  {
    if (error) *error = e.what();
    return std::nullopt;
  }
  catch (const std::exception& e)
  {
    // tf2 computes with ROS time, which throws beyond 32-bit seconds: a stamp decades off
    if (error) *error = "transform " + source_frame + " -> " + target_frame + ": " + e.what();
    return std::nullopt;
  }
}

void RosLayerContext::report(Severity severity, const std::string& key, const std::string& message)
{
  log_->log(severity, private_nh_.getNamespace() + "/" + key, message);
}
}  // namespace costmap_layers_ros
