#include "costmap_layers/ros/tf_gate.hpp"

#include <cmath>
#include <cstdio>

#include "costmap_layers/core/config/input_error.hpp"

namespace costmap_layers_ros
{
TfChangeWake::TfChangeWake(tf2::BufferCore& tf, std::function<void()> retry) : shared_(std::make_shared<Shared>())
{
  shared_->retry = std::move(retry);
  // The slot holds the shared state, not this object: a signal already under way when the destructor
  // disconnects finds alive false.
  connection_ = tf._addTransformsChangedListener(
      [shared = shared_]
      {
        std::lock_guard<std::mutex> lock(shared->mutex);
        if (shared->alive) shared->retry();
      });
}

TfChangeWake::~TfChangeWake()
{
  {
    std::lock_guard<std::mutex> lock(shared_->mutex);  // waits for a retry under way
    shared_->alive = false;
  }
  connection_.disconnect();  // safe when the buffer has gone first
}

GateFailure gateFailure(const std::string& owner, const std::string& topic, const std::string& global,
                        const std::string& sensor_frame, const std::string& frame_id, const ros::Time& stamp,
                        const ros::Time& now, TfVerdict verdict)
{
  // Each reason is its own throttled report, so that a stale stamp does not hide a wrong frame.
  std::string key = owner + topic + "/tf/", why;
  const double behind = secondsBetween(now, stamp);
  char when[96];
  std::snprintf(when, sizeof(when), "header.stamp %.3f s (%.3f s %s now)", stamp.toSec(), std::fabs(behind),
                behind >= 0.0 ? "before" : "after");
  switch (verdict)
  {
    case TfVerdict::NoFrame:
      key += "frame_id";
      why = "header.frame_id is empty";
      break;
    case TfVerdict::TooOld:
      key += "stamp";
      why = std::string(when) + " is older than every transform tf keeps";
      break;
    case TfVerdict::BadStamp:
      key += "stamp";
      why = std::string(when) + " is beyond what tf can compute with";
      break;
    case TfVerdict::Future:
      key += "future";
      why = std::string(when) + " is more than " + costmap_layers::valueText(kGateMaxAhead) +
            " s ahead of the clock (a wrong sensor clock, or the clock jumped back)";
      break;
    default:
      key += "wait";
      why = std::string("no transform at ") + when + " arrived while " + std::to_string(kGateQueue) +
            " newer readings waited";
      break;
  }
  return {key, owner + ": dropped a reading on " + topic + ": cannot transform frame '" +
                   costmap_layers::shownText(frame_id) + "'" +
                   (sensor_frame.empty() ? std::string() : " (sensor_frame '" + sensor_frame + "')") + " into '" +
                   global + "': " + why};
}
}  // namespace costmap_layers_ros
