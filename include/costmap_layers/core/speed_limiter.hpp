// Limits velocity commands to the speed a SpeedFilter publishes, for ROS 1 local planners that do not
// read /max_speed. A command is scaled as a whole, so the path's curvature (angular over linear speed)
// is kept.
#pragma once

#include <optional>
#include <string>

namespace costmap_layers
{
/// A velocity command (geometry_msgs/Twist): linear [m/s] and angular [rad/s].
struct Twist
{
  double lx = 0, ly = 0, lz = 0;
  double ax = 0, ay = 0, az = 0;
};

struct SpeedLimiterConfig
{
  double command_timeout = 0.5;         ///< [s] an input older than this is stale
  bool publish_zero_when_stale = true;  ///< on going stale publish one zero command; false: fall silent
};

/// Scales every component of `in` by the same factor so that the planar linear speed
/// hypot(lx, ly) is at most `limit` [m/s]; limit 0 means no limit. Commands already within the limit
/// pass unchanged.
Twist limitTwist(const Twist& in, double limit);

/// Why a value was refused, or nullopt when it is valid.
std::optional<std::string> checkTwist(const Twist& t);
std::optional<std::string> checkMaxSpeed(double max_speed);
}  // namespace costmap_layers
