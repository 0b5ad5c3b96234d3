// The update loop's pacing and stall rules (LoopPacer), at the edges of time. Expected values are
// worked out by hand from the period.
#include <gtest/gtest.h>

#include "costmap_layers/core/costmap/loop_pacer.hpp"

using costmap_layers::LoopPacer;

TEST(LoopPacer, CyclesStartOnThePeriod)
{
  LoopPacer p(0.2);
  p.start(100.0);
  EXPECT_NEAR(p.waitAfterCycle(100.05), 0.15, 1e-9);  // the next cycle at 100.2
  EXPECT_NEAR(p.waitAfterCycle(100.30), 0.10, 1e-9);  // cycle 2 started at 100.2: the next at 100.4
  EXPECT_NEAR(p.waitAfterCycle(100.40), 0.20, 1e-9);  // cycle 3 started late (100.4 ended it): 100.6
}

TEST(LoopPacer, ALateCycleStartsTheNextAtOnceWithoutABurst)
{
  LoopPacer p(0.1);
  p.start(10.0);
  EXPECT_DOUBLE_EQ(p.waitAfterCycle(12.0), 0.0);     // 2 s late: no 20 cycles to catch up
  EXPECT_NEAR(p.waitAfterCycle(12.05), 0.05, 1e-9);  // the schedule restarted at 12.0
}

// A clock that steps back (the system clock set back by 990 s, were it wall time) waits one period at
// most, never the size of the step: the loop that waited 990 s froze the costmap for 990 s.
TEST(LoopPacer, TimesGoingBackWaitOnePeriodAtMost)
{
  LoopPacer p(0.2);
  p.start(1000.0);
  EXPECT_NEAR(p.waitAfterCycle(1000.1), 0.1, 1e-9);
  EXPECT_NEAR(p.waitAfterCycle(10.0), 0.2, 1e-9);    // back by 990 s
  EXPECT_NEAR(p.waitAfterCycle(10.25), 0.15, 1e-9);  // on the new schedule: 10.2, then 10.4
  // A first call without start() starts the schedule there.
  LoopPacer q(0.5);
  EXPECT_NEAR(q.waitAfterCycle(3.0), 0.5, 1e-9);
}

TEST(LoopPacer, AStalledLoopIsNamedAfterThreePeriodsOrOneSecond)
{
  LoopPacer p(0.1);                           // 3 periods = 0.3 s: the 1 s floor applies
  EXPECT_DOUBLE_EQ(p.stalledFor(50.0), 0.0);  // no cycle yet: "waiting", not stalled
  EXPECT_DOUBLE_EQ(p.sinceLastCycle(50.0), -1.0);
  p.noteCycleEnd(50.0);
  EXPECT_DOUBLE_EQ(p.stalledFor(50.9), 0.0);
  EXPECT_NEAR(p.stalledFor(51.5), 1.5, 1e-9);
  EXPECT_NEAR(p.sinceLastCycle(51.5), 1.5, 1e-9);
  EXPECT_DOUBLE_EQ(p.sinceLastCycle(49.0), 0.0);  // never negative
  LoopPacer slow(2.0);                            // 3 periods = 6 s
  slow.noteCycleEnd(0.0);
  EXPECT_DOUBLE_EQ(slow.stalledFor(5.9), 0.0);
  EXPECT_NEAR(slow.stalledFor(6.5), 6.5, 1e-9);
}
