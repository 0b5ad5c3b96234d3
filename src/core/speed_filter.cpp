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
  // Read without recording (the base reads it): it cannot change at run time.
  const ParamValue* info_topic = params.raw("filter_info_topic");
  c.filter_info = info_topic && info_topic->type() == ParamValue::Type::String && !info_topic->asString().empty();
  if (c.filter_info)
    for (const char* held : {"mask_mode", "base", "multiplier", "speed_limit_in_percent", "features_topic"})
      if (params.has(held))
        params.fail(held, std::string("is set together with 'filter_info_topic' (") + info_topic->toString() +
                              "): the filter info (costmap_filter_info_server) gives the unit (type 1 percent, 2 "
                              "m/s), base and multiplier, and the mask holds the limits; remove '" +
                              held + "', or configure the filter with mask_topic instead");
  c.max_speed_topic = params.getString("max_speed_topic", c.max_speed_topic);
  c.speed_limit_topic = params.getString("speed_limit_topic", c.speed_limit_topic);
  c.default_max_speed = params.getDouble("default_max_speed", c.default_max_speed, 0.0);
  if (c.filter_info)
  {
    c.mask_mode = SpeedMaskMode::Nav2;
    return c;
  }
  c.features_topic = params.getString("features_topic", c.features_topic);
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
  if (!config_.speed_limit_topic.empty()) addOutput(OutputPort{OutputKind::SpeedLimit, config_.speed_limit_topic});
  if (!config_.filter_info && config_.mask_mode == SpeedMaskMode::AreaId)
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
  return name != "features_topic" && name != "max_speed_topic" && name != "speed_limit_topic" && name != "mask_mode";
}
}  // namespace

