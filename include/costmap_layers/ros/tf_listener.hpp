// The node's tf listener: what tf2_ros::TransformListener does (reading /tf and /tf_static into the
// buffer, here in roscpp's network thread rather than a thread of its own, the buffer cleared when the
// clock jumps back), with every transform's
// stamp checked first. tf2 adds the cache length to a stamp with ROS time arithmetic, which throws
// past the last second ROS time holds; tf2_ros's listener catches only tf2's own exceptions, so one
// /tf message stamped secs = 0xFFFFFFFF ended the whole node.
#pragma once

#include <ros/ros.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/buffer.h>

#include <memory>
#include <mutex>
#include <string>

#include "costmap_layers/ros/inline_callback_queue.hpp"
#include "costmap_layers/ros/ros_layer_context.hpp"

namespace costmap_layers_ros
{
/// Why tf's buffer cannot take a transform stamped `stamp` when it keeps `cache_length` of them, or ""
/// when it can. With `now` (non-zero) and a transform that is not static, also a stamp more than the
/// cache length ahead of now: tf2 would keep it and refuse every later transform of that frame as too
/// old, freezing the frame (the robot's pose) until a restart.
std::string tfStampProblem(const ros::Time& stamp, const ros::Duration& cache_length, const ros::Time& now = {},
                           bool is_static = false);

class GuardedTfListener
{
public:
  /// Starts reading /tf and /tf_static into buffer; problems go to log under "<owner>/tf/...".
  GuardedTfListener(tf2_ros::Buffer& buffer, std::shared_ptr<ThrottledLog> log, std::string owner);
  ~GuardedTfListener();
  GuardedTfListener(const GuardedTfListener&) = delete;
  GuardedTfListener& operator=(const GuardedTfListener&) = delete;

private:
  void receive(const ros::MessageEvent<const tf2_msgs::TFMessage>& event, bool is_static);

  tf2_ros::Buffer& buffer_;
  std::shared_ptr<ThrottledLog> log_;
  std::string owner_;
  InlineCallbackQueue queue_;  ///< outlives the subscriptions (declared before them)
  ros::NodeHandle nh_;
  ros::Subscriber tf_sub_;
  ros::Subscriber static_sub_;
  std::mutex receive_mutex_;
  ros::Time last_update_;  ///< the clock at the last message (guarded by receive_mutex_)
};
}  // namespace costmap_layers_ros
