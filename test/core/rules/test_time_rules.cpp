// The core's rules for time: stamps ahead of now, clock jumps back (a looping bag, a restarted
// simulator under /use_sim_time) and forward, and the extremes a sender can write (0, UINT64_MAX).
#include <gtest/gtest.h>

#include <cstdint>

#include "costmap_layers/core/rules/stamp_order.hpp"

using namespace costmap_layers;

namespace
{
constexpr uint64_t kSec = 1'000'000'000ull;
}  // namespace

TEST(TimeRules, StampsAheadOfNow)
{
  EXPECT_FALSE(isAheadOfNow(10 * kSec, 10 * kSec));
  EXPECT_FALSE(isAheadOfNow(10 * kSec + 500'000'000, 10 * kSec));  // the tolerance itself: skew between hosts
  EXPECT_TRUE(isAheadOfNow(10 * kSec + 500'000'001, 10 * kSec));
  EXPECT_FALSE(isAheadOfNow(0, 10 * kSec));  // older is never ahead
  EXPECT_TRUE(isAheadOfNow(UINT64_MAX, 10 * kSec));
  EXPECT_TRUE(isAheadOfNow(UINT64_MAX, 0));
  EXPECT_FALSE(isAheadOfNow(UINT64_MAX, UINT64_MAX));
  EXPECT_FALSE(isAheadOfNow(0, UINT64_MAX));
  const std::string e = aheadOfNowError(100 * kSec, 10 * kSec);
  EXPECT_EQ(e.rfind("header.stamp 100.000 s", 0), 0u) << e;
  EXPECT_NE(e.find("now 10.000 s"), std::string::npos) << e;
}

TEST(TimeRules, ClockWatchSeesJumpsBackOnly)
{
  ClockWatch w;
  EXPECT_FALSE(w.jumpedBack(0));
  EXPECT_FALSE(w.jumpedBack(100 * kSec));
  EXPECT_FALSE(w.jumpedBack(100 * kSec - 500'000'000));  // within the tolerance: jitter between threads
  EXPECT_EQ(w.latest(), 100 * kSec);                     // ... which does not lower the latest time
  EXPECT_FALSE(w.jumpedBack(10'000 * kSec));             // forward jumps are not jumps back
  EXPECT_TRUE(w.jumpedBack(3 * kSec));                   // a restarted simulator
  EXPECT_EQ(w.latest(), 3 * kSec);                       // the new time line from here on
  EXPECT_FALSE(w.jumpedBack(4 * kSec));
  EXPECT_FALSE(w.jumpedBack(UINT64_MAX));
  EXPECT_TRUE(w.jumpedBack(0));
  EXPECT_FALSE(w.jumpedBack(0));
  const std::string m = clockJumpMessage(1000 * kSec, 3 * kSec);
  EXPECT_NE(m.find("jumped back from 1000.000 s to 3.000 s"), std::string::npos) << m;
}

TEST(TimeRules, OutOfOrderAfterAClockJumpAndWithStampsAhead)
{
  // Normal: older than the one in force is dropped, newer or equal is taken.
  EXPECT_TRUE(isOutOfOrder(5 * kSec, 10 * kSec, 20 * kSec));
  EXPECT_FALSE(isOutOfOrder(10 * kSec, 10 * kSec, 20 * kSec));
  // A message stamped ahead of now is newer: taken (a latched map stamped before a jump back is still
  // the map), and it does not lock out the next one, which the clock being behind the stamp in force
  // lets through.
  EXPECT_FALSE(isOutOfOrder(100 * kSec, 10 * kSec, 20 * kSec));
  EXPECT_FALSE(isOutOfOrder(21 * kSec, 100 * kSec, 21 * kSec));
  EXPECT_FALSE(isOutOfOrder(1, UINT64_MAX, 21 * kSec));
  // Clock jumped back below the stamp in force: anything is taken; the first one taken re-anchors the
  // check on the new time line.
  EXPECT_FALSE(isOutOfOrder(2 * kSec, 1000 * kSec, 3 * kSec));
  EXPECT_TRUE(isOutOfOrder(1 * kSec, 2 * kSec, 3 * kSec));
  // Zero stamps carry no time.
  EXPECT_FALSE(isOutOfOrder(0, 10 * kSec, 20 * kSec));
  EXPECT_FALSE(isOutOfOrder(5 * kSec, 0, 20 * kSec));
}

// The start-up grace before "waiting for ..." warnings: 2 s from the first time noted, and again from a
// clock that jumped back (rosbag play --loop restarts the time a map may take to come).
TEST(TimeRules, StartupGraceIsTwoSecondsAndRestartsAfterAJumpBack)
{
  StartupGrace g;
  EXPECT_FALSE(g.over(100'000'000'000));
  EXPECT_FALSE(g.over(101'999'999'999));
  EXPECT_TRUE(g.over(102'000'000'000));
  EXPECT_TRUE(g.over(500'000'000'000));
  EXPECT_FALSE(g.over(3'000'000'000));  // back in time: a new grace from here
  EXPECT_FALSE(g.over(4'999'999'999));
  EXPECT_TRUE(g.over(5'000'000'000));
  StartupGrace at_zero;  // a simulated clock that starts at 0
  EXPECT_FALSE(at_zero.over(0));
  EXPECT_TRUE(at_zero.over(2'000'000'000));
}
