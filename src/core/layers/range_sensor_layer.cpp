#include "costmap_layers/core/layers/range_sensor_layer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/core/config/param_reader.hpp"

namespace costmap_layers
{
RangeSensorConfig parseRangeSensorConfig(const ParamReader& p)
{
  RangeSensorConfig c;
  p.declare("topics", "topic names of sensor_msgs/Range, separated by spaces (or a list)", "none");
  if (const ParamValue* t = p.raw("topics"))
  {
    if (t->type() == ParamValue::Type::String)
    {
      std::istringstream in(t->asString());
      std::string topic;
      while (in >> topic)
        c.topics.push_back(topic);
    }
    else if (t->isList())
    {
      for (const auto& item : t->asList())
      {
        if (item.type() != ParamValue::Type::String || item.asString().empty())
          p.fail("topics", "must list non-empty topic names");
        c.topics.push_back(item.asString());
      }
    }
    else
    {
      p.fail("topics", "must be a list of topic names");
    }
    for (const auto& topic : c.topics)
    {
      const std::string problem = rosNameProblem(topic);
      if (!problem.empty()) p.fail("topics", "must list topic names: " + problem);
    }
  }
  const double big = std::numeric_limits<double>::max();
  c.phi = p.getDouble("phi", c.phi, 1e-9, big);
  c.inflate_cone = p.getDouble("inflate_cone", c.inflate_cone, 0.0, 1.0);
  c.no_readings_timeout = p.getDouble("no_readings_timeout", c.no_readings_timeout, 0.0, limits::kMaxDuration);
  c.clear_threshold = p.getDouble("clear_threshold", c.clear_threshold, 0.0, 1.0);
  c.mark_threshold = p.getDouble("mark_threshold", c.mark_threshold, 0.0, 1.0);
  if (c.clear_threshold > c.mark_threshold) p.fail("clear_threshold", "must not exceed mark_threshold");
  c.clear_on_max_reading = p.getBool("clear_on_max_reading", c.clear_on_max_reading);
  const std::string type = p.getChoice("input_sensor_type", "ALL", {"ALL", "VARIABLE", "FIXED"});
  c.input_sensor_type = type == "VARIABLE" ? RangeInputType::Variable
                        : type == "FIXED"  ? RangeInputType::Fixed
                                           : RangeInputType::All;
  return c;
}


void RangeSensorLayer::onInitialize()
{
  config_ = parseRangeSensorConfig(ParamReader(context_->params(), name_));
  costmap_.setDefaultValue(range_model::toCost(0.5));
  matchSize();
  last_reading_ns_ = context_->nowNs();
  if (config_.topics.empty())
    context_->report(Severity::Warn, "no_topics", name_ + ": no range topics given (parameter 'topics')");
  for (const auto& topic : config_.topics)
  {
    addInput(InputPort::range(topic,
                              [this](const std::shared_ptr<const RangeData>& range, const SensorPose& pose)
                              {
                                if (range) addRange(*range, pose);
                              }));
  }
}

std::string RangeSensorLayer::addRange(const RangeData& range, const SensorPose& pose)
{
  std::string result = queueRange(range, pose);
  const uint64_t now = context_->nowNs();
  std::lock_guard<std::mutex> lock(mutex_);
  if (result.empty())
  {
    ++readings_accepted_;
    last_accepted_ns_ = now;
  }
  else
  {
    ++readings_rejected_;
    last_rejection_ = result;
  }
  return result;
}

LayerStatus RangeSensorLayer::status() const
{
  LayerStatus s = Layer::status();
  s.level = StatusLevel::Ok;
  s.message.clear();
  const uint64_t now = context_ ? context_->nowNs() : 0;
  std::string topics;
  for (const auto& t : config_.topics)
    topics += (topics.empty() ? "" : " ") + t;
  std::lock_guard<std::mutex> lock(mutex_);
  s.add("readings accepted", std::to_string(readings_accepted_));
  s.add("readings rejected", std::to_string(readings_rejected_));
  s.add("last reading accepted",
        readings_accepted_ > 0 ? describeAge(secondsBetween(last_accepted_ns_, now)) : "never");
  if (readings_rejected_ > 0) s.add("last rejection", last_rejection_);
  s.add("no_readings_timeout [s]", std::to_string(config_.no_readings_timeout));
  if (!enabled())
  {
    s.message = "disabled";
    return s;
  }
  if (config_.topics.empty()) s.raise(StatusLevel::Warn, "no topics configured");
  if (!current_)
    s.raise(StatusLevel::Warn, "no range readings on " + topics + " for " +
                                   std::to_string(secondsBetween(last_reading_ns_, now)) + " s (no_readings_timeout " +
                                   std::to_string(config_.no_readings_timeout) + " s)");
  else if (readings_accepted_ == 0 && readings_rejected_ > 0)
    s.raise(StatusLevel::Warn, "every range reading on " + topics + " rejected (" + last_rejection_ + ")");
  if (s.level == StatusLevel::Ok)
    s.message = readings_accepted_ > 0 ? "readings arriving on " + topics : "no reading yet on " + topics;
  return s;
}

std::string RangeSensorLayer::queueRange(const RangeData& range, const SensorPose& pose)
{
  const RangeInterpretation r = interpretRange(range, config_.input_sensor_type, config_.clear_on_max_reading);
  if (!r.ok())
  {
    context_->report(Severity::Warn, "invalid_range",
                     name_ + ": range reading in frame '" + shownText(range.frame_id) + "' rejected: " + r.error);
    return r.error;
  }
  if (!r.use) return {};
  const uint64_t now = context_->nowNs();
  if (isAheadOfNow(range.stamp_ns, now))
  {
    const std::string error = aheadOfNowError(range.stamp_ns, now);
    context_->report(Severity::Warn, "future_range",
                     name_ + ": range reading in frame '" + shownText(range.frame_id) + "' rejected: " + error);
    return error;
  }
  Pending p;
  double oz, tz;
  pose.to_global.apply(0.0, 0.0, 0.0, p.ox, p.oy, oz);
  pose.to_global.apply(r.range, 0.0, 0.0, p.tx, p.ty, tz);
  if (!std::isfinite(p.ox) || !std::isfinite(p.oy) || !std::isfinite(p.tx) || !std::isfinite(p.ty))
  {
    context_->report(Severity::Warn, "invalid_range", name_ + ": range reading with a non-finite pose rejected");
    return "non-finite pose";
  }
  p.range = r.range;
  p.max_angle = range.field_of_view / 2.0;
  p.clear = r.clear;
  std::lock_guard<std::mutex> lock(mutex_);
  if (!active_) return {};
  if (queue_.size() >= kMaxPending)
  {
    queue_.pop_front();
    ++dropped_;
  }
  queue_.push_back(p);
  return {};
}

std::size_t RangeSensorLayer::pending() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return queue_.size();
}

