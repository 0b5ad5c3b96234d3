#include "costmap_layers/core/layers/obstacle_layer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/layers/ray_geometry.hpp"
#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/core/rules/stamp_order.hpp"

namespace costmap_layers
{
namespace
{
/// std::hypot of two cell counts, as Costmap2D::raytraceLine computes a line's length (the same bits:
/// the cleared steps depend on it), looked up for the short lines a local costmap traces.
double lineLength(unsigned int a, unsigned int b)
{
  constexpr unsigned int kSide = 128;
  struct Table
  {
    std::vector<double> length;
    Table() : length(kSide * kSide)
    {
      for (unsigned int i = 0; i < kSide; ++i)
        for (unsigned int j = 0; j < kSide; ++j)
          length[i * kSide + j] = std::hypot(static_cast<double>(i), static_cast<double>(j));
    }
  };
  static const Table table;
  if (a < kSide && b < kSide) return table.length[a * kSide + b];
  return std::hypot(static_cast<double>(a), static_cast<double>(b));
}

/// The new name when set, else the old one, else the default. Ranges are lengths: kMaxDistance.
double rangeParam(const ParamReader& p, const std::string& name, const std::string& old_name, double def)
{
  if (!p.has(name) && p.has(old_name)) return p.getDouble(old_name, def, 0.0, limits::kMaxDistance);
  return p.getDouble(name, def, 0.0, limits::kMaxDistance);
}

std::vector<std::string> sourceNames(const ParamReader& p)
{
  std::vector<std::string> names;
  p.declare("observation_sources",
            "source names, separated by spaces (or a list); each source's parameters in <source>/", "no source");
  const ParamValue* v = p.raw("observation_sources");
  if (v == nullptr) return names;
  if (v->type() == ParamValue::Type::String)
  {
    std::istringstream in(v->asString());
    std::string name;
    while (in >> name)
      names.push_back(name);
  }
  else if (v->isList())
  {
    for (const auto& item : v->asList())
    {
      if (item.type() != ParamValue::Type::String) p.fail("observation_sources", "must list source names");
      names.push_back(item.asString());
    }
  }
  else
  {
    p.fail("observation_sources", "must be a space-separated string of source names");
  }
  for (std::size_t i = 0; i < names.size(); ++i)
  {
    if (std::count(names.begin(), names.end(), names[i]) > 1)
      p.fail("observation_sources", "names source '" + names[i] + "' twice");
    if (names[i].find(',') != std::string::npos)
      p.fail("observation_sources", "names source '" + shownText(names[i]) +
                                        "': source names are separated by blanks (as in costmap_2d), not commas");
    // Each name is also its parameter namespace (and the default topic).
    const std::string problem = rosNameProblem(names[i], false);
    if (!problem.empty()) p.fail("observation_sources", "must name sources by ROS names: " + problem);
  }
  return names;
}
}  // namespace

const char* sensorDataTypeName(SensorDataType type)
{
  switch (type)
  {
    case SensorDataType::LaserScan:
      return "LaserScan";
    case SensorDataType::PointCloud:
      return "PointCloud";
    case SensorDataType::PointCloud2:
      break;
  }
  return "PointCloud2";
}

ObservationSourceConfig parseObservationSourceConfig(const ParamReader& p, const std::string& name)
{
  ObservationSourceConfig c;
  c.name = name;
  c.topic = p.getTopic("topic", name, true);
  if (c.topic.empty()) p.fail("topic", "must not be empty");
  c.sensor_frame = p.getFrameId("sensor_frame", c.sensor_frame, true);  // empty: the message's frame
  c.observation_persistence =
      p.getDouble("observation_persistence", c.observation_persistence, 0.0, limits::kMaxDuration);
  c.expected_update_rate = p.getDouble("expected_update_rate", c.expected_update_rate, 0.0, limits::kMaxDuration);
  const std::string data_type = p.getChoice("data_type", "PointCloud2", {"LaserScan", "PointCloud2", "PointCloud"});
  c.data_type = data_type == "LaserScan"    ? SensorDataType::LaserScan
                : data_type == "PointCloud" ? SensorDataType::PointCloud
                                            : SensorDataType::PointCloud2;
  c.min_obstacle_height = p.getDouble("min_obstacle_height", c.min_obstacle_height);
  c.max_obstacle_height = p.getDouble("max_obstacle_height", c.max_obstacle_height);
  if (c.max_obstacle_height < c.min_obstacle_height) p.fail("max_obstacle_height", "must be >= min_obstacle_height");
  c.inf_is_valid = p.getBool("inf_is_valid", c.inf_is_valid);
  c.marking = p.getBool("marking", c.marking);
  c.clearing = p.getBool("clearing", c.clearing);
  c.obstacle_min_range = p.getDouble("obstacle_min_range", c.obstacle_min_range, 0.0, limits::kMaxDistance);
  c.obstacle_max_range = rangeParam(p, "obstacle_max_range", "obstacle_range", c.obstacle_max_range);
  if (c.obstacle_max_range < c.obstacle_min_range) p.fail("obstacle_max_range", "must be >= obstacle_min_range");
  c.raytrace_min_range = p.getDouble("raytrace_min_range", c.raytrace_min_range, 0.0, limits::kMaxDistance);
  c.raytrace_max_range = rangeParam(p, "raytrace_max_range", "raytrace_range", c.raytrace_max_range);
  if (c.raytrace_max_range < c.raytrace_min_range) p.fail("raytrace_max_range", "must be >= raytrace_min_range");
  c.observation_keep_distance =
      p.getDouble("observation_keep_distance", c.observation_keep_distance, 0.0, limits::kMaxDistance);
  return c;
}

ObstacleConfig parseObstacleConfig(const ParamReader& p, bool default_track_unknown)
{
  ObstacleConfig c;
  c.footprint_clearing_enabled = p.getBool("footprint_clearing_enabled", c.footprint_clearing_enabled);
  c.min_obstacle_height = p.getDouble("min_obstacle_height", c.min_obstacle_height);
  c.max_obstacle_height = p.getDouble("max_obstacle_height", c.max_obstacle_height);
  if (c.max_obstacle_height < c.min_obstacle_height) p.fail("max_obstacle_height", "must be >= min_obstacle_height");
  // 0 overwrite, 1 maximum, 2 maximum keeping unknown master cells (Nav2's), 99 nothing (costmap_2d's
  // "Do nothing"; costmap_2d and Nav2 type names are translated to these by applyCostmap2dRules).
  c.combination_method = p.getInt("combination_method", c.combination_method, 0, 99);
  if (c.combination_method > 2 && c.combination_method != 99)
    p.fail("combination_method",
           "must be 0 (overwrite), 1 (maximum), 2 (maximum, unknown master cells stay unknown) "
           "or 99 (nothing, as costmap_2d's \"Do nothing\")");
  c.track_unknown_space = p.getBool("track_unknown_space", default_track_unknown);
  static const ParamValue empty = ParamValue::makeMap();
  for (const auto& name : sourceNames(p))
  {
    const ParamValue* ns = p.raw(name);
    if (ns != nullptr && !ns->isMap()) p.fail(name, "must be a namespace of source parameters");
    c.sources.push_back(parseObservationSourceConfig(ParamReader(ns ? *ns : empty, p.owner() + "/" + name), name));
  }
  return c;
}

void ObstacleLayer::onInitialize()
{
  config_ = parseObstacleConfig(ParamReader(context_->params(), name_), layered_costmap_->isTrackingUnknown());
  costmap_.setDefaultValue(config_.track_unknown_space ? NO_INFORMATION : FREE_SPACE);
  matchSize();
  const uint64_t now = context_->nowNs();
  buffers_.clear();
  {
    std::lock_guard<std::mutex> lock(counts_mutex_);
    counts_.assign(config_.sources.size(), SourceCounts{});
  }
  for (std::size_t i = 0; i < config_.sources.size(); ++i)
  {
    const ObservationSourceConfig& s = config_.sources[i];
    ObservationBufferConfig bc;
    bc.observation_persistence = s.observation_persistence;
    bc.expected_update_rate = s.expected_update_rate;
    bc.observation_keep_distance = s.observation_keep_distance;
    buffers_.push_back(std::make_unique<ObservationBuffer>(s.name, bc, now));
  }
  for (std::size_t i = 0; i < config_.sources.size(); ++i)
  {
    const ObservationSourceConfig& s = config_.sources[i];
    if (s.data_type == SensorDataType::LaserScan)
      addInput(InputPort::laserScan(s.topic, s.sensor_frame,
                                    [this, i](const std::shared_ptr<const LaserScanData>& scan, const SensorPose& pose)
                                    {
                                      if (scan) addLaserScan(i, *scan, pose);
                                    }));
    else
    {
      auto on_cloud = [this, i](const std::shared_ptr<const PointCloud2Data>& cloud, const SensorPose& pose)
      {
        if (cloud) addPointCloud2(i, *cloud, pose);
      };
      addInput(s.data_type == SensorDataType::PointCloud ? InputPort::pointCloud(s.topic, s.sensor_frame, on_cloud)
                                                         : InputPort::pointCloud2(s.topic, s.sensor_frame, on_cloud));
    }
  }
  if (config_.sources.empty())
    context_->report(Severity::Warn, "no_sources",
                     name_ + ": no observation_sources: the layer only clears the footprint");
  // A listed source without its namespace runs on defaults alone: most likely a misspelt namespace.
  for (const auto& s : config_.sources)
  {
    const ParamValue* ns = context_->params().find(s.name);
    if (ns == nullptr)
      context_->report(Severity::Warn, "sources/" + s.name,
                       name_ + ": observation source '" + shownText(s.name) + "' has no namespace of that name: " +
                           "it runs on the defaults (topic '" + shownText(s.topic) + "', data_type " +
                           sensorDataTypeName(s.data_type) + ", marking and clearing as their defaults say)");
    else if (ns->find("data_type") == nullptr)
      context_->report(Severity::Info, "sources/" + s.name + "/data_type",
                       name_ + ": observation source '" + shownText(s.name) + "': data_type not set, reading " +
                           sensorDataTypeName(s.data_type) +
                           " (costmap_2d's default is PointCloud, Nav2's LaserScan; the costmap_2d and Nav2 type "
                           "names of this layer take theirs)");
  }
}

void ObstacleLayer::matchSize()
{
  CostmapLayer::matchSize();
}

std::string ObstacleLayer::sourceLabel(std::size_t source) const
{
  const ObservationSourceConfig& s = config_.sources[source];
  return name_ + ": observation source '" + s.name + "' (topic '" + s.topic + "')";
}

std::string ObstacleLayer::noteReading(std::size_t source, std::string result)
{
  const uint64_t now = context_->nowNs();
  std::lock_guard<std::mutex> lock(counts_mutex_);
  SourceCounts& c = counts_.at(source);
  if (result.empty())
  {
    ++c.accepted;
    c.last_accepted_ns = now;
  }
  else
  {
    ++c.rejected;
    c.last_rejection = result;
  }
  return result;
}

LayerStatus ObstacleLayer::status() const
{
  LayerStatus s = Layer::status();
  s.level = StatusLevel::Ok;
  s.message.clear();
  const uint64_t now = context_ ? context_->nowNs() : 0;
  std::lock_guard<std::mutex> lock(counts_mutex_);
  for (std::size_t i = 0; i < buffers_.size() && i < counts_.size(); ++i)
  {
    const ObservationSourceConfig& src = config_.sources[i];
    const SourceCounts& c = counts_[i];
    const ObservationBuffer& b = *buffers_[i];
    const double age = b.secondsSinceUpdate(now);
    char text[160];
    std::snprintf(
        text, sizeof(text), "%llu accepted, %llu rejected, last accepted %s, expected every %s",
        static_cast<unsigned long long>(c.accepted), static_cast<unsigned long long>(c.rejected),
        c.accepted > 0 ? describeAge(secondsBetween(c.last_accepted_ns, now)).c_str() : "never",
        src.expected_update_rate > 0.0 ? (std::to_string(src.expected_update_rate) + " s").c_str() : "(unchecked)");
    s.add("source " + src.name + " (" + src.topic + ")", text);
    if (c.rejected > 0) s.add("source " + src.name + " last rejection", c.last_rejection);
    if (!enabled()) continue;
    if (!b.isCurrent(now))
    {
      std::snprintf(text, sizeof(text), "%.2f s without a reading (expected every %.2f s)", age,
                    src.expected_update_rate);
      s.raise(StatusLevel::Warn, "source " + src.name + " on " + src.topic + " is late: " +
                                     (c.accepted == 0 ? std::string("no reading yet, ") : std::string()) + text);
    }
    else if (c.accepted == 0 && c.rejected > 0)
      s.raise(StatusLevel::Warn,
              "source " + src.name + " on " + src.topic + ": every reading rejected (" + c.last_rejection + ")");
  }
  if (!enabled())
    s.message = "disabled";
  else if (s.level == StatusLevel::Ok)
    s.message = buffers_.empty() ? "no observation sources: only clears the footprint"
                                 : std::to_string(buffers_.size()) + " source(s) current";
  return s;
}

namespace
{
/// Moves a point of the sensor's frame into the global frame and keeps it when its height is within
/// the source's limits (and its coordinates finite).
struct Projection
{
  const Transform3D& T;
  double zmin, zmax;
  void operator()(const Point3f& p, std::vector<Point3f>& out) const
  {
    double gx, gy, gz;
    T.apply(p.x, p.y, p.z, gx, gy, gz);
    if (!(gz >= zmin && gz <= zmax)) return;  // also drops NaN from a broken transform
    if (!std::isfinite(gx) || !std::isfinite(gy)) return;
    out.push_back({static_cast<float>(gx), static_cast<float>(gy), static_cast<float>(gz)});
  }
};
}  // namespace

std::string ObstacleLayer::refuseReading(std::size_t source, const std::string& error)
{
  context_->report(Severity::Warn, "invalid/" + config_.sources[source].name,
                   sourceLabel(source) + ": reading rejected: " + error);
  return noteReading(source, error);
}

// Each reading goes from the message's own storage straight into the observation the buffer keeps: the
// points are parsed, moved into the global frame and height-filtered in one pass, with no copy between.
std::string ObstacleLayer::addLaserScan(std::size_t source, const LaserScanData& scan, const SensorPose& pose)
{
  if (source >= config_.sources.size()) return "no observation source " + std::to_string(source);
  if (!active_) return {};
  const std::string invalid = validateLaserScan(scan);
  if (!invalid.empty()) return refuseReading(source, invalid);
  const uint64_t now = context_->nowNs();
  std::string refused = refuseStamp(source, scan.stamp_ns, now);
  if (!refused.empty()) return noteReading(source, std::move(refused));
  const ObservationSourceConfig& s = config_.sources[source];
  std::shared_ptr<Observation> obs = startObservation(source, scan.stamp_ns, now, pose);
  obs->points.reserve(scan.ranges.size());
  const Projection project{pose.to_global, s.min_obstacle_height, s.max_obstacle_height};
  ParseResult r;
  forEachScanPoint(scan, s.inf_is_valid, r,
                   [&](const Point3f& p, bool clear_only) { project(p, clear_only ? obs->clear_only : obs->points); });
  buffers_[source]->add(std::move(obs), now);
  return noteReading(source, {});
}

std::string ObstacleLayer::addPointCloud2(std::size_t source, const PointCloud2Data& cloud, const SensorPose& pose)
{
  if (source >= config_.sources.size()) return "no observation source " + std::to_string(source);
  if (!active_) return {};
  detail::CloudLayout layout;
  const std::string invalid = detail::cloudLayout(cloud, layout);
  if (!invalid.empty()) return refuseReading(source, invalid);
  const uint64_t now = context_->nowNs();
  std::string refused = refuseStamp(source, cloud.stamp_ns, now);
  if (!refused.empty()) return noteReading(source, std::move(refused));
  const ObservationSourceConfig& s = config_.sources[source];
  std::shared_ptr<Observation> obs = startObservation(source, cloud.stamp_ns, now, pose);
  // The layout check bounds width * height by data.size() / point_step, so this reservation is safe.
  obs->points.reserve(static_cast<std::size_t>(cloud.width) * cloud.height);
  const Projection project{pose.to_global, s.min_obstacle_height, s.max_obstacle_height};
  ParseResult r;
  forEachCloudPoint(cloud, layout, r, [&](const Point3f& p) { project(p, obs->points); });
  buffers_[source]->add(std::move(obs), now);
  return noteReading(source, {});
}

std::string ObstacleLayer::refuseStamp(std::size_t source, uint64_t stamp_ns, uint64_t now)
{
  const ObservationSourceConfig& s = config_.sources[source];
  // Buffered, it would count as fresh until the clock caught up with it: a ghost re-marked every cycle.
  if (isAheadOfNow(stamp_ns, now))
  {
    const std::string error = aheadOfNowError(stamp_ns, now);
    context_->report(Severity::Warn, "future/" + s.name, sourceLabel(source) + ": reading rejected: " + error);
    return error;
  }
  // costmap_2d buffers such a reading and purges it at once, counting it as an update: the source reads
  // current while nothing is ever marked. Refused here, said, and counted as a rejection.
  if (stamp_ns != 0 && olderThanPersistence(stamp_ns, now, s.observation_persistence))
  {
    const std::string error = olderThanPersistenceError(stamp_ns, now, s.observation_persistence);
    context_->report(Severity::Warn, "old/" + s.name, sourceLabel(source) + ": reading rejected: " + error);
    return error;
  }
  return {};
}

std::shared_ptr<Observation> ObstacleLayer::startObservation(std::size_t source, uint64_t stamp_ns, uint64_t now,
                                                             const SensorPose& pose)
{
  const ObservationSourceConfig& s = config_.sources[source];
  std::shared_ptr<Observation> obs = pool_->take();
  obs->origin_x = pose.origin_x;
  obs->origin_y = pose.origin_y;
  obs->origin_z = pose.origin_z;
  obs->stamp_ns = stamp_ns != 0 ? stamp_ns : now;
  obs->obstacle_min_range = s.obstacle_min_range;
  obs->obstacle_max_range = s.obstacle_max_range;
  obs->raytrace_min_range = s.raytrace_min_range;
  obs->raytrace_max_range = s.raytrace_max_range;
  return obs;
}

void ObstacleLayer::addStaticObservation(const Observation& observation, bool marking, bool clearing)
{
  auto obs = std::make_shared<const Observation>(observation);
  std::lock_guard<std::mutex> lock(static_mutex_);
  if (marking) static_marking_.push_back(obs);
  if (clearing) static_clearing_.push_back(obs);
}

void ObstacleLayer::clearStaticObservations(bool marking, bool clearing)
{
  std::lock_guard<std::mutex> lock(static_mutex_);
  if (marking) static_marking_.clear();
  if (clearing) static_clearing_.clear();
}

void ObstacleLayer::updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y,
                                 double* max_x, double* max_y)
{
  const auto [shift_x, shift_y] = followRollingMaster();
  if (shift_x != 0 || shift_y != 0) onGridShifted(shift_x, shift_y);
  useExtraBounds(min_x, min_y, max_x, max_y);

  const uint64_t now = context_->nowNs();
  bool current = true;
  marking_.clear();
  clearing_.clear();
  for (std::size_t i = 0; i < buffers_.size(); ++i)
  {
    ObservationBuffer& b = *buffers_[i];
    if (!b.isCurrent(now))
    {
      current = false;
      char text[128];
      std::snprintf(text, sizeof(text), " has not been updated for %.2f s, expected every %.2f s",
                    b.secondsSinceUpdate(now), b.config().expected_update_rate);
      context_->report(Severity::Warn, "late/" + config_.sources[i].name, sourceLabel(i) + text);
    }
    scratch_.clear();
    b.getObservations(scratch_, now, robot_x, robot_y);
    if (config_.sources[i].marking) marking_.insert(marking_.end(), scratch_.begin(), scratch_.end());
    if (config_.sources[i].clearing) clearing_.insert(clearing_.end(), scratch_.begin(), scratch_.end());
  }
  {
    std::lock_guard<std::mutex> lock(static_mutex_);
    marking_.insert(marking_.end(), static_marking_.begin(), static_marking_.end());
    clearing_.insert(clearing_.end(), static_clearing_.begin(), static_clearing_.end());
  }
  current_ = current;
  reportClockJump();

  for (const auto& obs : clearing_)
    raytraceFreespace(*obs, min_x, min_y, max_x, max_y);
  for (const auto& obs : marking_)
    markObservation(*obs, min_x, min_y, max_x, max_y);
  // Drop the references now: an observation must not outlive its buffer's persistence by a cycle.
  marking_.clear();
  clearing_.clear();
  scratch_.clear();

  transformed_footprint_.clear();
  if (config_.footprint_clearing_enabled)
  {
    transformed_footprint_ = transformFootprint(robot_x, robot_y, robot_yaw, getFootprint());
    for (const auto& v : transformed_footprint_)
      touch(v.x(), v.y(), min_x, min_y, max_x, max_y);
  }
}

