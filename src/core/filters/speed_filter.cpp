#include "costmap_layers/core/filters/speed_filter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/core/filters/speed_lookahead.hpp"
#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/rules/stamp_order.hpp"

namespace costmap_layers
{
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
  c.max_speed_topic = params.getTopic("max_speed_topic", c.max_speed_topic, true);
  c.speed_limit_topic = params.getTopic("speed_limit_topic", c.speed_limit_topic, true);
  c.default_max_speed = params.getDouble("default_max_speed", c.default_max_speed, 0.0);
  c.enable_path_lookahead = params.getBool("enable_path_lookahead", c.enable_path_lookahead);
  c.max_decel = params.getDouble("max_decel", c.max_decel, -1e3, 1e3);
  if (c.max_decel > 0.0)
    params.fail("max_decel",
                "is positive (" + valueText(c.max_decel) +
                    "): as in Nav2 a deceleration is negative [m/s^2], e.g. -0.5 (0 means always max_lookahead)");
  c.min_lookahead = params.getDouble("min_lookahead", c.min_lookahead, 0.0, limits::kMaxDistance);
  c.max_lookahead = params.getDouble("max_lookahead", c.max_lookahead, 0.0, limits::kMaxDistance);
  if (c.max_lookahead < c.min_lookahead)
    params.fail("max_lookahead", "(" + valueText(c.max_lookahead) + " m) is below min_lookahead (" +
                                     valueText(c.min_lookahead) +
                                     " m): the lookahead is clamped to [min_lookahead, max_lookahead]");
  c.path_topic = params.getTopic("path_topic", c.path_topic, true);
  c.odom_topic = params.getTopic("odom_topic", c.odom_topic, true);
  c.odom_timeout = params.getDouble("odom_timeout", c.odom_timeout, 1e-3, limits::kMaxDuration);
  if (c.enable_path_lookahead && (c.path_topic.empty() || c.odom_topic.empty()))
    params.fail(c.path_topic.empty() ? "path_topic" : "odom_topic",
                "is empty while enable_path_lookahead is true: the lookahead needs the path and the odometry");
  if (c.filter_info)
  {
    c.mask_mode = SpeedMaskMode::Nav2;
    return c;
  }
  c.features_topic = params.getTopic("features_topic", c.features_topic, true);
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
  return buildSpeedLimitTable(limits, config.speed_limit_in_percent, config.default_max_speed, issues);
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
  path_topic_ = config_.path_topic;
  odom_topic_ = config_.odom_topic;
  if (config_.enable_path_lookahead)
  {
    addInput(InputPort::path(config_.path_topic, [this](const std::shared_ptr<const PathData>& m) { setPath(m); }));
    addInput(InputPort::odometry(config_.odom_topic,
                                 [this](const std::shared_ptr<const OdometryData>& m)
                                 {
                                   if (m) setOdometry(*m);
                                 }));
  }
}

std::string SpeedFilter::setPath(const std::shared_ptr<const PathData>& path)
{
  InputError error = path ? validatePath(*path) : InputError::of("poses", "no path");
  if (error.ok())
  {
    const uint64_t now = context_ ? context_->nowNs() : UINT64_MAX;
    std::lock_guard<std::mutex> lock(motion_mutex_);
    if (!path_ || !isOutOfOrder(path->stamp_ns, path_->stamp_ns, now))
    {
      path_ = path;
      return {};
    }
    error = InputError::of("header.stamp", outOfOrderError(path->stamp_ns, path_->stamp_ns, "path"));
  }
  if (context_)
    context_->report(Severity::Error, "path/" + error.field,
                     name_ + ": path on " + path_topic_ + " refused, keeping the previous one: " + error.message);
  return error.message;
}

std::string SpeedFilter::setOdometry(const OdometryData& odom)
{
  InputError error = validateOdometry(odom);
  const uint64_t now = context_ ? context_->nowNs() : 0;
  if (error.ok())
  {
    std::unique_lock<std::mutex> lock(motion_mutex_);
    const uint64_t dropped_at = dropOdometryBeforeJumpLocked(now);
    if (dropped_at != 0)
    {
      lock.unlock();
      reportOdometryJump(dropped_at, now);
      lock.lock();
    }
    if (speeds_.empty() || !isOutOfOrder(odom.stamp_ns, speeds_.newestStamp(), now))
    {
      speeds_.add(now, odom.stamp_ns, odom.linear_x);
      return {};
    }
    error = InputError::of("header.stamp", outOfOrderError(odom.stamp_ns, speeds_.newestStamp(), "odometry"));
  }
  if (context_)
    context_->report(Severity::Error, "odom/" + error.field,
                     name_ + ": odometry on " + odom_topic_ + " refused, keeping the previous speed: " + error.message);
  return error.message;
}

