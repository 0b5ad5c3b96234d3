#include "costmap_layers/core/speed_filter.hpp"

#include <cmath>
#include <sstream>

#include "costmap_layers/core/param_reader.hpp"
#include "costmap_layers/core/stamp_order.hpp"

namespace costmap_layers
{
namespace
{
std::string num(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}
}  // namespace

SpeedFilterConfig parseSpeedFilterConfig(const ParamReader& params)
{
  SpeedFilterConfig c;
  c.features_topic = params.getString("features_topic", c.features_topic);
  c.max_speed_topic = params.getString("max_speed_topic", c.max_speed_topic);
  c.default_max_speed = params.getDouble("default_max_speed", c.default_max_speed, 0.0);
  c.speed_limit_in_percent = params.getBool("speed_limit_in_percent", c.speed_limit_in_percent);
  const std::string mode = params.getChoice("mask_mode", "area_id", {"area_id", "nav2"});
  c.mask_mode = mode == "nav2" ? SpeedMaskMode::Nav2 : SpeedMaskMode::AreaId;
  c.base = params.getDouble("base", c.base);
  c.multiplier = params.getDouble("multiplier", c.multiplier);
  if (c.speed_limit_in_percent && c.default_max_speed <= 0.0)
    params.fail("speed_limit_in_percent",
                "is true while 'default_max_speed' is 0 (no limit): percent limits are percentages of "
                "default_max_speed, so set default_max_speed to the robot's top speed [m/s] (> 0) or set "
                "speed_limit_in_percent to false");
  return c;
}

SpeedLimitTable buildSpeedLimitTable(const SpeedLimitsData& limits, const SpeedFilterConfig& config,
                                     std::vector<SpeedLimitIssue>* issues)
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
                             ", max_speed " + num(e.max_speed) + ")";
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
    if (config.speed_limit_in_percent)
    {
      if (!(e.max_speed > 0.0 && e.max_speed <= 100.0))
      {
        issue(true, k, e.area_id, what + " dropped: in percent mode max_speed must be in (0, 100] [%]");
        continue;
      }
      mps = config.default_max_speed * (e.max_speed / 100.0);  // <= default_max_speed: cannot overflow
    }
    if (seen[e.area_id])
      issue(false, k, e.area_id,
            what + " repeats area id " + std::to_string(e.area_id) + ": this later entry replaces the earlier one");
    seen[e.area_id] = true;
    table.limit_mps[e.area_id] = mps;
  }
  return table;
}

void SpeedFilter::onInitializeFilter(const ParamReader& params)
{
  config_ = parseSpeedFilterConfig(params);
  addOutput(OutputPort{OutputKind::MaxSpeed, config_.max_speed_topic});
  if (config_.mask_mode == SpeedMaskMode::AreaId)
    addInput(InputPort::speedLimits(config_.features_topic,
                                    [this](const std::shared_ptr<const SpeedLimitsData>& m)
                                    {
                                      if (m) setSpeedLimits(*m);
                                    }));
}

std::size_t SpeedFilter::setSpeedLimits(const SpeedLimitsData& limits)
{
  SpeedFilterConfig config;
  const uint64_t now = context_ ? context_->nowNs() : UINT64_MAX;
  {
    std::lock_guard<std::mutex> lock(limits_mutex_);
    config = config_;
    if (last_features_ && isOutOfOrder(limits.stamp_ns, last_features_->stamp_ns, now))
    {
      const std::string error = outOfOrderError(limits.stamp_ns, last_features_->stamp_ns, "speed limits message");
      if (context_)
        context_->report(Severity::Error, "features_stamp",
                         name_ + ": " + config.features_topic + ": rejected, keeping the previous limits: " + error);
      return limits.limits.size();
    }
    last_features_ = std::make_shared<const SpeedLimitsData>(limits);
  }
  std::vector<SpeedLimitIssue> issues;
  auto table = std::make_shared<SpeedLimitTable>(buildSpeedLimitTable(limits, config, &issues));
  // One report per kind of problem and message, keyed by the field, naming at most kListed entries:
  // however many entries a sender puts in, the log gets at most two lines per throttle period, each
  // of bounded length, and the throttle table two keys.
  constexpr std::size_t kListed = 8;
  std::size_t dropped = 0, duplicates = 0;
  std::string errors, repeats;
  for (const auto& i : issues)
  {
    std::size_t& n = i.error ? dropped : duplicates;
    std::string& text = i.error ? errors : repeats;
    if (n++ < kListed) text += (text.empty() ? "" : "; ") + i.message;
  }
  const auto more = [](std::size_t n) { return n > kListed ? "; and " + std::to_string(n - kListed) + " more" : ""; };
  if (dropped != 0 && context_)
    context_->report(Severity::Error, "features/limits",
                     name_ + ": " + config.features_topic + ": " + std::to_string(dropped) + " of " +
                         std::to_string(limits.limits.size()) + " entries dropped: " + errors + more(dropped));
  if (duplicates != 0 && context_)
    context_->report(Severity::Warn, "features/limits.area_id",
                     name_ + ": " + config.features_topic + ": " + std::to_string(duplicates) +
                         " repeated area id(s): " + repeats + more(duplicates));
  std::lock_guard<std::mutex> lock(limits_mutex_);
  // A dropped entry keeps its area's last good limit (an area the message leaves out has none).
  for (const auto& i : issues)
  {
    if (!i.error || i.area_id < 1 || i.area_id > SpeedLimitTable::kMaxAreaId || !limits_) continue;
    auto& slot = table->limit_mps[i.area_id];
    if (!slot) slot = limits_->limit_mps[i.area_id];
  }
  limits_ = std::move(table);
  return dropped;
}