void ObstacleLayer::reportClockJump()
{
  for (auto& b : buffers_)
    if (const std::size_t n = b->takeDropped())
      context_->report(Severity::Warn, "flood/" + b->name(),
                       name_ + ": observation source '" + b->name() +
                           "': readings arrive faster than they expire: dropped the " + std::to_string(n) +
                           " oldest since the last update (at most " +
                           std::to_string(ObservationBuffer::kMaxObservations) + " are kept)");
  // The buffers saw the jump (on this thread or a sensor thread) and dropped their readings: one warning
  // for all of them.
  std::optional<ObservationBuffer::ClockJump> jump;
  for (auto& b : buffers_)
  {
    const auto j = b->takeClockJump();
    if (!j) continue;
    if (!jump)
      jump = j;
    else
    {
      jump->from_ns = std::max(jump->from_ns, j->from_ns);
      jump->to_ns = std::min(jump->to_ns, j->to_ns);
      jump->dropped += j->dropped;
    }
  }
  if (!jump) return;
  context_->report(Severity::Warn, "clock_jump",
                   name_ + ": " + clockJumpMessage(jump->from_ns, jump->to_ns) + ": dropped " +
                       std::to_string(jump->dropped) +
                       " buffered reading(s); the expected_update_rate checks restart now (the grid is kept)");
}

