// costmap_2d's Observation and ObservationBuffer: sensor points already in the global frame, with the
// sensor origin and the ranges of their source, kept for a while and handed to the update thread.
// Times are passed in (the layers use LayerContext::nowNs()), so the buffer itself has no clock.
// Every method is thread-safe: readings arrive on the host's sensor threads, updates run elsewhere.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "costmap_layers/core/sensor_parsing.hpp"

namespace costmap_layers
{
/// One reading in the global frame. Immutable once buffered (shared between threads).
struct Observation
{
  double origin_x = 0, origin_y = 0, origin_z = 0;  ///< sensor origin [m], global frame
  std::vector<Point3f> points;                      ///< hits: rays clear up to them and they may be marked [m, global]
  std::vector<Point3f> clear_only;  ///< no-return points (inf ranges): rays only, never marked [m, global]
  uint64_t stamp_ns = 0;            ///< when the reading was taken
  double obstacle_min_range = 0.0, obstacle_max_range = 2.5;  ///< [m] marking window from the origin
  double raytrace_min_range = 0.0, raytrace_max_range = 3.0;  ///< [m] clearing window from the origin
};

struct ObservationBufferConfig
{
  /// [s] how long an observation is kept, measured from its stamp to the current time; 0 keeps only
  /// the newest one (costmap_2d's observation_persistence).
  double observation_persistence = 0.0;
  /// [s] despite the name (costmap_2d's), a period: the buffer is current while the newest reading
  /// arrived at most this many seconds ago; 0 disables the check.
  double expected_update_rate = 0.0;
  /// [m] observations whose sensor origin lies farther than this from the robot (in x, y) are dropped;
  /// 0 disables it.
  double observation_keep_distance = 0.0;
};

class ObservationBuffer
{
public:
  /// @param now_ns  creation time: a buffer that never receives anything goes stale from here, as in
  ///                costmap_2d where last_updated_ starts at construction.
  ObservationBuffer(std::string name, const ObservationBufferConfig& config, uint64_t now_ns);

  /// Adds an observation received at now_ns (the time the update-rate check uses) and drops stale ones.
  void add(std::shared_ptr<const Observation> observation, uint64_t now_ns);

  /// Drops stale and distant observations, then appends the remaining ones (oldest first) to out.
  void getObservations(std::vector<std::shared_ptr<const Observation>>& out, uint64_t now_ns, double robot_x,
                       double robot_y);

  /// False when expected_update_rate > 0 and the newest reading arrived more than that many seconds
  /// before now_ns (costmap_2d: now - last_updated <= expected_update_rate).
  bool isCurrent(uint64_t now_ns) const;
  /// [s] since the newest reading arrived (or since creation / the last resetLastUpdated()).
  double secondsSinceUpdate(uint64_t now_ns) const;
  /// Restarts the update-rate check at now_ns (after a reset or activation).
  void resetLastUpdated(uint64_t now_ns);
  /// Drops every observation.
  void clear();
  std::size_t size() const;

  const std::string& name() const { return name_; }
  const ObservationBufferConfig& config() const { return config_; }

private:
  void purgeLocked(uint64_t now_ns);

  const std::string name_;
  const ObservationBufferConfig config_;
  mutable std::mutex mutex_;
  std::deque<std::shared_ptr<const Observation>> observations_;  ///< oldest first
  uint64_t last_updated_ns_;
};
}  // namespace costmap_layers
