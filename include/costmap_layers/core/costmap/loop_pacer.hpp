// The update loop's clock rules, without ROS: when the next cycle starts, and when a loop that has not
// finished a cycle for too long is stalled. The node feeds it times of a monotonic clock (steady), so
// a step of the system clock neither freezes the loop nor bursts it; the rules still hold if the
// times it is fed ever go back.
#pragma once

namespace costmap_layers
{
class LoopPacer
{
public:
  /// @param period_s  the update period [s], > 0 (1 / update_frequency)
  explicit LoopPacer(double period_s);

  /// The first cycle starts at now_s.
  void start(double now_s);
  /// After a cycle that ended at now_s: how long to wait [s] before the next one starts, in [0, period].
  /// Cycles start on the intended period (start + k period); a late cycle starts the next at once
  /// rather than bursting to catch up; times that go back wait one period at most.
  double waitAfterCycle(double now_s);
  /// Notes the end of a cycle at now_s, for stalled().
  void noteCycleEnd(double now_s);
  /// How long [s] the loop has not finished a cycle at now_s when that is more than 3 periods (and more
  /// than 1 s), else 0: a loop stuck in a cycle or waiting for something says so.
  double stalledFor(double now_s) const;
  /// Seconds since the last cycle ended (never negative), or -1 when none ended yet.
  double sinceLastCycle(double now_s) const;

private:
  double period_s_;
  bool started_ = false;
  double next_s_ = 0.0;
  bool cycled_ = false;
  double last_end_s_ = 0.0;
};
}  // namespace costmap_layers