bool ObstacleLayer::clipRay2D(double ox, double oy, double wx, double wy, double max_range, double& t) const
{
  const double x0 = costmap_.getOriginX(), y0 = costmap_.getOriginY();
  const double x1 = x0 + costmap_.getSizeInMetersX(), y1 = y0 + costmap_.getSizeInMetersY();
  if (!(ox >= x0 && ox < x1 && oy >= y0 && oy < y1)) return false;
  const double a = wx - ox, b = wy - oy;
  t = 1.0;
  const double d2 = a * a + b * b;
  if (d2 > max_range * max_range) t = max_range / std::sqrt(d2);
  t = clipRayToBox<2>({ox, oy}, {a, b}, {x0, y0}, {x1, y1}, t);
  return true;
}

bool ObstacleLayer::marksPoint(const Observation& obs, const Point3f& p, unsigned int& mx, unsigned int& my) const
{
  if (!config_.marksHeight(p.z)) return false;
  const double dx = p.x - obs.origin_x, dy = p.y - obs.origin_y, dz = p.z - obs.origin_z;
  const double d2 = dx * dx + dy * dy + dz * dz;
  if (d2 > obs.obstacle_max_range * obs.obstacle_max_range || d2 < obs.obstacle_min_range * obs.obstacle_min_range)
    return false;
  return costmap_.worldToMap(p.x, p.y, mx, my);
}