uint64_t SpeedFilter::dropOdometryBeforeJumpLocked(uint64_t now)
{
  // Samples received after now belong to a timeline the clock left (a bag played in a loop, a restarted
  // simulation): averaged with the new ones they would mix two robots' speeds, and the newest of them
  // would count as fresh until the clock caught up. As the observation buffers do: drop them all.
  const uint64_t from = odom_clock_.latest();
  if (!odom_clock_.jumpedBack(now)) return 0;
  speeds_.clear();
  return from;
}

void SpeedFilter::reportOdometryJump(uint64_t from_ns, uint64_t now)
{
  if (context_)
    context_->report(Severity::Warn, "odom/clock",
                     name_ + ": " + clockJumpMessage(from_ns, now) + ": the odometry received before is dropped");
}

std::optional<double> SpeedFilter::currentSpeed()
{
  const uint64_t now = context_->nowNs();
  OdometrySpeedWindow::Mean mean;
  uint64_t dropped_at = 0;
  {
    std::lock_guard<std::mutex> lock(motion_mutex_);
    dropped_at = dropOdometryBeforeJumpLocked(now);
    mean = speeds_.mean();
  }
  if (dropped_at != 0) reportOdometryJump(dropped_at, now);
  if (mean.samples == 0)
  {
    context_->report(Severity::Error, "odom/missing",
                     name_ + ": no odometry yet on " + config_.odom_topic + ": looking max_lookahead (" +
                         valueText(config_.max_lookahead) + " m) ahead");
    return std::nullopt;
  }
  const double age = secondsBetween(mean.newest_received_ns, now);
  if (age > config_.odom_timeout)
  {
    context_->report(Severity::Error, "odom/stale",
                     name_ + ": the newest odometry on " + config_.odom_topic + " is " + valueText(age) +
                         " s old, more than odom_timeout (" + valueText(config_.odom_timeout) +
                         " s): looking max_lookahead (" + valueText(config_.max_lookahead) + " m) ahead");
    return std::nullopt;
  }
  return std::fabs(mean.linear_x);
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
  return name != "features_topic" && name != "max_speed_topic" && name != "speed_limit_topic" && name != "mask_mode" &&
         name != "enable_path_lookahead" && name != "path_topic" && name != "odom_topic";
}
}  // namespace

