#include "costmap_layers/core/costmap/loop_pacer.hpp"

#include <algorithm>

namespace costmap_layers
{
LoopPacer::LoopPacer(double period_s) : period_s_(period_s > 0.0 ? period_s : 1.0) {}

void LoopPacer::start(double now_s)
{
  started_ = true;
  next_s_ = now_s;
}

double LoopPacer::waitAfterCycle(double now_s)
{
  if (!started_) start(now_s);
  next_s_ += period_s_;
  if (next_s_ <= now_s)
    next_s_ = now_s;  // late: the cycle took longer than the period, start the next at once
  else if (next_s_ - now_s > period_s_)
    next_s_ = now_s + period_s_;  // more than a period ahead: the times went back, restart from now
  return next_s_ - now_s;
}

void LoopPacer::noteCycleEnd(double now_s)
{
  cycled_ = true;
  last_end_s_ = now_s;
}

double LoopPacer::sinceLastCycle(double now_s) const
{
  if (!cycled_) return -1.0;
  return std::max(0.0, now_s - last_end_s_);
}

double LoopPacer::stalledFor(double now_s) const
{
  if (!cycled_) return 0.0;
  const double since = sinceLastCycle(now_s);
  return since > std::max(3.0 * period_s_, 1.0) ? since : 0.0;
}
}  // namespace costmap_layers
