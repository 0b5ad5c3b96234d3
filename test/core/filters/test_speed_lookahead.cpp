// SpeedFilter's path lookahead (Nav2's enable_path_lookahead): the braking distance, the path
// geometry, the checks of paths and odometry, and what is published as a robot drives toward a zone.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/data/path_data.hpp"
#include "costmap_layers/core/filters/speed_filter.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;
using costmap_layers_test::GridKind;

namespace
{
/// 20 m x 3 m at 1 m: area 1 for x >= 10, no area before.
OccupancyGridData zoneMask()
{
  OccupancyGridData m;
  m.frame_id = "map";
  m.width = 20;
  m.height = 3;
  m.resolution = 1.0;
  m.data.assign(60, 0);
  for (int j = 0; j < 3; ++j)
    for (int i = 10; i < 20; ++i)
      m.data[static_cast<std::size_t>(j) * 20 + i] = 1;
  return m;
}

/// A straight path along y = 1.5 from x = x0 to 19.5, a pose every 0.5 m.
PathData straightPath(const std::string& frame = "map", double x0 = 0.0, double shift = 0.0)
{
  PathData p;
  p.frame_id = frame;
  for (double x = x0; x <= 19.5 + 1e-9; x += 0.5)
    p.poses.push_back({x - shift, 1.5});
  return p;
}

ParamValue lookaheadParams()
{
  ParamValue p = ParamValue::makeMap();
  p.set("default_max_speed", ParamValue::makeDouble(1.0));
  p.set("enable_path_lookahead", ParamValue::makeBool(true));
  p.set("max_decel", ParamValue::makeDouble(-0.5));
  p.set("min_lookahead", ParamValue::makeDouble(0.3));
  p.set("max_lookahead", ParamValue::makeDouble(5.0));
  return p;
}

OdometryData moving(double v)
{
  OdometryData o;
  o.frame_id = "odom";
  o.child_frame_id = "base_link";
  o.linear_x = v;
  return o;
}

struct Rig
{
  LayeredCostmap lc{"map", false, false};
  std::shared_ptr<FakeContext> ctx;
  std::shared_ptr<SpeedFilter> filter = std::make_shared<SpeedFilter>();

  explicit Rig(ParamValue p = lookaheadParams()) : ctx(std::make_shared<FakeContext>(std::move(p)))
  {
    filter->initialize(&lc, "speed_filter", ctx);
    ctx->bind(*filter);
    ctx->publishGrid(GridKind::Mask, zoneMask());
    SpeedLimitsData limits;
    limits.limits.push_back({1, 0.3});
    ctx->publishSpeedLimits(limits);
  }
  /// One cycle with the robot at (x, 1.5); returns the limit in force.
  double at(double x)
  {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    filter->updateBounds(x, 1.5, 0.0, &x0, &y0, &x1, &y1);
    return filter->lastPublished().value_or(std::nan(""));
  }
};
}  // namespace

TEST(PathLookahead, BrakingDistanceByHand)
{
  EXPECT_DOUBLE_EQ(lookaheadDistance(1.0, -0.5, 0.3, 5.0), 1.0);   // 1 / (2 * 0.5)
  EXPECT_DOUBLE_EQ(lookaheadDistance(2.0, -0.5, 0.3, 5.0), 4.0);   // 4 / 1
  EXPECT_DOUBLE_EQ(lookaheadDistance(0.5, -1.0, 0.3, 5.0), 0.3);   // 0.125 -> min_lookahead
  EXPECT_DOUBLE_EQ(lookaheadDistance(3.0, -0.5, 0.3, 5.0), 5.0);   // 9 -> max_lookahead
  EXPECT_DOUBLE_EQ(lookaheadDistance(1.0, 0.0, 0.3, 5.0), 5.0);    // no deceleration: max_lookahead
  EXPECT_DOUBLE_EQ(lookaheadDistance(1.2, -2.0, 0.0, 5.0), 0.36);  // 1.44 / 4
}