void RangeSensorLayer::updateCell(double ox, double oy, double ot, double r, double max_angle, unsigned int x,
                                  unsigned int y, bool clear)
{
  double nx, ny;
  costmap_.mapToWorld(x, y, nx, ny);
  const double dx = nx - ox, dy = ny - oy;
  const double theta = std::remainder(std::atan2(dy, dx) - ot, 6.283185307179586);  // normalised to [-pi, pi]
  const double phi = std::sqrt(dx * dx + dy * dy);
  const double sensor =
      clear ? 0.0 : range_model::sensorModel(r, phi, theta, max_angle, config_.phi, costmap_.getResolution());
  const double prior = range_model::toProbability(costmap_.getCost(x, y));
  const double occupied = sensor * prior;
  const double not_occupied = (1.0 - sensor) * (1.0 - prior);
  const double sum = occupied + not_occupied;
  // A certain prior met by certain contrary evidence (0/0): the new reading wins.
  double posterior = sum > 0.0 ? occupied / sum : sensor;
  posterior = std::min(1.0, std::max(0.0, posterior));
  costmap_.setCost(x, y, range_model::toCost(posterior));
}

void RangeSensorLayer::applyReading(const Pending& reading)
{
  const double ox = reading.ox, oy = reading.oy, tx = reading.tx, ty = reading.ty;
  const double dx = tx - ox, dy = ty - oy;
  const double theta = std::atan2(dy, dx), d = std::sqrt(dx * dx + dy * dy);
  // The cone's corners go through int cell indices: refuse readings that would overflow them.
  const double res = costmap_.getResolution();
  if (!(d * 1.2 / res < 1e8) || !(std::fabs(ox - costmap_.getOriginX()) / res < 1e8) ||
      !(std::fabs(oy - costmap_.getOriginY()) / res < 1e8))
  {
    context_->report(Severity::Warn, "invalid_range", name_ + ": range reading too far from the grid ignored");
    return;
  }
  auto touchTouched = [this](double x, double y)
  {
    if (!touched_)
    {
      touched_min_x_ = touched_max_x_ = x;
      touched_min_y_ = touched_max_y_ = y;
      touched_ = true;
      return;
    }
    touch(x, y, &touched_min_x_, &touched_min_y_, &touched_max_x_, &touched_max_y_);
  };

  // The cone as a triangle: the origin O and the two edges A, B at 1.2 times the reading (Nav2).
  int Ox, Oy, Ax, Ay, Bx, By;
  costmap_.worldToMapNoBounds(ox, oy, Ox, Oy);
  touchTouched(ox, oy);
  unsigned int cx, cy;
  if (costmap_.worldToMap(tx, ty, cx, cy))
  {
    costmap_.setCost(cx, cy, 233);
    touchTouched(tx, ty);
  }
  const double ax = ox + std::cos(theta - reading.max_angle) * d * 1.2;
  const double ay = oy + std::sin(theta - reading.max_angle) * d * 1.2;
  const double bx = ox + std::cos(theta + reading.max_angle) * d * 1.2;
  const double by = oy + std::sin(theta + reading.max_angle) * d * 1.2;
  costmap_.worldToMapNoBounds(ax, ay, Ax, Ay);
  costmap_.worldToMapNoBounds(bx, by, Bx, By);
  touchTouched(ax, ay);
  touchTouched(bx, by);

  const int size_x = static_cast<int>(costmap_.getSizeInCellsX()),
            size_y = static_cast<int>(costmap_.getSizeInCellsY());
  const int bx0 = std::max(0, std::min({Ox, Ax, Bx})), by0 = std::max(0, std::min({Oy, Ay, By}));
  const int bx1 = std::min(size_x - 1, std::max({Ox, Ax, Bx})), by1 = std::min(size_y - 1, std::max({Oy, Ay, By}));

  auto orient2d = [](long ax_, long ay_, long bx_, long by_, long cx_, long cy_)
  { return (bx_ - ax_) * (cy_ - ay_) - (by_ - ay_) * (cx_ - ax_); };
  const double area = std::fabs((static_cast<double>(Ax) * (By - Oy) + static_cast<double>(Bx) * (Oy - Ay) +
                                 static_cast<double>(Ox) * (Ay - By)) /
                                2.0);
  const double inside_limit = -config_.inflate_cone * area;
  for (int x = bx0; x <= bx1; ++x)
  {
    for (int y = by0; y <= by1; ++y)
    {
      if (config_.inflate_cone < 1.0)
      {
        // Barycentric-style test against the triangle, loosened by inflate_cone (Nav2's rule).
        const double w0 = static_cast<double>(orient2d(Ax, Ay, Bx, By, x, y));
        const double w1 = static_cast<double>(orient2d(Bx, By, Ox, Oy, x, y));
        const double w2 = static_cast<double>(orient2d(Ox, Oy, Ax, Ay, x, y));
        if (!(w0 >= inside_limit && w1 >= inside_limit && w2 >= inside_limit)) continue;
      }
      updateCell(ox, oy, theta, reading.range, reading.max_angle, static_cast<unsigned>(x), static_cast<unsigned>(y),
                 reading.clear);
    }
  }
}

