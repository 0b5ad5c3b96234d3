#include "costmap_layers/core/stamp_order.hpp"

#include <cstdio>

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
}  // namespace costmap_layers
