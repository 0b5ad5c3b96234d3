#include "costmap_layers/core/filters/speed_lookahead.hpp"

#include <algorithm>
#include <limits>

namespace costmap_layers
{
double speedLookaheadDistance(const std::optional<double>& speed, double max_decel, double min_lookahead,
                              double max_lookahead, double held)
{
  if (!speed || !(max_decel < 0.0)) return max_lookahead;
  return std::max(lookaheadDistance(*speed, max_decel, min_lookahead, max_lookahead), held);
}

SpeedAhead strictestAhead(const std::vector<PathData::Point>& path, std::size_t first, std::size_t end,
                          const std::optional<SpeedPublication>& at_robot, double distance,
                          const std::function<std::optional<SpeedPublication>(const PathData::Point&)>& limit_at)
{
  constexpr double kNone = std::numeric_limits<double>::infinity();
  SpeedAhead r;
  r.best = at_robot;
  for (std::size_t i = first; i < end; ++i)
  {
    const std::optional<SpeedPublication> p = limit_at(path[i]);
    if (!p) continue;
    const double bound = r.best ? speedLimitStrictness(r.best->speed_limit) : kNone;
    if (speedLimitStrictness(p->speed_limit) < bound) r.best = p;
  }
  const double here = at_robot ? speedLimitStrictness(at_robot->speed_limit) : kNone;
  r.held_lookahead = r.best && speedLimitStrictness(r.best->speed_limit) != here ? distance : 0.0;
  return r;
}
}  // namespace costmap_layers
