// speed_limiter's core: scaling commands to a speed limit with the same curvature, and the watchdog
// that decides when the command input went stale (also across clock jumps).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "costmap_layers/core/filters/speed_limiter.hpp"

using costmap_layers::checkMaxSpeed;
using costmap_layers::checkTwist;
using costmap_layers::CommandWatchdog;
using costmap_layers::limitTwist;
using costmap_layers::Twist;

TEST(SpeedLimiter, ScalesToTheLimitKeepingCurvature)
{
  const Twist in{1.0, 0.0, 0.0, 0.0, 0.0, 0.5};
  const Twist out = limitTwist(in, 0.3);
  EXPECT_DOUBLE_EQ(out.lx, 0.3);
  EXPECT_DOUBLE_EQ(out.az, 0.15);
  EXPECT_DOUBLE_EQ(out.az / out.lx, in.az / in.lx);  // the same arc
}

TEST(SpeedLimiter, HolonomicSpeedIsThePlanarNorm)
{
  const Twist out = limitTwist(Twist{0.6, 0.8, 0.0, 0.0, 0.0, -1.0}, 0.5);  // 1.0 m/s diagonally
  EXPECT_NEAR(std::hypot(out.lx, out.ly), 0.5, 1e-12);
  EXPECT_NEAR(out.lx, 0.3, 1e-12);
  EXPECT_NEAR(out.ly, 0.4, 1e-12);
  EXPECT_NEAR(out.az, -0.5, 1e-12);
}

TEST(SpeedLimiter, WithinTheLimitOrNoLimitPassesUntouched)
{
  const Twist in{0.2, 0.0, 0.0, 0.0, 0.0, 0.7};
  for (double limit : {0.3, 0.2, 0.0})
  {
    const Twist out = limitTwist(in, limit);
    EXPECT_EQ(out.lx, in.lx) << limit;
    EXPECT_EQ(out.az, in.az) << limit;
  }
  const Twist spin = limitTwist(Twist{0, 0, 0, 0, 0, 2.0}, 0.1);  // turning in place has no linear speed
  EXPECT_EQ(spin.az, 2.0);
  const Twist back = limitTwist(Twist{-1.0, 0, 0, 0, 0, 0.4}, 0.25);  // reversing is limited too
  EXPECT_DOUBLE_EQ(back.lx, -0.25);
  EXPECT_DOUBLE_EQ(back.az, 0.1);
}

TEST(SpeedLimiter, BadValuesAreNamed)
{
  EXPECT_FALSE(checkTwist(Twist{1.0, 0, 0, 0, 0, 0.5}));
  const auto bad = checkTwist(Twist{1.0, 0, 0, 0, 0, std::numeric_limits<double>::quiet_NaN()});
  ASSERT_TRUE(bad);
  EXPECT_NE(bad->find("angular.z"), std::string::npos);
  EXPECT_FALSE(checkMaxSpeed(0.0));
  EXPECT_FALSE(checkMaxSpeed(0.3));
  EXPECT_TRUE(checkMaxSpeed(-0.1));
  EXPECT_TRUE(checkMaxSpeed(std::numeric_limits<double>::infinity()));
  EXPECT_NE(checkMaxSpeed(std::nan(""))->find("max_speed"), std::string::npos);
}

namespace
{
constexpr uint64_t kSec = 1'000'000'000ull;
}  // namespace