void ObstacleLayer::raytraceFreespace(const Observation& obs, double* min_x, double* min_y, double* max_x,
                                      double* max_y)
{
  const double ox = obs.origin_x, oy = obs.origin_y;
  unsigned int x0, y0;
  if (!costmap_.worldToMap(ox, oy, x0, y0))
  {
    context_->report(Severity::Warn, "origin_outside",
                     name_ + ": a sensor origin is outside the costmap, its rays clear nothing");
    return;
  }
  touch(ox, oy, min_x, min_y, max_x, max_y);
  const double min_cells = costmap_.cellDistance(obs.raytrace_min_range);
  // costmap_2d's reach: the range in whole cells, rounded up (cellDistance), and every cell of the walk
  // up to that many cells along the line, the end cell included (its raytraceLine). NaN clears nothing.
  const unsigned int range_cells = costmap_.cellDistance(obs.raytrace_max_range);
  const double max_cells = std::isnan(obs.raytrace_max_range) ? -1.0 : static_cast<double>(range_cells);
  // The walk itself stops a little beyond (cellDistance saturates for huge ranges).
  const unsigned int walk_cells = range_cells < 0xFFFFFFFDu ? range_cells + 2 : 0xFFFFFFFFu;
  const unsigned int size_x = costmap_.getSizeInCellsX();
  uint8_t* grid = costmap_.data();
  TouchedBox<unsigned int> visited_cells(x0, y0);
  ray_ends_.reset(costmap_.cellCount());
  auto ray = [&](const Point3f& p)
  {
    // As costmap_2d: the line runs towards the reading's own cell (cut at the grid's border only) and
    // stops after raytrace_max_range in cells, so a beam longer than the range keeps its direction
    // (a line to the cell of the point cut at the range would bend by up to a cell over the range).
    double t;
    if (!clipRay2D(ox, oy, p.x, p.y, std::numeric_limits<double>::infinity(), t)) return;
    int cx, cy;
    costmap_.worldToMapEnforceBounds(ox + t * (p.x - ox), oy + t * (p.y - oy), cx, cy);
    // A walk depends on its two end cells only: a ray ending where an earlier one of this observation
    // ended clears nothing new (a dense cloud sends many readings per cell).
    const std::size_t end = static_cast<std::size_t>(cy) * size_x + static_cast<std::size_t>(cx);
    if (ray_ends_.test(end)) return;
    ray_ends_.set(end);
    const int dx = cx - static_cast<int>(x0), dy = cy - static_cast<int>(y0);
    const unsigned int abs_dx = static_cast<unsigned int>(std::abs(dx)),
                       abs_dy = static_cast<unsigned int>(std::abs(dy));
    // The walk is costmap_2d's raytraceLine (Costmap2D::raytraceLine): one step of the major axis per
    // cell, cut at walk_cells along the line, the end cell (the reading's, or where the grid cuts the
    // line) visited last. Step k lies k * step cells along the line from the origin's cell. Cleared:
    // min_cells <= k * step <= the range in whole cells, as costmap_2d clears: the reading's own cell
    // too (marked again afterwards when the reading marks), and a reading in the origin's cell clears
    // that cell. Both ends are applied on the same line (costmap_2d restarts the line from a rounded
    // cell at the minimum range, which bends it). The first and last cleared step are found once per
    // ray, so the walk itself only writes.
    const bool x_major = abs_dx >= abs_dy;
    const unsigned int abs_da = x_major ? abs_dx : abs_dy, abs_db = x_major ? abs_dy : abs_dx;
    const double dist = lineLength(abs_dx, abs_dy);
    const double step = abs_da == 0 ? 0.0 : dist / abs_da;
    const double scale = dist == 0.0 ? 1.0 : std::min(1.0, walk_cells / dist);
    const int64_t length = static_cast<unsigned int>(scale * abs_da);  // the walk's last step
    int64_t lo, hi;
    if (step == 0.0)
    {
      const bool cleared = 0.0 >= min_cells && 0.0 <= max_cells;
      lo = 0;
      hi = cleared ? 0 : -1;
    }
    else
    {
      lo = firstStepAtLeast(step, min_cells);
      hi = std::min(length, lastStepAtMost(step, max_cells));
    }
    if (hi < lo) return;
    const int offset_a = x_major ? (dx > 0 ? 1 : -1) : (dy > 0 ? 1 : -1) * static_cast<int>(size_x);
    const int offset_b = x_major ? (dy > 0 ? 1 : -1) * static_cast<int>(size_x) : (dx > 0 ? 1 : -1);
    unsigned int offset = y0 * size_x + x0;
    unsigned int error = abs_da / 2;
    for (int64_t k = 0;; ++k)
    {
      if (k >= lo) grid[offset] = FREE_SPACE;
      if (k == hi) break;
      offset += offset_a;
      error += abs_db;
      if (error >= abs_da)
      {
        offset += offset_b;
        error -= abs_da;
      }
    }
    // Bresenham stays in the box of its first and last cells: that box is what changed.
    visited_cells.add(offset % size_x, offset / size_x);
  };
  for (const Point3f& p : obs.points)
    ray(p);
  for (const Point3f& p : obs.clear_only)
    ray(p);
  double wx, wy;
  costmap_.mapToWorld(visited_cells.min_x, visited_cells.min_y, wx, wy);
  touch(wx, wy, min_x, min_y, max_x, max_y);
  costmap_.mapToWorld(visited_cells.max_x, visited_cells.max_y, wx, wy);
  touch(wx, wy, min_x, min_y, max_x, max_y);
}

