// Limits velocity commands to the speed a SpeedFilter publishes, for ROS 1 local planners that do not
// read /max_speed. A command is scaled as a whole, so the path's curvature (angular over linear speed)
// is kept.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "costmap_layers/core/stamp_order.hpp"

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

/// Decides when the command input went stale (the node's watchdog); times [ns] are passed in. A jump of
/// the clock back (now more than kClockJumpBackToleranceNs before the last command or the latest check)
/// restarts the timeout at the jump: the input goes stale command_timeout s later unless a command
/// arrives, instead of staying fresh until the clock is back at the last command's time. A jump forward
/// makes it stale. Not thread-safe: the node holds its mutex.
class CommandWatchdog
{
public:
  enum class Event
  {
    None,
    WentStale,       ///< no command for more than command_timeout: publish the zero command (once)
    ClockJumpedBack  ///< the timeout restarted at now_ns (worth one warning)
  };

  /// @param command_timeout [s]; the node refuses values that are not > 0.
  explicit CommandWatchdog(double command_timeout) : timeout_s_(command_timeout) {}

  /// A command arrived at now_ns: the input is fresh.
  void commandReceived(uint64_t now_ns)
  {
    clock_.jumpedBack(now_ns);
    last_command_ns_ = now_ns;
    stale_ = false;
  }
  /// Called periodically. WentStale once when the input goes stale, then None until the next command.
  Event check(uint64_t now_ns);
  /// True before the first command and after WentStale until the next command.
  bool stale() const { return stale_; }

private:
  double timeout_s_;
  uint64_t last_command_ns_ = 0;
  bool stale_ = true;
  ClockWatch clock_;
};
}  // namespace costmap_layers