void RangeSensorLayer::updateBounds(double /*robot_x*/, double /*robot_y*/, double /*robot_yaw*/, double* min_x,
                                    double* min_y, double* max_x, double* max_y)
{
  followRollingMaster();
  useExtraBounds(min_x, min_y, max_x, max_y);
  uint64_t dropped = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    work_.swap(queue_);
    std::swap(dropped, dropped_);
  }
  // Bound the work of this cycle, which runs under the costmap's lock: keep the newest readings whose
  // cones fit kMaxCellsPerUpdate cells (a cone costs at most its bounding box, clipped to the grid).
  const double res = costmap_.getResolution();
  const double grid_cells = static_cast<double>(costmap_.getSizeInCellsX()) * costmap_.getSizeInCellsY();
  double budget = static_cast<double>(kMaxCellsPerUpdate);
  std::size_t first = work_.size();
  while (first > 0)
  {
    const Pending& r = work_[first - 1];
    const double side = 2.4 * std::hypot(r.tx - r.ox, r.ty - r.oy) / res + 2.0;
    const double cells = std::min(grid_cells, side * side);
    if (cells > budget && first != work_.size()) break;  // the newest one is always applied
    budget -= cells;
    --first;
  }
  dropped += first;
  if (dropped != 0)
    context_->report(Severity::Warn, "flood",
                     name_ + ": range readings arrive faster than the update loop applies them: dropped the " +
                         std::to_string(dropped) + " oldest since the last update (at most " +
                         std::to_string(kMaxPending) + " readings or " + std::to_string(kMaxCellsPerUpdate) +
                         " cells are applied per update)");
  const uint64_t now = context_->nowNs();
  const uint64_t before = clock_.latest();
  if (clock_.jumpedBack(now))
  {
    // Readings are applied once, at the next update, whatever their stamp: nothing here is kept by time
    // but the silence timer, which would otherwise read 0 s until the clock is back at `before`.
    last_reading_ns_ = now;
    context_->report(Severity::Warn, "clock_jump",
                     name_ + ": " + clockJumpMessage(before, now) + ": no_readings_timeout restarts now");
  }
  const bool got_readings = !work_.empty();
  for (std::size_t k = first; k < work_.size(); ++k)
    applyReading(work_[k]);
  work_.clear();
  if (touched_)
  {
    touch(touched_min_x_, touched_min_y_, min_x, min_y, max_x, max_y);
    touch(touched_max_x_, touched_max_y_, min_x, min_y, max_x, max_y);
    touched_ = false;
  }
  if (got_readings)
  {
    last_reading_ns_ = now;
    current_ = true;
    return;
  }
  const double silent = now > last_reading_ns_ ? static_cast<double>(now - last_reading_ns_) * 1e-9 : 0.0;
  if (config_.no_readings_timeout > 0.0 && silent > config_.no_readings_timeout)
  {
    char text[128];
    std::snprintf(text, sizeof(text), ": no range readings for %.2f s, expected at least every %.2f s", silent,
                  config_.no_readings_timeout);
    context_->report(Severity::Warn, "no_readings", name_ + text);
    current_ = false;
  }
}

