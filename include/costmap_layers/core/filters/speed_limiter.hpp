// Limits velocity commands to the speed a SpeedFilter publishes, for ROS 1 local planners that do not
// read /max_speed. A command is scaled as a whole, so the path's curvature (angular over linear speed)
// is kept.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "costmap_layers/core/rules/stamp_order.hpp"

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
/// makes it stale. A clock that does not move at all (simulated time with no /clock, or a paused one) cannot
/// time anything: when it has not moved since the last command, command_timeout s of the steady clock
/// make the input stale (a simulation slower than real time still moves, and is timed on its own clock).
/// Not thread-safe: the node holds its mutex.
class CommandWatchdog
{
public:
  enum class Event
  {
    None,
    WentStale,        ///< no command for more than command_timeout: publish the zero command (once)
    ClockJumpedBack,  ///< the timeout restarted at now_ns (worth one warning)
    WentStaleNoClock  ///< as WentStale, timed on the steady clock: the clock has not moved since the command
  };

  /// @param command_timeout [s]; the node refuses values that are not > 0.
  explicit CommandWatchdog(double command_timeout) : timeout_s_(command_timeout) {}

  /// A command arrived at now_ns (steady_ns on a steady clock, 0 without one): the input is fresh.
  void commandReceived(uint64_t now_ns, uint64_t steady_ns = 0)
  {
    clock_.jumpedBack(now_ns);
    last_command_ns_ = now_ns;
    last_command_steady_ns_ = steady_ns;
    stale_ = false;
  }
  /// Called periodically (steady_ns as for commandReceived). WentStale or WentStaleNoClock once when the
  /// input goes stale, then None until the next command.
  Event check(uint64_t now_ns, uint64_t steady_ns = 0);
  /// True before the first command and after WentStale until the next command.
  bool stale() const { return stale_; }

private:
  double timeout_s_;
  uint64_t last_command_ns_ = 0;
  uint64_t last_command_steady_ns_ = 0;
  bool stale_ = true;
  ClockWatch clock_;
};
}  // namespace costmap_layers