TEST(PathLookahead, NearestSegmentAndWalkByHand)
{
  std::vector<PathData::Point> poses;
  for (int k = 0; k <= 10; ++k)
    poses.push_back({static_cast<double>(k), 0.0});
  EXPECT_EQ(closestSegment(poses, 3.4, 0.2, 0), 3u);
  EXPECT_EQ(closestSegment(poses, 3.4, 0.2, 5), 5u);   // only forward from the last one
  EXPECT_EQ(closestSegment(poses, 3.4, 0.2, 99), 3u);  // past the end: from 0
  EXPECT_EQ(closestSegment(poses, -7.0, 0.0, 0), 0u);
  EXPECT_EQ(closestSegment(poses, 30.0, 1.0, 0), 9u);
  EXPECT_EQ(closestSegment({{1.0, 1.0}}, 0.0, 0.0, 0), 0u);
  // From pose 3: poses 3, 4, 5 lie within 2.5 m along the path (0, 1, 2 m); within exactly 2 m too.
  EXPECT_EQ(lookaheadEnd(poses, 3, 2.5), 6u);
  EXPECT_EQ(lookaheadEnd(poses, 3, 2.0), 6u);
  EXPECT_EQ(lookaheadEnd(poses, 3, 0.0), 4u);  // pose 3 itself always
  EXPECT_EQ(lookaheadEnd(poses, 3, 100.0), 11u);
  EXPECT_EQ(lookaheadEnd(poses, 11, 1.0), 11u);
  // A path that doubles back: distance is measured along it, not straight.
  const std::vector<PathData::Point> hairpin{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_EQ(lookaheadEnd(hairpin, 0, 2.0), 3u);
  // A path of zero length (every pose at one point): every pose is 0 m along, the first segment nearest.
  const std::vector<PathData::Point> point(5, PathData::Point{2.0, 3.0});
  EXPECT_EQ(closestSegment(point, 9.0, 9.0, 0), 0u);
  EXPECT_EQ(lookaheadEnd(point, 0, 0.0), 5u);
}

TEST(PathLookahead, BadPathsAndOdometryNameTheField)
{
  PathData p = straightPath();
  EXPECT_TRUE(validatePath(p).ok());
  EXPECT_TRUE(validatePath(PathData{}).ok());  // empty: "no plan"
  PathData nan_path = p;
  nan_path.poses[7].y = std::nan("");
  EXPECT_EQ(validatePath(nan_path).field, "poses[i].pose.position");
  EXPECT_NE(validatePath(nan_path).message.find("poses[7]"), std::string::npos);
  PathData inf_path = p;
  inf_path.poses[0].x = INFINITY;
  EXPECT_EQ(validatePath(inf_path).field, "poses[i].pose.position");
  PathData far_path = p;
  far_path.poses[3].x = 2e7;
  EXPECT_EQ(validatePath(far_path).field, "poses[i].pose.position");
  PathData no_frame = p;
  no_frame.frame_id.clear();
  EXPECT_EQ(validatePath(no_frame).field, "header.frame_id");
  PathData huge;
  huge.frame_id = "map";
  huge.poses.resize(limits::kMaxPathPoses + 1);
  EXPECT_EQ(validatePath(huge).field, "poses");
  huge.poses.resize(limits::kMaxPathPoses);
  EXPECT_TRUE(validatePath(huge).ok());

  EXPECT_TRUE(validateOdometry(moving(-1.5)).ok());
  EXPECT_EQ(validateOdometry(moving(std::nan(""))).field, "twist.twist.linear");
  EXPECT_EQ(validateOdometry(moving(1e9)).field, "twist.twist.linear");
  OdometryData spin = moving(0.0);
  spin.angular_z = -INFINITY;
  EXPECT_EQ(validateOdometry(spin).field, "twist.twist.angular");
}

TEST(PathLookahead, BadParametersNameTheParameter)
{
  auto fails = [](const std::string& name, ParamValue v)
  {
    ParamValue p = lookaheadParams();
    p.set(name, std::move(v));
    try
    {
      parseSpeedFilterConfig(ParamReader(p, "speed"));
    }
    catch (const std::invalid_argument& e)
    {
      return std::string(e.what()).find("'" + name + "'") != std::string::npos;
    }
    return false;
  };
  EXPECT_TRUE(fails("max_decel", ParamValue::makeDouble(0.5)));  // Nav2's sign: negative
  EXPECT_TRUE(fails("max_decel", ParamValue::makeDouble(std::nan(""))));
  EXPECT_TRUE(fails("max_decel", ParamValue::makeDouble(-INFINITY)));
  EXPECT_TRUE(fails("min_lookahead", ParamValue::makeDouble(-0.1)));
  EXPECT_TRUE(fails("max_lookahead", ParamValue::makeDouble(0.2)));  // below min_lookahead 0.3
  EXPECT_TRUE(fails("max_lookahead", ParamValue::makeDouble(INFINITY)));
  EXPECT_TRUE(fails("path_topic", ParamValue::makeString("")));
  EXPECT_TRUE(fails("odom_timeout", ParamValue::makeDouble(0.0)));
  const ParamValue empty = ParamValue::makeMap();
  const SpeedFilterConfig d = parseSpeedFilterConfig(ParamReader(empty, "speed"));
  EXPECT_FALSE(d.enable_path_lookahead);
  EXPECT_EQ(d.max_decel, -0.5);
  EXPECT_EQ(d.min_lookahead, 0.3);
  EXPECT_EQ(d.max_lookahead, 5.0);
  EXPECT_EQ(d.path_topic, "plan");
  EXPECT_EQ(d.odom_topic, "odom");
}

TEST(PathLookahead, TheLimitDropsBeforeTheZoneByTheBrakingDistance)
{
  Rig rig;
  rig.ctx->publishPath(straightPath());
  rig.ctx->publishOdometry(moving(2.0));  // braking distance 4 m
  // Robot at 5.0: nearest segment starts at 4.5 (the first of two at distance 0); poses to 8.5.
  EXPECT_EQ(rig.at(5.0), 1.0);
  EXPECT_DOUBLE_EQ(rig.filter->lastLookahead(), 4.0);
  // At 6.6: the segment from 6.5; poses to 10.5 reach the zone (x >= 10), 3.4 m ahead.
  EXPECT_EQ(rig.at(6.6), 0.3);
  EXPECT_EQ(rig.at(12.0), 0.3);  // inside
  // Without lookahead the limit would drop only inside.
  ParamValue plain = lookaheadParams();
  plain.set("enable_path_lookahead", ParamValue::makeBool(false));
  Rig without(plain);
  EXPECT_EQ(without.at(6.6), 1.0);
  EXPECT_EQ(without.at(9.9), 1.0);
  EXPECT_EQ(without.at(10.1), 0.3);
}

TEST(PathLookahead, SlowingDownDoesNotLiftTheLimitAhead)
{
  Rig rig;
  rig.ctx->publishPath(straightPath());
  rig.ctx->publishOdometry(moving(2.0));
  ASSERT_EQ(rig.at(6.6), 0.3);
  // Slower: 0.5 m/s brakes in 0.25 m (min_lookahead 0.3), but the 4 m that found the zone are held.
  rig.ctx->now_ns += 400'000'000;  // the 2 m/s sample leaves the 0.3 s average
  rig.ctx->publishOdometry(moving(0.5));
  EXPECT_EQ(rig.at(6.7), 0.3);
  EXPECT_DOUBLE_EQ(rig.filter->lastLookahead(), 4.0);
  // A fresh filter at 0.5 m/s at the same place does not see the zone.
  Rig slow;
  slow.ctx->publishPath(straightPath());
  slow.ctx->publishOdometry(moving(0.5));
  EXPECT_EQ(slow.at(6.7), 1.0);
  EXPECT_DOUBLE_EQ(slow.filter->lastLookahead(), 0.3);
}

TEST(PathLookahead, OdometryMissingOrStaleLooksTheWholeMaxLookahead)
{
  Rig rig;
  rig.ctx->publishPath(straightPath());
  // No odometry: 5 m. At 5.2 the walk starts at pose 5.0 and reaches 10.0 exactly.
  EXPECT_EQ(rig.at(5.2), 0.3);
  EXPECT_DOUBLE_EQ(rig.filter->lastLookahead(), 5.0);
  EXPECT_GE(rig.ctx->countKey("odom/missing"), 1);

  Rig stale;
  stale.ctx->publishPath(straightPath());
  stale.ctx->publishOdometry(moving(0.0));
  EXPECT_EQ(stale.at(5.2), 1.0);     // standing: 0.3 m
  stale.ctx->now_ns += 600'000'000;  // 0.6 s later, odom_timeout 0.5 s
  EXPECT_EQ(stale.at(5.2), 0.3);
  EXPECT_GE(stale.ctx->countKey("odom/stale"), 1);
}

// The clock jumps back (a bag played in a loop): odometry received on the old timeline is dropped,
// not averaged with the new (standing before, 2 m/s after would read 1 m/s: a 1 m look-ahead instead of
// 4 m, the zone at x = 10 seen too late from 6.6), and not taken as fresh when none follows.
TEST(PathLookahead, OdometryFromBeforeAClockJumpBackIsDropped)
{
  Rig rig;
  rig.ctx->publishPath(straightPath());
  rig.ctx->now_ns = 100'000'000'000;
  for (int k = 0; k < 5; ++k, rig.ctx->now_ns += 50'000'000)
    rig.ctx->publishOdometry(moving(0.0));
  EXPECT_EQ(rig.at(6.6), 1.0);      // standing: 0.3 m ahead
  rig.ctx->now_ns = 1'000'000'000;  // back to 1 s
  for (int k = 0; k < 5; ++k, rig.ctx->now_ns += 50'000'000)
    rig.ctx->publishOdometry(moving(2.0));
  EXPECT_EQ(rig.at(6.6), 0.3);  // 2 m/s: 4 m ahead reaches the zone
  EXPECT_DOUBLE_EQ(rig.filter->lastLookahead(), 4.0);
  EXPECT_EQ(rig.ctx->countKey("odom/clock"), 1);

  Rig quiet;
  quiet.ctx->publishPath(straightPath());
  quiet.ctx->now_ns = 100'000'000'000;
  quiet.ctx->publishOdometry(moving(0.0));
  EXPECT_EQ(quiet.at(6.6), 1.0);
  quiet.ctx->now_ns = 1'000'000'000;  // back to 1 s, no odometry since
  EXPECT_EQ(quiet.at(6.6), 0.3);      // missing: max_lookahead (5 m)
  EXPECT_DOUBLE_EQ(quiet.filter->lastLookahead(), 5.0);
  EXPECT_EQ(quiet.ctx->countKey("odom/clock"), 1);
  EXPECT_GE(quiet.ctx->countKey("odom/missing"), 1);
  // A step back within the tolerance (threads reading the clock a moment apart) drops nothing.
  Rig jitter;
  jitter.ctx->publishPath(straightPath());
  jitter.ctx->now_ns = 100'000'000'000;
  jitter.ctx->publishOdometry(moving(2.0));
  jitter.ctx->now_ns -= 400'000'000;
  EXPECT_EQ(jitter.at(6.6), 0.3);
  EXPECT_DOUBLE_EQ(jitter.filter->lastLookahead(), 4.0);
  EXPECT_EQ(jitter.ctx->countKey("odom/clock"), 0);
}

TEST(PathLookahead, PathInAnotherFrameBadPathsAndNoPlan)
{
  Rig rig;
  // The path in "odom", which lies 2 m along x from "map": odom x = map x - 2.
  Transform2D odom_to_map;
  odom_to_map.x = 2.0;
  rig.ctx->transforms[{"map", "odom"}] = odom_to_map;
  rig.ctx->publishPath(straightPath("odom", 0.0, 2.0));
  rig.ctx->publishOdometry(moving(2.0));
  EXPECT_EQ(rig.at(5.0), 1.0);
  EXPECT_EQ(rig.at(6.6), 0.3);

  // A path with a NaN is refused, the previous one stays.
  PathData bad = straightPath();
  bad.poses[3].x = std::nan("");
  EXPECT_FALSE(rig.filter->setPath(std::make_shared<const PathData>(bad)).empty());
  EXPECT_EQ(rig.ctx->countKey("path/poses[i].pose.position"), 1);
  EXPECT_EQ(rig.at(6.6), 0.3);

  // Odometry with a NaN is refused, the previous speed stays.
  EXPECT_FALSE(rig.filter->setOdometry(moving(std::nan(""))).empty());
  EXPECT_EQ(rig.ctx->countKey("odom/twist.twist.linear"), 1);

  // Without the transform: the robot's own cell only, reported.
  rig.ctx->transforms.clear();
  EXPECT_EQ(rig.at(6.6), 1.0);
  EXPECT_GE(rig.ctx->countKey("path/transform"), 1);

  // An empty path: no plan, the robot's own cell only.
  PathData none;
  none.frame_id = "map";
  rig.ctx->publishPath(none);
  EXPECT_EQ(rig.at(6.6), 1.0);
  EXPECT_EQ(rig.at(10.5), 0.3);
}
