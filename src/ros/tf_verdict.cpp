#include "costmap_layers/ros/tf_verdict.hpp"

#include <exception>

namespace costmap_layers_ros
{
TfVerdict tfVerdict(tf2::BufferCore& tf, const std::string& target, const std::string& frame, const ros::Time& stamp,
                    const ros::Time& now, double max_ahead)
{
  if (frame.empty()) return TfVerdict::NoFrame;
  if (secondsBetween(stamp, now) > max_ahead) return TfVerdict::Future;
  try
  {
    if (tf.canTransform(target, frame, stamp)) return TfVerdict::Ready;
  }
  catch (const std::exception&)
  {
    // tf2 computes with ROS time, which throws beyond 32-bit seconds (a stamp decades before now)
    return TfVerdict::BadStamp;
  }
  try
  {
    // The newest transform tf has between the frames; the reading is beyond hope when even the
    // oldest one tf still keeps is newer than it.
    const ros::Time latest = tf.lookupTransform(target, frame, ros::Time(0)).header.stamp;
    if (!latest.isZero() && secondsBetween(latest, stamp) > tf.getCacheLength().toSec()) return TfVerdict::TooOld;
  }
  catch (const std::exception&)
  {
    // frames not connected (yet): wait
  }
  return TfVerdict::Wait;
}

TfVerdict gateVerdict(tf2::BufferCore& tf, const std::string& target, const std::string& frame,
                      const std::string& sensor_frame, const ros::Time& stamp, const ros::Time& now, double max_ahead)
{
  const TfVerdict v = tfVerdict(tf, target, frame, stamp, now, max_ahead);
  if (v != TfVerdict::Ready || sensor_frame.empty() || sensor_frame == frame) return v;
  return tfVerdict(tf, target, sensor_frame, stamp, now, max_ahead);
}
}  // namespace costmap_layers_ros
