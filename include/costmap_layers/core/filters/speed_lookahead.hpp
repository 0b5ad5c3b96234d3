// The path lookahead of SpeedFilter (Nav2's enable_path_lookahead), without its inputs: how far to look
// this cycle, and the strictest limit at the robot and along the path ahead. The filter owns the path,
// the odometry, the transform and the reports (filters/speed_filter.hpp documents the behaviour).
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "costmap_layers/core/data/path_data.hpp"
#include "costmap_layers/core/rules/speed_rules.hpp"

namespace costmap_layers
{
/// The lookahead distance of one cycle [m]: max_lookahead without a speed (no or stale odometry, the
/// cautious choice) or with max_decel 0; else lookaheadDistance() at |speed|, but not below held (Nav2's
/// hold: slowing down must not lift the limit that made the robot slow down).
double speedLookaheadDistance(const std::optional<double>& speed, double max_decel, double min_lookahead,
                              double max_lookahead, double held);

struct SpeedAhead
{
  std::optional<SpeedPublication> best;  ///< the strictest (nullopt: unknown at the robot, nothing ahead)
  double held_lookahead = 0.0;           ///< [m] the hold for the next cycle
};

/// The strictest publication (speedLimitStrictness()) of at_robot and of the poses [first, end) of the
/// path; limit_at gives a pose's publication, or nullopt where it adds nothing (outside the mask, an
/// unknown cell). Poses are visited in order and a later one wins only when strictly stricter. The hold
/// is `distance` while the best differs in strictness from at_robot, else 0.
SpeedAhead strictestAhead(const std::vector<PathData::Point>& path, std::size_t first, std::size_t end,
                          const std::optional<SpeedPublication>& at_robot, double distance,
                          const std::function<std::optional<SpeedPublication>(const PathData::Point&)>& limit_at);
}  // namespace costmap_layers