void ObstacleLayer::markObservation(const Observation& obs, double* min_x, double* min_y, double* max_x, double* max_y)
{
  uint8_t* grid = costmap_.data();
  TouchedBox<double> marked;
  for (const Point3f& p : obs.points)
  {
    unsigned int mx, my;
    if (!marksPoint(obs, p, mx, my)) continue;
    grid[costmap_.getIndex(mx, my)] = LETHAL_OBSTACLE;
    marked.add(p.x, p.y);
  }
  if (!marked.empty())
  {
    touch(marked.min_x, marked.min_y, min_x, min_y, max_x, max_y);
    touch(marked.max_x, marked.max_y, min_x, min_y, max_x, max_y);
  }
}

void ObstacleLayer::updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j)
{
  if (config_.footprint_clearing_enabled && transformed_footprint_.size() >= 3)
    costmap_.setConvexPolygonCost(transformed_footprint_, FREE_SPACE);
  switch (config_.combination_method)
  {
    case 0:
      updateWithOverwrite(master_grid, min_i, min_j, max_i, max_j);
      break;
    case 2:
      updateWithMaxWithoutUnknownOverwrite(master_grid, min_i, min_j, max_i, max_j);
      break;
    case 99:  // costmap_2d's "Do nothing": the layer keeps its marks to itself
      break;
    default:
      updateWithMax(master_grid, min_i, min_j, max_i, max_j);
      break;
  }
}

void ObstacleLayer::reset()
{
  costmap_.resetMaps();
  for (auto& b : buffers_)
    b->clear();
  clearStaticObservations(true, true);
  const uint64_t now = context_ ? context_->nowNs() : 0;
  for (auto& b : buffers_)
    b->resetLastUpdated(now);
  current_ = true;
}

void ObstacleLayer::activate()
{
  active_ = true;
  const uint64_t now = context_->nowNs();
  for (auto& b : buffers_)
    b->resetLastUpdated(now);
}

void ObstacleLayer::deactivate()
{
  active_ = false;
}
}  // namespace costmap_layers
