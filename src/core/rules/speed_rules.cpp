#include "costmap_layers/core/rules/speed_rules.hpp"

#include <cmath>
#include <limits>

#include "costmap_layers/core/config/input_error.hpp"

namespace costmap_layers
{
Nav2SpeedLimit nav2SpeedLimit(int v, double base, double multiplier, bool percent)
{
  Nav2SpeedLimit r;
  if (v == 0) return r;  // a free cell: no limit
  r.computed = base + multiplier * v;
  const bool in_range =
      percent ? (r.computed >= 0.0 && r.computed <= 100.0) : (std::isfinite(r.computed) && r.computed >= 0.0);
  if (in_range)
    r.speed_limit = r.computed;
  else
    r.out_of_range = true;  // Nav2: "setting it to no-limit value"
  return r;
}

SpeedLimitTable buildSpeedLimitTable(const SpeedLimitsData& limits, bool speed_limit_in_percent,
                                     double default_max_speed, std::vector<SpeedLimitIssue>* issues)
{
  SpeedLimitTable table;
  std::array<bool, SpeedLimitTable::kMaxAreaId + 1> seen{};
  auto issue = [&](bool error, std::size_t index, uint32_t id, const std::string& text)
  {
    if (issues) issues->push_back({error, index, id, text});
  };
  for (std::size_t k = 0; k < limits.limits.size(); ++k)
  {
    const SpeedLimitEntry& e = limits.limits[k];
    const std::string what = "limits[" + std::to_string(k) + "] (area_id " + std::to_string(e.area_id) +
                             ", max_speed " + valueText(e.max_speed) + ")";
    if (e.area_id < 1 || e.area_id > static_cast<uint32_t>(SpeedLimitTable::kMaxAreaId))
    {
      issue(true, k, e.area_id, what + " dropped: area ids must be in 1..100 (mask cell values)");
      continue;
    }
    if (!std::isfinite(e.max_speed) || e.max_speed < 0.0)
    {
      issue(true, k, e.area_id, what + " dropped: max_speed must be a finite number >= 0");
      continue;
    }
    double mps = e.max_speed;
    if (speed_limit_in_percent)
    {
      if (!(e.max_speed > 0.0 && e.max_speed <= 100.0))
      {
        issue(true, k, e.area_id, what + " dropped: in percent mode max_speed must be in (0, 100] [%]");
        continue;
      }
      mps = default_max_speed * (e.max_speed / 100.0);  // <= default_max_speed: cannot overflow
    }
    if (seen[e.area_id])
      issue(false, k, e.area_id,
            what + " repeats area id " + std::to_string(e.area_id) + ": this later entry replaces the earlier one");
    seen[e.area_id] = true;
    table.limit_mps[e.area_id] = mps;
  }
  return table;
}

SpeedPublication speedNoLimit(const SpeedRule& rule)
{
  SpeedPublication p;
  p.max_speed = rule.default_max_speed;
  if (rule.nav2)
  {
    p.percentage = rule.percent;
    p.speed_limit = 0.0;
  }
  else
    p.speed_limit = rule.default_max_speed;  // area_id: the same m/s value as MaxSpeed
  return p;
}

SpeedPublication speedFromNav2Limit(const SpeedRule& rule, double speed_limit)
{
  SpeedPublication p;
  p.percentage = rule.percent;
  p.speed_limit = speed_limit;
  if (speed_limit == 0.0)
    p.max_speed = rule.default_max_speed;
  else if (!p.percentage)
    p.max_speed = speed_limit;
  else if (rule.default_max_speed > 0.0)
    // The fraction first: speed_limit is at most 100 here, so the product is at most
    // default_max_speed and stays finite (the product first overflowed for 1e307 m/s).
    p.max_speed = rule.default_max_speed * (speed_limit / 100.0);
  return p;  // a percentage without default_max_speed has no m/s value
}

SpeedVerdict speedLimitForValue(int8_t v, const SpeedRule& rule, const SpeedLimitTable* table)
{
  SpeedVerdict r;
  r.publication = speedNoLimit(rule);
  if (v == 0) return r;
  if (v < 0 || v > 100)
  {
    r.warning = SpeedWarning::InvalidValue;
    return r;
  }
  if (!rule.nav2)
  {
    // An area the table knows: its limit on both outputs; an unknown one counts as no area.
    if (table && table->limit_mps[static_cast<std::size_t>(v)])
      r.publication.max_speed = r.publication.speed_limit = *table->limit_mps[static_cast<std::size_t>(v)];
    else
      r.warning = SpeedWarning::UnknownArea;
    return r;
  }
  // Nav2's speed mask: the value encodes the limit.
  const Nav2SpeedLimit limit = nav2SpeedLimit(v, rule.base, rule.multiplier, rule.percent);
  r.publication = speedFromNav2Limit(rule, limit.speed_limit);
  r.computed = limit.computed;
  if (limit.out_of_range) r.warning = SpeedWarning::OutOfRange;
  return r;
}

double speedLimitStrictness(double speed_limit)
{
  return speed_limit > 0.0 ? speed_limit : std::numeric_limits<double>::infinity();
}
}  // namespace costmap_layers
