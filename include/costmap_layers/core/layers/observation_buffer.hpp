// costmap_2d's Observation and ObservationBuffer: sensor points already in the global frame, with the
// sensor origin and the ranges of their source, kept for a while and handed to the update thread.
// Times are passed in (the layers use LayerContext::nowNs()), so the buffer itself has no clock; it
// notices the clock jumping back (see stamp_order.hpp) and then drops everything, as tf does.
// Every method is thread-safe: readings arrive on the host's sensor threads, updates run elsewhere.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "costmap_layers/core/layers/sensor_parsing.hpp"
#include "costmap_layers/core/rules/stamp_order.hpp"

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

/// Observations to fill, reused once every reference to them went: their vectors keep their capacity,
/// so that a sensor's steady stream of readings allocates no point storage. Thread-safe; an observation
/// may outlive its pool (it is then freed as usual).
class ObservationPool
{
public:
  /// The most unused observations kept (each holds a reading's worth of points).
  static constexpr std::size_t kMaxFree = 4;
  static std::shared_ptr<ObservationPool> make();
  /// An observation with no points and the defaults otherwise; returned here when released.
  std::shared_ptr<Observation> take();

private:
  ObservationPool() = default;
  void giveBack(Observation* observation);

  std::weak_ptr<ObservationPool> self_;
  std::mutex mutex_;
  std::vector<std::unique_ptr<Observation>> free_;  ///< guarded by mutex_
};

/// True when a reading stamped stamp_ns is older at now_ns than observation_persistence (> 0) allows:
/// a buffer drops it (a reading stamped ahead counts as age 0). 0 (keep the newest) never expires one.
bool olderThanPersistence(uint64_t stamp_ns, uint64_t now_ns, double observation_persistence);

struct ObservationBufferConfig
{
  /// [s] how long an observation is kept, measured from its stamp to the current time; 0 keeps only
  /// the newest one (costmap_2d's observation_persistence). Observations stamped more than
  /// kFutureStampToleranceNs ahead of the current time are dropped whatever this is.
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
  /// What the buffer did when it saw the clock jump back.
  struct ClockJump
  {
    uint64_t from_ns = 0;     ///< the latest time seen before the jump
    uint64_t to_ns = 0;       ///< the time after it
    std::size_t dropped = 0;  ///< observations dropped
  };

  /// @param now_ns  creation time: a buffer that never receives anything goes stale from here, as in
  ///                costmap_2d where last_updated_ starts at construction.
  ObservationBuffer(std::string name, const ObservationBufferConfig& config, uint64_t now_ns);

  /// The most observations a buffer keeps (however long observation_persistence is): a flood of
  /// readings pushes the oldest out, counted (takeDropped()), so that neither memory nor the work of
  /// an update grows with the sender's rate.
  static constexpr std::size_t kMaxObservations = 256;

  /// Adds an observation received at now_ns (the time the update-rate check uses) and drops stale ones.
  /// @return false when the observation was dropped at once for being stamped more than
  /// kFutureStampToleranceNs ahead of now_ns (it does not count as an update then).
  bool add(std::shared_ptr<const Observation> observation, uint64_t now_ns);

  /// Drops stale and distant observations, then appends the remaining ones (oldest first) to out.
  /// Stale: older than observation_persistence, or stamped more than kFutureStampToleranceNs ahead of
  /// now_ns, wherever they are in the buffer.
  void getObservations(std::vector<std::shared_ptr<const Observation>>& out, uint64_t now_ns, double robot_x,
                       double robot_y);

  /// False when expected_update_rate > 0 and the newest reading arrived more than that many seconds
  /// before now_ns (costmap_2d: now - last_updated <= expected_update_rate).
  bool isCurrent(uint64_t now_ns) const;
  /// [s] since the newest reading arrived (or since creation / the last resetLastUpdated() / the last
  /// clock jump back).
  double secondsSinceUpdate(uint64_t now_ns) const;
  /// Restarts the update-rate check at now_ns (after a reset or activation).
  void resetLastUpdated(uint64_t now_ns);
  /// Drops every observation.
  void clear();
  std::size_t size() const;

  /// The clock jump back seen since the last call, if any (several merge into one: the first time
  /// before, the last time after). Every method that takes now_ns watches for one: when now_ns lies more
  /// than kClockJumpBackToleranceNs before the latest time seen, every observation is dropped (their
  /// stamps belong to the time line before the jump) and the update-rate check restarts at now_ns.
  std::optional<ClockJump> takeClockJump();
  /// How many observations kMaxObservations pushed out since the last call.
  std::size_t takeDropped();

  const std::string& name() const { return name_; }
  const ObservationBufferConfig& config() const { return config_; }

private:
  /// Notes now_ns, handling a jump back. Called under the lock (also from the const queries: the
  /// buffer catching up with the clock is not a change its users asked for).
  void noteTimeLocked(uint64_t now_ns) const;
  void purgeLocked(uint64_t now_ns);

  const std::string name_;
  const ObservationBufferConfig config_;
  mutable std::mutex mutex_;
  mutable std::deque<std::shared_ptr<const Observation>> observations_;  ///< in arrival order
  mutable uint64_t last_updated_ns_;
  mutable ClockWatch clock_;
  mutable std::optional<ClockJump> jump_;
  std::size_t dropped_ = 0;  ///< pushed out by kMaxObservations since the last takeDropped()
};
}  // namespace costmap_layers