void SpeedFilter::onReconfigure(const ParamValue& params)
{
  const ParamReader reader(params, name_);
  const SpeedFilterConfig next = parseSpeedFilterConfig(reader);  // validates first
  if (next.features_topic != config_.features_topic || next.max_speed_topic != config_.max_speed_topic ||
      next.speed_limit_topic != config_.speed_limit_topic || next.mask_mode != config_.mask_mode ||
      next.filter_info != config_.filter_info || next.enable_path_lookahead != config_.enable_path_lookahead ||
      next.path_topic != config_.path_topic || next.odom_topic != config_.odom_topic)
    throw std::invalid_argument(name_ +
                                ": features_topic, max_speed_topic, speed_limit_topic, mask_mode, "
                                "filter_info_topic, enable_path_lookahead, path_topic and odom_topic cannot change at "
                                "run time");
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

SpeedRule SpeedFilter::rule() const
{
  SpeedRule r;
  r.nav2 = nav2Rule();
  r.percent = percentUnit();
  r.default_max_speed = config_.default_max_speed;
  // The filter-info form: the info in force gives base and multiplier.
  const FilterInfoData* info = activeInfo().get();
  r.base = info ? info->base : config_.base;
  r.multiplier = info ? info->multiplier : config_.multiplier;
  return r;
}

SpeedFilter::Publication SpeedFilter::noLimit() const
{
  return speedNoLimit(rule());
}

std::string SpeedFilter::describe(const Publication& p) const
{
  std::string text = "publishing ";
  text += p.max_speed ? "max_speed " + valueText(*p.max_speed) + " m/s" + (*p.max_speed == 0.0 ? " (no limit)" : "") +
                            " on " + config_.max_speed_topic
                      : "nothing on " + config_.max_speed_topic + " (a percentage, and default_max_speed is 0)";
  if (!config_.speed_limit_topic.empty())
    text += " and speed_limit " + valueText(p.speed_limit) + (p.percentage ? " %" : " m/s") +
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
  const SpeedRule r = rule();
  const SpeedVerdict verdict = speedLimitForValue(v, r, table);
  const Publication& p = verdict.publication;
  switch (verdict.warning)
  {
    case SpeedWarning::None:
      break;
    case SpeedWarning::InvalidValue:
      warnValueOnce(v, "the mask holds the value " + std::to_string(v) +
                           " (outside -1..100, invalid in an OccupancyGrid); " + describe(p) + " there");
      break;
    case SpeedWarning::UnknownArea:
      if (!warned_ids_.test(static_cast<std::size_t>(v)))
      {
        warned_ids_.set(static_cast<std::size_t>(v));
        context_->report(Severity::Warn, "mask/area_id",
                         name_ + ": the robot is (or its path ahead runs) in area " + std::to_string(v) +
                             " of the mask, which has no speed "
                             "limit" +
                             (table ? " in the last message on " : " yet (nothing received on ") +
                             config_.features_topic + (table ? "" : ")") + "; treating it as no area: " + describe(p));
      }
      break;
    case SpeedWarning::OutOfRange:
      warnValueOnce(v, "mask value " + std::to_string(v) + " gives base + multiplier * v = " + valueText(r.base) +
                           " + " + valueText(r.multiplier) + " * " + std::to_string(v) + " = " +
                           valueText(verdict.computed) + (r.percent ? " %, outside [0, 100]" : " m/s, below 0") +
                           " (Nav2's rule: no limit); " + describe(p) + " there");
      break;
  }
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
  std::optional<Publication> at_robot;  // nullopt on a -1 (unknown) cell
  if (!v || *v != -1) at_robot = v ? limitForValue(*v, active_limits_.get()) : noLimit();
  if (config_.enable_path_lookahead)
  {
    const std::optional<Publication> ahead = lookahead(mask, to_mask, robot_x, robot_y, at_robot);
    if (ahead) at_robot = ahead;
  }
  if (at_robot)
    publishIfChanged(*at_robot);
  else if (!last_published_ && !last_speed_limit_)
    publishIfChanged(noLimit());  // unknown: keep what was published (no limit when nothing was)
}

std::optional<SpeedFilter::Publication> SpeedFilter::lookahead(const OccupancyGridData& mask,
                                                               const Transform2D& to_mask, double robot_x,
                                                               double robot_y,
                                                               const std::optional<Publication>& at_robot)
{
  last_lookahead_ = 0.0;
  std::shared_ptr<const PathData> path;
  {
    std::lock_guard<std::mutex> lock(motion_mutex_);
    path = path_;
  }
  if (!path || path->poses.empty())
  {
    active_path_ = path;
    if (path)
      context_->report(
          Severity::Debug, "path/empty",
          name_ + ": the path on " + config_.path_topic + " is empty (no plan): the robot's own cell only");
    return std::nullopt;
  }
  // The path in the global frame, every cycle (the frames may move against each other).
  Transform2D to_global;
  const std::string& global = context_->globalFrame();
  if (path->frame_id != global)
  {
    std::string error;
    const auto t = context_->lookupTransform(global, path->frame_id, &error);
    if (!t)
    {
      context_->report(Severity::Error, "path/transform",
                       name_ + ": cannot transform the path on " + config_.path_topic + " from " +
                           shownText(path->frame_id) + " into " + global +
                           ": the robot's own cell only this cycle: " + shownText(error, 400));
      return std::nullopt;
    }
    to_global = *t;
  }
  if (path != active_path_)
  {
    active_path_ = path;
    segment_ = 0;  // a new path: search it from its start
  }
  path_global_.resize(path->poses.size());
  for (std::size_t i = 0; i < path->poses.size(); ++i)
    to_global.apply(path->poses[i].x, path->poses[i].y, path_global_[i].x, path_global_[i].y);

  const std::optional<double> speed = currentSpeed();
  const double distance = speedLookaheadDistance(speed, config_.max_decel, config_.min_lookahead,
                                                 config_.max_lookahead, held_lookahead_);
  last_lookahead_ = distance;

  segment_ = closestSegment(path_global_, robot_x, robot_y, segment_);
  const std::size_t end = lookaheadEnd(path_global_, segment_, distance);
  const SpeedAhead ahead =
      strictestAhead(path_global_, segment_, end, at_robot, distance,
                     [&](const PathData::Point& pose) -> std::optional<Publication>
                     {
                       // Outside the mask or on an unknown cell a pose adds nothing.
                       const std::optional<int8_t> v = maskValueAt(mask, to_mask, pose.x, pose.y);
                       if (!v || *v == -1) return std::nullopt;
                       return limitForValue(*v, active_limits_.get());
                     });
  held_lookahead_ = ahead.held_lookahead;
  return ahead.best;
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