namespace
{
bool runTimeTunable(const std::string& name)
{
  return name != "features_topic" && name != "max_speed_topic" && name != "mask_mode";
}
}  // namespace

void SpeedFilter::onReconfigure(const ParamValue& params)
{
  const ParamReader reader(params, name_);
  const SpeedFilterConfig next = parseSpeedFilterConfig(reader);  // validates first
  if (next.features_topic != config_.features_topic || next.max_speed_topic != config_.max_speed_topic ||
      next.mask_mode != config_.mask_mode)
    throw std::invalid_argument(name_ + ": features_topic, max_speed_topic and mask_mode cannot change at run time");
  std::shared_ptr<const SpeedLimitsData> features;
  {
    std::lock_guard<std::mutex> lock(limits_mutex_);
    config_ = next;
    features = last_features_;
  }
  if (features) setSpeedLimits(*features);  // percentages depend on default_max_speed
}

std::vector<ParamSpec> SpeedFilter::tunableLayerParameters(const ParamValue& params) const
{
  std::vector<ParamSpec> all = recordParameters(params, name_, [](const ParamReader& r) { parseSpeedFilterConfig(r); });
  std::vector<ParamSpec> tunable;
  for (auto& p : all)
    if (runTimeTunable(p.name)) tunable.push_back(std::move(p));
  return tunable;
}

void SpeedFilter::warnValueOnce(int8_t v, const std::string& message)
{
  const std::size_t bit = static_cast<uint8_t>(v);
  if (warned_values_.test(bit)) return;
  warned_values_.set(bit);
  context_->report(Severity::Warn, "mask/value", name_ + ": " + message);
}

double SpeedFilter::limitForValue(int8_t v, const SpeedLimitTable* table)
{
  const double none = config_.default_max_speed;
  if (v == 0) return none;
  if (v < 0 || v > 100)
  {
    warnValueOnce(v, "the mask holds the value " + std::to_string(v) +
                         " (outside -1..100, invalid in an OccupancyGrid); publishing default_max_speed there");
    return none;
  }
  if (config_.mask_mode == SpeedMaskMode::AreaId)
  {
    if (table && table->limit_mps[static_cast<std::size_t>(v)]) return *table->limit_mps[static_cast<std::size_t>(v)];
    if (!warned_ids_.test(static_cast<std::size_t>(v)))
    {
      warned_ids_.set(static_cast<std::size_t>(v));
      context_->report(Severity::Warn, "mask/area_id",
                       name_ + ": the robot is in area " + std::to_string(v) +
                           " of the mask, which has no speed "
                           "limit" +
                           (table ? " in the last message on " : " yet (nothing received on ") +
                           config_.features_topic + (table ? "" : ")") +
                           "; treating it as no area (default_max_speed " + num(none) + " m/s)");
    }
    return none;
  }
  // Nav2 speed mask: the value encodes the limit.
  const double limit = config_.base + config_.multiplier * v;
  if (config_.speed_limit_in_percent)
  {
    if (limit > 0.0 && limit <= 100.0) return config_.default_max_speed * limit / 100.0;
    warnValueOnce(v, "mask value " + std::to_string(v) + " gives base + multiplier * v = " + num(limit) +
                         " %, outside (0, 100]; publishing default_max_speed (no limit) there");
    return none;
  }
  if (std::isfinite(limit) && limit > 0.0) return limit;
  warnValueOnce(v, "mask value " + std::to_string(v) + " gives base + multiplier * v = " + num(limit) +
                       " m/s, not > 0; publishing default_max_speed (no limit) there");
  return none;
}

void SpeedFilter::processPose(const OccupancyGridData& mask, const Transform2D& to_mask, double robot_x, double robot_y,
                              double)
{
  std::shared_ptr<const SpeedLimitTable> table;
  {
    std::lock_guard<std::mutex> lock(limits_mutex_);
    table = limits_;
  }
  if (table != active_limits_)
  {
    active_limits_ = std::move(table);
    warned_ids_.reset();  // a new message: its missing ids are a new problem
  }
  const std::optional<int8_t> v = maskValueAt(mask, to_mask, robot_x, robot_y);
  double speed = config_.default_max_speed;
  if (v && *v == -1)
    speed = last_published_ ? *last_published_ : config_.default_max_speed;
  else if (v)
    speed = limitForValue(*v, active_limits_.get());
  publishIfChanged(speed);
}

void SpeedFilter::publishIfChanged(double speed)
{
  if (last_published_ && *last_published_ == speed) return;
  last_published_ = speed;
  emit(OutputKind::MaxSpeed, config_.max_speed_topic, speed);
}
}  // namespace costmap_layers
