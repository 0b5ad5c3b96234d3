// The core's rules for time. Whether a map, mask or speed-limit message arrived out of order: latched
// topics re-send their last message on every reconnection, and a second publisher (an old map server
// left running) can send an older grid after a newer one: applying it would silently roll the costmap
// back. Whether a sensor reading is stamped ahead of now, and whether the clock jumped back (a looping
// bag or a restarted simulator under /use_sim_time): then, as tf does with its buffer, the layers drop
// what they buffered by time and restart their timeouts at the jump.
#pragma once

#include <cstdint>
#include <string>

namespace costmap_layers
{
/// True when a message stamped stamp_ns is older than the one in force (stamped in_force_ns) and must
/// be dropped. A zero stamp on either side carries no time and never makes a message stale. When the
/// clock went back below the stamp in force (a restarted simulation, a looping bag: now_ns < in_force_ns),
/// every message is accepted, or nothing would ever be accepted again.
inline bool isOutOfOrder(uint64_t stamp_ns, uint64_t in_force_ns, uint64_t now_ns)
{
  return stamp_ns != 0 && in_force_ns != 0 && stamp_ns < in_force_ns && in_force_ns <= now_ns;
}

/// "header.stamp 12.500 s is older than the <what> in force (stamped 20.000 s)": the error a layer
/// reports for an out-of-order message; it starts with the field's name, the key its report is
/// throttled by.
std::string outOfOrderError(uint64_t stamp_ns, uint64_t in_force_ns, const std::string& what);

/// [ns] How far the clock may step back before it counts as a jump back. Smaller steps are the jitter
/// of threads that read the clock a moment apart (a sensor thread, the update thread) and are ignored.
constexpr uint64_t kClockJumpBackToleranceNs = 500'000'000;
/// [ns] How far ahead of now a sensor reading may be stamped (clock skew between hosts); readings stamped
/// further ahead are refused: they would count as fresh until the clock caught up with them.
constexpr uint64_t kFutureStampToleranceNs = 500'000'000;

/// True when stamp_ns lies more than kFutureStampToleranceNs after now_ns.
inline bool isAheadOfNow(uint64_t stamp_ns, uint64_t now_ns)
{
  return stamp_ns > now_ns && stamp_ns - now_ns > kFutureStampToleranceNs;
}

/// "header.stamp 100.000 s is 90.000 s ahead of now 10.000 s": why a reading was refused; it starts with
/// the field's name.
std::string aheadOfNowError(uint64_t stamp_ns, uint64_t now_ns);

/// "header.stamp 8.000 s is 2.000 s old at now 10.000 s, more than observation_persistence (1 s) ...": why
/// a reading that would expire on arrival was refused; it starts with the field's name.
std::string olderThanPersistenceError(uint64_t stamp_ns, uint64_t now_ns, double observation_persistence);

/// "the clock jumped back from 1000.000 s to 3.000 s": the start of the one warning a layer reports.
std::string clockJumpMessage(uint64_t from_ns, uint64_t to_ns);

/// Notices the clock jumping back, as tf's listener does (now earlier than the latest time seen), with
/// kClockJumpBackToleranceNs of slack. Not thread-safe: its owner holds its own lock or thread.
class ClockWatch
{
public:
  /// Notes now_ns. @return true when it lies more than the tolerance before the latest time noted (a
  /// jump back); now_ns is then the latest time. Smaller steps back leave the latest time as it was.
  bool jumpedBack(uint64_t now_ns)
  {
    if (now_ns < latest_ns_ && latest_ns_ - now_ns > kClockJumpBackToleranceNs)
    {
      latest_ns_ = now_ns;
      return true;
    }
    if (now_ns > latest_ns_) latest_ns_ = now_ns;
    return false;
  }
  /// The latest time noted (0 before any).
  uint64_t latest() const { return latest_ns_; }

private:
  uint64_t latest_ns_ = 0;
};

/// [ns] A latched input (a map, a mask, a filter info) reaches a layer moments after start-up: a layer
/// says it is waiting for one only once this much time has passed without it (then every cycle, as the
/// host's log throttles), so that a start-up that works prints no warning.
constexpr uint64_t kStartupGraceNs = 2'000'000'000;

/// When a start-up grace ends: started at the first time noted, again after the clock jumped back
/// (rosbag play --loop). Not thread-safe: the update thread owns it.
class StartupGrace
{
public:
  /// Notes now_ns; true once kStartupGraceNs have passed since the grace started.
  bool over(uint64_t now_ns)
  {
    if (!started_ || now_ns < start_ns_)
    {
      started_ = true;
      start_ns_ = now_ns;
    }
    return now_ns - start_ns_ >= kStartupGraceNs;
  }

private:
  bool started_ = false;
  uint64_t start_ns_ = 0;
};
}  // namespace costmap_layers