void RangeSensorLayer::updateCosts(Costmap2D& master, int min_i, int min_j, int max_i, int max_j)
{
  const uint8_t clear = range_model::toCost(config_.clear_threshold);
  const uint8_t mark = range_model::toCost(config_.mark_threshold);
  min_i = std::max(min_i, 0);
  min_j = std::max(min_j, 0);
  max_i = std::min(max_i, static_cast<int>(std::min(master.getSizeInCellsX(), costmap_.getSizeInCellsX())));
  max_j = std::min(max_j, static_cast<int>(std::min(master.getSizeInCellsY(), costmap_.getSizeInCellsY())));
  for (int j = min_j; j < max_j; ++j)
  {
    const uint8_t* own = costmap_.data() + costmap_.getIndex(static_cast<unsigned>(min_i), static_cast<unsigned>(j));
    uint8_t* out = master.data() + master.getIndex(static_cast<unsigned>(min_i), static_cast<unsigned>(j));
    for (int i = 0; i < max_i - min_i; ++i)
    {
      const uint8_t p = own[i];
      if (p == NO_INFORMATION) continue;
      uint8_t cost;
      if (p > mark)
        cost = LETHAL_OBSTACLE;
      else if (p < clear)
        cost = FREE_SPACE;
      else
        continue;
      if (out[i] == NO_INFORMATION || out[i] < cost) out[i] = cost;
    }
  }
  if (!current_ && was_reset_)
  {
    was_reset_ = false;
    current_ = true;
  }
}

void RangeSensorLayer::reset()
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.clear();
  }
  costmap_.resetMaps();
  was_reset_ = true;
  if (context_) last_reading_ns_ = context_->nowNs();
}

void RangeSensorLayer::activate()
{
  std::lock_guard<std::mutex> lock(mutex_);
  queue_.clear();
  active_ = true;
}

void RangeSensorLayer::deactivate()
{
  std::lock_guard<std::mutex> lock(mutex_);
  queue_.clear();
  active_ = false;
}
}  // namespace costmap_layers
