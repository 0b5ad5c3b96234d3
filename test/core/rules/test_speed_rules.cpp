// The speed rules as pure functions (rules/speed_rules.hpp), at the edges of their accepted values.
#include <gtest/gtest.h>

#include <cmath>

#include "costmap_layers/core/rules/speed_rules.hpp"

using namespace costmap_layers;

namespace
{
SpeedRule percentRule(double default_max_speed)
{
  SpeedRule r;
  r.nav2 = true;
  r.percent = true;
  r.default_max_speed = default_max_speed;
  return r;
}
}  // namespace

// A percentage of the largest accepted default_max_speed: finite, and never above it.
TEST(SpeedRules, PercentOfAHugeDefaultStaysFinite)
{
  const double huge = 1e307;
  const SpeedPublication half = speedFromNav2Limit(percentRule(huge), 50.0);
  ASSERT_TRUE(half.max_speed.has_value());
  ASSERT_TRUE(std::isfinite(*half.max_speed));
  EXPECT_DOUBLE_EQ(*half.max_speed, 5e306);
  const SpeedPublication all = speedFromNav2Limit(percentRule(huge), 100.0);
  EXPECT_EQ(all.max_speed.value_or(0.0), huge);  // 100 / 100 = 1 exactly
  const SpeedPublication max = speedFromNav2Limit(percentRule(1.7976931348623157e308), 100.0);
  EXPECT_EQ(max.max_speed.value_or(0.0), 1.7976931348623157e308);
}

TEST(SpeedRules, PercentOfAnOrdinaryDefault)
{
  EXPECT_DOUBLE_EQ(speedFromNav2Limit(percentRule(0.8), 25.0).max_speed.value_or(0.0), 0.2);
  EXPECT_DOUBLE_EQ(speedFromNav2Limit(percentRule(0.8), 0.0).max_speed.value_or(0.0), 0.8);  // 0 = no limit
}

// Through the mask value: base + multiplier * v in percent of a huge default.
TEST(SpeedRules, MaskValueInPercentOfAHugeDefaultStaysFinite)
{
  SpeedRule r = percentRule(1e307);
  r.base = 0.0;
  r.multiplier = 1.0;
  const SpeedVerdict v = speedLimitForValue(40, r, nullptr);
  EXPECT_EQ(v.warning, SpeedWarning::None);
  ASSERT_TRUE(v.publication.max_speed.has_value());
  ASSERT_TRUE(std::isfinite(*v.publication.max_speed));
  EXPECT_DOUBLE_EQ(*v.publication.max_speed, 4e306);
}
