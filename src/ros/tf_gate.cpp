#include "costmap_layers/ros/tf_gate.hpp"

#include <cmath>
#include <cstdio>

#include "costmap_layers/core/config/input_error.hpp"

namespace costmap_layers_ros
{
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
