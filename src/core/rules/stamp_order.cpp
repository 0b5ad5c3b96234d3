#include "costmap_layers/core/rules/stamp_order.hpp"

#include <cstdio>

#include "costmap_layers/core/config/input_error.hpp"

namespace costmap_layers
{
namespace
{
std::string seconds(uint64_t ns)
{
  char text[48];
  std::snprintf(text, sizeof(text), "%.3f s", static_cast<double>(ns) * 1e-9);
  return text;
}
}  // namespace

std::string outOfOrderError(uint64_t stamp_ns, uint64_t in_force_ns, const std::string& what)
{
  return "header.stamp " + seconds(stamp_ns) + " is older than the " + what + " in force (stamped " +
         seconds(in_force_ns) + "): an out-of-order or replayed message";
}

std::string aheadOfNowError(uint64_t stamp_ns, uint64_t now_ns)
{
  return "header.stamp " + seconds(stamp_ns) + " is " + seconds(stamp_ns > now_ns ? stamp_ns - now_ns : 0) +
         " ahead of now " + seconds(now_ns) +
         " (clock skew between hosts, or a reading from before the clock jumped back)";
}

std::string olderThanPersistenceError(uint64_t stamp_ns, uint64_t now_ns, double observation_persistence)
{
  return "header.stamp " + seconds(stamp_ns) + " is " + seconds(now_ns > stamp_ns ? now_ns - stamp_ns : 0) +
         " old at now " + seconds(now_ns) + ", more than observation_persistence (" +
         valueText(observation_persistence) +
         " s): it would expire on arrival (a sensor clock behind this host's, or a slow driver?)";
}

std::string clockJumpMessage(uint64_t from_ns, uint64_t to_ns)
{
  return "the clock jumped back from " + seconds(from_ns) + " to " + seconds(to_ns) +
         " (a looping bag or a restarted simulator?)";
}
}  // namespace costmap_layers
