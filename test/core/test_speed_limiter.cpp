// speed_limiter's core: scaling commands to a speed limit with the same curvature.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "costmap_layers/core/speed_limiter.hpp"

using costmap_layers::checkMaxSpeed;
using costmap_layers::checkTwist;
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
