#include "costmap_layers/ros/tf_listener.hpp"

#include <cstdint>
#include <cstdio>

#include "costmap_layers/core/config/input_error.hpp"

namespace costmap_layers_ros
{
std::string tfStampProblem(const ros::Time& stamp, const ros::Duration& cache_length, const ros::Time& now,
                           bool is_static)
{
  // The last instant ROS time holds, in nanoseconds; tf2 computes stamp + cache_length.
  constexpr uint64_t kLastNs = 0xFFFFFFFFull * 1000000000ull + 999999999ull;
  const uint64_t cache_ns = cache_length.toNSec() > 0 ? static_cast<uint64_t>(cache_length.toNSec()) : 0;
  char text[200];
  if (stamp.toNSec() <= kLastNs - cache_ns)
  {
    // Both sides in nanoseconds below 2^63: no overflow.
    if (is_static || now.isZero() || stamp.toNSec() <= now.toNSec() + cache_ns) return {};
    std::snprintf(text, sizeof(text),
                  "header.stamp %u.%09u s is more than tf's cache length (%.1f s) ahead of now (%u.%09u s): tf would "
                  "refuse every later transform of this frame",
                  stamp.sec, stamp.nsec, cache_length.toSec(), now.sec, now.nsec);
    return text;
  }
  std::snprintf(text, sizeof(text),
                "header.stamp %u.%09u s is within tf's cache length (%.1f s) of the end of ROS time", stamp.sec,
                stamp.nsec, cache_length.toSec());
  return text;
}

GuardedTfListener::GuardedTfListener(tf2_ros::Buffer& buffer, std::shared_ptr<ThrottledLog> log, std::string owner)
    : buffer_(buffer),
      log_(std::move(log)),
      owner_(std::move(owner)),
      queue_([this](const std::string& problem)
             { log_->log(costmap_layers::Severity::Error, owner_ + "/tf/callback", owner_ + ": tf: " + problem); })
{
  nh_.setCallbackQueue(&queue_);
  // As tf2_ros: /tf in order and without delay, /tf_static latched by its publishers. Each message goes
  // into the buffer in roscpp's network thread, as it is read (InlineCallbackQueue).
  const auto subscribe = [this](const std::string& topic, bool is_static)
  {
    ros::SubscribeOptions options;
    options.init<tf2_msgs::TFMessage>(topic, 100,
                                      [this, is_static](const ros::MessageEvent<const tf2_msgs::TFMessage>& e)
                                      { receive(e, is_static); });
    options.transport_hints = ros::TransportHints().tcpNoDelay();
    options.allow_concurrent_callbacks = true;  // receive() takes a lock of its own
    return nh_.subscribe(options);
  };
  tf_sub_ = subscribe("/tf", false);
  static_sub_ = subscribe("/tf_static", true);
  // Look-ups with a timeout may wait: the network thread fills the buffer meanwhile (as tf2_ros's thread).
  buffer_.setUsingDedicatedThread(true);
}

GuardedTfListener::~GuardedTfListener()
{
  tf_sub_.shutdown();  // returns once a message being received is in the buffer; none comes after
  static_sub_.shutdown();
}

void GuardedTfListener::receive(const ros::MessageEvent<const tf2_msgs::TFMessage>& event, bool is_static)
{
  // One message at a time, in arrival order: both topics come through roscpp's network thread, but a
  // publisher in this process delivers in its own thread.
  std::lock_guard<std::mutex> lock(receive_mutex_);
  const ros::Time now = ros::Time::now();
  if (now < last_update_)
  {
    // A restarted simulation or bag: what the buffer holds belongs to the old timeline.
    log_->log(costmap_layers::Severity::Warn, owner_ + "/tf/clock",
              owner_ + ": the clock jumped back: tf's buffer is cleared (as tf2_ros does)");
    buffer_.clear();
  }
  last_update_ = now;
  // The sender, as tf2_ros names it (the buffer keeps it as the transform's authority).
  std::string authority = "unknown";
  if (const auto header = event.getConnectionHeaderPtr())
  {
    const auto caller = header->find("callerid");
    if (caller != header->end()) authority = caller->second;
  }
  const tf2_msgs::TFMessage& msg = *event.getConstMessage();
  for (std::size_t k = 0; k < msg.transforms.size(); ++k)
  {
    const geometry_msgs::TransformStamped& t = msg.transforms[k];
    std::string problem = tfStampProblem(t.header.stamp, buffer_.getCacheLength(), now, is_static);
    if (problem.empty())
    {
      try
      {
        buffer_.setTransform(t, authority, is_static);
        continue;
      }
      catch (const std::exception& e)
      {
        problem = e.what();
      }
    }
    const std::string topic = is_static ? "/tf_static" : "/tf";
    log_->log(costmap_layers::Severity::Error, owner_ + "/tf/transforms",
              owner_ + ": dropped transforms[" + std::to_string(k) + "] (" +
                  costmap_layers::shownText(t.header.frame_id) + " -> " + costmap_layers::shownText(t.child_frame_id) +
                  ") on " + topic + " from " + costmap_layers::shownText(authority) + ": " +
                  costmap_layers::shownText(problem, 400));
  }
}
}  // namespace costmap_layers_ros
