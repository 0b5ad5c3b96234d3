// The speed rules of SpeedFilter, as pure functions: what a speed mask value limits the robot to, how
// a features message becomes a table of limits, and which of two limits is stricter. They return the
// limit and what is wrong with the input (a SpeedWarning, or issues with their text); they never
// report: SpeedFilter decides what to log and how often (filters/speed_filter.hpp documents the
// behaviour these rules implement).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "costmap_layers/core/data/grid_data.hpp"

namespace costmap_layers
{
/// Nav2's speed limit for a mask value v in 0..100: v = 0 -> no limit; else L = base + multiplier * v,
/// out of range (then "no limit") when, in percent, L < 0 or L > 100, in m/s when L < 0 or not finite.
struct Nav2SpeedLimit
{
  double speed_limit = 0.0;   ///< what Nav2 publishes: [%] or [m/s], 0 = no limit
  double computed = 0.0;      ///< base + multiplier * v (0 for v = 0)
  bool out_of_range = false;  ///< computed was replaced by "no limit"
};
Nav2SpeedLimit nav2SpeedLimit(int v, double base, double multiplier, bool percent);

/// The valid limits of one features message, by area id, already in m/s.
struct SpeedLimitTable
{
  static constexpr int kMaxAreaId = 100;
  /// limit_mps[id] for id in 1..100; nullopt when the message gave none (or only bad ones).
  std::array<std::optional<double>, kMaxAreaId + 1> limit_mps{};
};

/// One problem found in a features message.
struct SpeedLimitIssue
{
  bool error = true;      ///< true: the entry was dropped; false: a warning (duplicate id)
  std::size_t index = 0;  ///< index of the entry in the message
  uint32_t area_id = 0;
  std::string message;  ///< one line, names the entry, its values and the rule
};

/// Checks a features message entry by entry (ids in 1..100; max_speed finite and >= 0; in percent mode
/// in (0, 100], converted to m/s as default_max_speed * max_speed / 100; a repeated id: the later entry
/// wins, with a warning). Problems are appended to issues (may be nullptr).
SpeedLimitTable buildSpeedLimitTable(const SpeedLimitsData& limits, bool speed_limit_in_percent,
                                     double default_max_speed, std::vector<SpeedLimitIssue>* issues);

/// What a SpeedFilter publishes for one evaluation, for both of its outputs.
struct SpeedPublication
{
  std::optional<double> max_speed;  ///< [m/s]; nullopt: cannot be given in m/s (percent, no default)
  bool percentage = false;          ///< Nav2SpeedLimit
  double speed_limit = 0.0;         ///< Nav2SpeedLimit: [%] or [m/s], 0 = no limit
};

/// The settings the rules read, as in force at one evaluation.
struct SpeedRule
{
  bool nav2 = false;               ///< the value encodes the limit (nav2 mode or the filter-info form)
  bool percent = false;            ///< nav2: limits in percent of default_max_speed
  double default_max_speed = 0.0;  ///< [m/s]; 0 = no limit
  double base = 0.0;               ///< nav2: L = base + multiplier * v
  double multiplier = 1.0;
};

/// "No limit": MaxSpeed default_max_speed; Nav2SpeedLimit 0 in nav2 (in its unit), or
/// default_max_speed in m/s in area_id mode.
SpeedPublication speedNoLimit(const SpeedRule& rule);

/// Nav2's limit L ([%] or [m/s], 0 = none) as both outputs carry it: MaxSpeed is L in m/s,
/// default_max_speed * L / 100 in percent, default_max_speed for no limit, and nothing for a
/// percentage while default_max_speed is 0.
SpeedPublication speedFromNav2Limit(const SpeedRule& rule, double speed_limit);

/// What is wrong with a mask value, for the filter to report.
enum class SpeedWarning
{
  None,
  InvalidValue,  ///< outside -1..100 (invalid in an OccupancyGrid): no limit
  UnknownArea,   ///< area_id: the id has no limit (or no features message came yet): no area
  OutOfRange     ///< nav2: base + multiplier * v is out of range (Nav2's rule: no limit)
};

struct SpeedVerdict
{
  SpeedPublication publication;
  SpeedWarning warning = SpeedWarning::None;
  double computed = 0.0;  ///< OutOfRange: base + multiplier * v
};

/// The limit for a mask value other than -1 (0 = no limit; area_id: the table's limit of area v;
/// nav2: nav2SpeedLimit()). table may be nullptr (no features message yet).
SpeedVerdict speedLimitForValue(int8_t v, const SpeedRule& rule, const SpeedLimitTable* table);

/// How strict a published speed_limit is: smaller is stricter; 0 (no limit) is the least strict
/// (infinity).
double speedLimitStrictness(double speed_limit);
}  // namespace costmap_layers
