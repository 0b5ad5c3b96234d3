#include "costmap_layers/core/filters/speed_limiter.hpp"

#include <cmath>
#include <sstream>

namespace costmap_layers
{
Twist limitTwist(const Twist& in, double limit)
{
  const double speed = std::hypot(in.lx, in.ly);
  if (!(limit > 0.0) || speed <= limit) return in;
  const double f = limit / speed;
  return Twist{in.lx * f, in.ly * f, in.lz * f, in.ax * f, in.ay * f, in.az * f};
}

std::optional<std::string> checkTwist(const Twist& t)
{
  const double v[6] = {t.lx, t.ly, t.lz, t.ax, t.ay, t.az};
  const char* names[6] = {"linear.x", "linear.y", "linear.z", "angular.x", "angular.y", "angular.z"};
  for (int k = 0; k < 6; ++k)
  {
    if (!std::isfinite(v[k]))
    {
      std::ostringstream s;
      s << names[k] << " is not finite (" << v[k] << ")";
      return s.str();
    }
  }
  return std::nullopt;
}

std::optional<std::string> checkMaxSpeed(double max_speed)
{
  if (std::isfinite(max_speed) && max_speed >= 0.0) return std::nullopt;
  std::ostringstream s;
  s << "max_speed must be finite and >= 0 (got " << max_speed << ")";
  return s.str();
}

CommandWatchdog::Event CommandWatchdog::check(uint64_t now_ns, uint64_t steady_ns)
{
  // Noted even while stale; commandReceived() notes its times too, so a jump back below the last
  // command is seen here.
  const bool jumped = clock_.jumpedBack(now_ns);
  if (stale_) return Event::None;
  if (jumped)
  {
    last_command_ns_ = now_ns;
    return Event::ClockJumpedBack;
  }
  if (now_ns == last_command_ns_ && steady_ns > last_command_steady_ns_ &&
      static_cast<double>(steady_ns - last_command_steady_ns_) * 1e-9 > timeout_s_)
  {
    stale_ = true;
    return Event::WentStaleNoClock;
  }
  if (now_ns <= last_command_ns_) return Event::None;  // a step back within the tolerance
  if (static_cast<double>(now_ns - last_command_ns_) * 1e-9 <= timeout_s_) return Event::None;
  stale_ = true;
  return Event::WentStale;
}
}  // namespace costmap_layers