TEST(CommandWatchdog, GoesStaleOnceAfterTheTimeout)
{
  CommandWatchdog w(0.5);
  EXPECT_TRUE(w.stale());  // nothing received yet
  EXPECT_EQ(w.check(10 * kSec), CommandWatchdog::Event::None);
  w.commandReceived(10 * kSec);
  EXPECT_FALSE(w.stale());
  EXPECT_EQ(w.check(10 * kSec + 500'000'000), CommandWatchdog::Event::None);
  EXPECT_EQ(w.check(10 * kSec + 500'000'001), CommandWatchdog::Event::WentStale);
  EXPECT_TRUE(w.stale());
  EXPECT_EQ(w.check(11 * kSec), CommandWatchdog::Event::None);  // once
  w.commandReceived(12 * kSec);
  EXPECT_EQ(w.check(10'000 * kSec), CommandWatchdog::Event::WentStale);  // a jump forward: stale
}

TEST(CommandWatchdog, ClockJumpBackDoesNotKeepTheInputFreshForever)
{
  // Commands stop at 1000 s and the clock restarts at 3 s: now - last_command is negative until the
  // clock is back at 1000 s, so the old rule kept the last command fresh for 997 s.
  CommandWatchdog w(0.5);
  w.commandReceived(1000 * kSec);
  EXPECT_EQ(w.check(3 * kSec), CommandWatchdog::Event::ClockJumpedBack);
  EXPECT_FALSE(w.stale());  // the timeout restarts at the jump
  EXPECT_EQ(w.check(3 * kSec + 400'000'000), CommandWatchdog::Event::None);
  EXPECT_EQ(w.check(3 * kSec + 600'000'000), CommandWatchdog::Event::WentStale);
  // Commands that go on across the jump keep the input fresh.
  w.commandReceived(2000 * kSec);
  w.commandReceived(5 * kSec);
  EXPECT_EQ(w.check(5 * kSec + 100'000'000), CommandWatchdog::Event::None);
  EXPECT_FALSE(w.stale());
  // 0.3 s back is jitter, not a jump.
  EXPECT_EQ(w.check(5 * kSec - 300'000'000), CommandWatchdog::Event::None);
  EXPECT_EQ(w.check(5 * kSec + 600'000'000), CommandWatchdog::Event::WentStale);
}

TEST(CommandWatchdog, ExtremeTimes)
{
  CommandWatchdog w(0.5);
  w.commandReceived(UINT64_MAX);
  EXPECT_EQ(w.check(UINT64_MAX), CommandWatchdog::Event::None);
  EXPECT_EQ(w.check(0), CommandWatchdog::Event::ClockJumpedBack);
  EXPECT_EQ(w.check(kSec), CommandWatchdog::Event::WentStale);
  w.commandReceived(0);
  EXPECT_EQ(w.check(0), CommandWatchdog::Event::None);
  EXPECT_EQ(w.check(UINT64_MAX), CommandWatchdog::Event::WentStale);
}

// Simulated time with no /clock (ROS time 0) or a paused /clock: the clock cannot time the input, so
// the steady clock does, and only while the clock has not moved since the command.
TEST(CommandWatchdog, AClockThatDoesNotMoveIsTimedOnTheSteadyClock)
{
  CommandWatchdog w(0.5);
  w.commandReceived(0, 100 * kSec);  // no /clock: ROS time 0
  EXPECT_EQ(w.check(0, 100 * kSec + 500'000'000), CommandWatchdog::Event::None);
  EXPECT_EQ(w.check(0, 100 * kSec + 500'000'001), CommandWatchdog::Event::WentStaleNoClock);
  EXPECT_EQ(w.check(0, 200 * kSec), CommandWatchdog::Event::None);  // once
  EXPECT_TRUE(w.stale());

  // A paused simulation at 42 s: the same.
  w.commandReceived(42 * kSec, 300 * kSec);
  EXPECT_EQ(w.check(42 * kSec, 300 * kSec + 400'000'000), CommandWatchdog::Event::None);
  EXPECT_EQ(w.check(42 * kSec, 300 * kSec + 600'000'000), CommandWatchdog::Event::WentStaleNoClock);

  // A simulation at a tenth of real time moves: 2 s of steady time are 0.2 s of its own, not stale.
  w.commandReceived(50 * kSec, 400 * kSec);
  EXPECT_EQ(w.check(50 * kSec + 200'000'000, 402 * kSec), CommandWatchdog::Event::None);
  EXPECT_EQ(w.check(50 * kSec + 400'000'000, 404 * kSec), CommandWatchdog::Event::None);
  EXPECT_EQ(w.check(50 * kSec + 600'000'000, 406 * kSec), CommandWatchdog::Event::WentStale);

  // Without a steady clock (0) nothing changes: ROS time 0 throughout stays fresh, as before.
  CommandWatchdog plain(0.5);
  plain.commandReceived(0);
  EXPECT_EQ(plain.check(0), CommandWatchdog::Event::None);
}