void SpeedFilter::onReconfigure(const ParamValue& params)
{
  const ParamReader reader(params, name_);
  const SpeedFilterConfig next = parseSpeedFilterConfig(reader);  // validates first
  if (next.features_topic != config_.features_topic || next.max_speed_topic != config_.max_speed_topic ||
      next.speed_limit_topic != config_.speed_limit_topic || next.mask_mode != config_.mask_mode ||
      next.filter_info != config_.filter_info)
    throw std::invalid_argument(name_ +
                                ": features_topic, max_speed_topic, speed_limit_topic, mask_mode and "
                                "filter_info_topic cannot change at run time");
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

bool SpeedFilter::nav2Rule() const
{
  return config_.filter_info || config_.mask_mode == SpeedMaskMode::Nav2;
}

bool SpeedFilter::percentUnit() const
{
  if (config_.filter_info) return activeInfo() && activeInfo()->type == filter_info::kSpeedPercent;
  return config_.speed_limit_in_percent;
}

SpeedFilter::Publication SpeedFilter::noLimit() const
{
  Publication p;
  p.max_speed = config_.default_max_speed;
  if (nav2Rule())
  {
    p.percentage = percentUnit();
    p.speed_limit = 0.0;
  }
  else
    p.speed_limit = config_.default_max_speed;  // area_id: the same m/s value as MaxSpeed
  return p;
}

SpeedFilter::Publication SpeedFilter::fromNav2Limit(double speed_limit) const
{
  Publication p;
  p.percentage = percentUnit();
  p.speed_limit = speed_limit;
  if (speed_limit == 0.0)
    p.max_speed = config_.default_max_speed;
  else if (!p.percentage)
    p.max_speed = speed_limit;
  else if (config_.default_max_speed > 0.0)
    p.max_speed = config_.default_max_speed * speed_limit / 100.0;
  return p;  // a percentage without default_max_speed has no m/s value
}

std::string SpeedFilter::describe(const Publication& p) const
{
  std::string text = "publishing ";
  text += p.max_speed ? "max_speed " + num(*p.max_speed) + " m/s" + (*p.max_speed == 0.0 ? " (no limit)" : "") +
                            " on " + config_.max_speed_topic
                      : "nothing on " + config_.max_speed_topic + " (a percentage, and default_max_speed is 0)";
  if (!config_.speed_limit_topic.empty())
    text += " and speed_limit " + num(p.speed_limit) + (p.percentage ? " %" : " m/s") +
            (p.speed_limit == 0.0 ? " (no limit)" : "") + " on " + config_.speed_limit_topic;
  return text;
}

void SpeedFilter::onFilterInfo(const FilterInfoData& info)
{
  SpeedFilterConfig config;  // on the info's thread: read under the lock onReconfigure() writes under
  {
    std::lock_guard<std::mutex> lock(limits_mutex_);
    config = config_;
  }
  if (info.type != filter_info::kSpeedPercent || config.default_max_speed > 0.0) return;
  context_->report(config.speed_limit_topic.empty() ? Severity::Error : Severity::Warn, "default_max_speed",
                   name_ + ": the filter info on " + filterInfoTopic() +
                       " gives limits in percent (type 1), but default_max_speed is 0: a percentage cannot be "
                       "published in m/s on " +
                       config.max_speed_topic + ", which gets only \"no limit\"" +
                       (config.speed_limit_topic.empty()
                            ? "; set default_max_speed to the robot's top speed [m/s], or set speed_limit_topic "
                              "to publish the percentage"
                            : "; the percentage is published on " + config.speed_limit_topic +
                                  " (set default_max_speed to the robot's top speed [m/s] to have it in m/s too)"));
}

SpeedFilter::Publication SpeedFilter::limitForValue(int8_t v, const SpeedLimitTable* table)
{
  const Publication none = noLimit();
  if (v == 0) return none;
  if (v < 0 || v > 100)
  {
    warnValueOnce(v, "the mask holds the value " + std::to_string(v) +
                         " (outside -1..100, invalid in an OccupancyGrid); " + describe(none) + " there");
    return none;
  }
  if (!nav2Rule())
  {
    Publication p;
    p.max_speed = config_.default_max_speed;
    p.speed_limit = config_.default_max_speed;
    if (table && table->limit_mps[static_cast<std::size_t>(v)])
    {
      p.max_speed = p.speed_limit = *table->limit_mps[static_cast<std::size_t>(v)];
      return p;
    }
    if (!warned_ids_.test(static_cast<std::size_t>(v)))
    {
      warned_ids_.set(static_cast<std::size_t>(v));
      context_->report(Severity::Warn, "mask/area_id",
                       name_ + ": the robot is in area " + std::to_string(v) +
                           " of the mask, which has no speed "
                           "limit" +
                           (table ? " in the last message on " : " yet (nothing received on ") +
                           config_.features_topic + (table ? "" : ")") + "; treating it as no area: " + describe(p));
    }
    return p;
  }
  // Nav2's speed mask: the value encodes the limit.
  const bool percent = percentUnit();
  const FilterInfoData* info = activeInfo().get();
  const double base = info ? info->base : config_.base;
  const double multiplier = info ? info->multiplier : config_.multiplier;
  const Nav2SpeedLimit limit = nav2SpeedLimit(v, base, multiplier, percent);
  const Publication p = fromNav2Limit(limit.speed_limit);
  if (limit.out_of_range)
    warnValueOnce(v, "mask value " + std::to_string(v) + " gives base + multiplier * v = " + num(base) + " + " +
                         num(multiplier) + " * " + std::to_string(v) + " = " + num(limit.computed) +
                         (percent ? " %, outside [0, 100]" : " m/s, below 0") + " (Nav2's rule: no limit); " +
                         describe(p) + " there");
  return p;
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
  if (activeInfo() != warned_for_info_)
  {
    warned_for_info_ = activeInfo();
    warned_values_.reset();  // a new info: its out-of-range values are a new problem
  }
  const std::optional<int8_t> v = maskValueAt(mask, to_mask, robot_x, robot_y);
  if (v && *v == -1)
  {
    // Unknown: keep what was published (no limit when nothing was).
    if (!last_published_ && !last_speed_limit_) publishIfChanged(noLimit());
    return;
  }
  publishIfChanged(v ? limitForValue(*v, active_limits_.get()) : noLimit());
}

void SpeedFilter::publishIfChanged(const Publication& p)
{
  if (p.max_speed && !(last_published_ && *last_published_ == *p.max_speed))
  {
    last_published_ = *p.max_speed;
    emit(OutputKind::MaxSpeed, config_.max_speed_topic, *p.max_speed);
  }
  if (config_.speed_limit_topic.empty()) return;
  const std::pair<bool, double> limit{p.percentage, p.speed_limit};
  if (last_speed_limit_ && *last_speed_limit_ == limit) return;
  last_speed_limit_ = limit;
  OutputEvent e;
  e.kind = OutputKind::SpeedLimit;
  e.topic = config_.speed_limit_topic;
  e.value = p.speed_limit;
  e.percentage = p.percentage;
  emit(e);
}
}  // namespace costmap_layers
