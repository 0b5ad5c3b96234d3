#include "costmap_layers/core/costmap/layer_status.hpp"

#include <cstdio>

namespace costmap_layers
{
void LayerStatus::raise(StatusLevel at_least, const std::string& why)
{
  if (at_least > level)
  {
    level = at_least;
    message = why;
  }
  else if (at_least == level && level != StatusLevel::Ok)
    message = message.empty() ? why : message + "; " + why;
}

std::string LayerStatus::value(const std::string& key) const
{
  for (const auto& [k, v] : values)
    if (k == key) return v;
  return {};
}

std::string describeAge(double seconds)
{
  if (seconds < 0.0) return "never";
  char text[48];
  std::snprintf(text, sizeof(text), "%.2f s ago", seconds);
  return text;
}

double secondsBetween(uint64_t then_ns, uint64_t now_ns)
{
  return now_ns > then_ns ? static_cast<double>(now_ns - then_ns) * 1e-9 : 0.0;
}
}  // namespace costmap_layers
