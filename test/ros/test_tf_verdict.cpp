// The tf gate's rule on a hand-filled tf2::BufferCore: no master, no listener, no waiting.
#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>

#include "costmap_layers/ros/tf_listener.hpp"
#include "costmap_layers/ros/tf_verdict.hpp"

using costmap_layers_ros::TfVerdict;
using costmap_layers_ros::tfVerdict;

namespace
{
geometry_msgs::TransformStamped tf(const std::string& parent, const std::string& child, double t, double x)
{
  geometry_msgs::TransformStamped m;
  m.header.frame_id = parent;
  m.header.stamp = ros::Time(t);
  m.child_frame_id = child;
  m.transform.translation.x = x;
  m.transform.rotation.w = 1.0;
  return m;
}

struct Rig
{
  tf2::BufferCore buffer{ros::Duration(10.0)};  // keeps 10 s of transforms
  Rig()
  {
    // map -> base_link from t = 100 s to t = 120 s, every second; base_link -> laser is static.
    for (int t = 100; t <= 120; ++t)
      buffer.setTransform(tf("map", "base_link", t, 0.1 * t), "test");
    buffer.setTransform(tf("base_link", "laser", 0.0, 0.2), "test", true);
  }
  TfVerdict at(const std::string& frame, double stamp, double now = 120.0)
  {
    return tfVerdict(buffer, "map", frame, ros::Time(stamp), ros::Time(now), 1.0);
  }
};
}  // namespace

TEST(TfVerdict, ReadyWhereTfHasTheTransform)
{
  Rig r;
  EXPECT_EQ(r.at("base_link", 115.5), TfVerdict::Ready);
  EXPECT_EQ(r.at("laser", 119.0), TfVerdict::Ready);  // through the static transform
  EXPECT_EQ(r.at("map", 119.0), TfVerdict::Ready);
}

TEST(TfVerdict, WaitForATransformThatMayStillArrive)
{
  Rig r;
  EXPECT_EQ(r.at("base_link", 120.5, 120.6), TfVerdict::Wait);  // newer than the newest transform
  EXPECT_EQ(r.at("unknown_frame", 119.0), TfVerdict::Wait);     // not connected yet
}

TEST(TfVerdict, TooOldForEveryTransformTfKeeps)
{
  Rig r;
  // The buffer keeps the last 10 s before its newest transform (120 s): 105 s and earlier are gone.
  EXPECT_EQ(r.at("base_link", 100.0), TfVerdict::TooOld);
  EXPECT_EQ(r.at("laser", 50.0), TfVerdict::TooOld);
}

// canTransform() between a frame and itself is true at any stamp, so without the clock check a
// reading from the future would pass (and look fresh in the buffers until the clock caught up).
TEST(TfVerdict, StampsAheadOfTheClockAreRefused)
{
  Rig r;
  EXPECT_EQ(r.at("map", 121.5, 120.0), TfVerdict::Future);
  EXPECT_EQ(r.at("map", 3600.0 + 120.0, 120.0), TfVerdict::Future);
  EXPECT_EQ(r.at("base_link", 130.0, 120.0), TfVerdict::Future);
  // Within the allowance it is tf's call: map to itself is ready, base_link waits for tf.
  EXPECT_EQ(r.at("map", 120.9, 120.0), TfVerdict::Ready);
  EXPECT_EQ(r.at("base_link", 120.9, 120.0), TfVerdict::Wait);
  // After the clock jumped back (a restarted simulation), readings of the old timeline are future.
  EXPECT_EQ(r.at("map", 119.0, 5.0), TfVerdict::Future);
}

TEST(TfVerdict, AnEmptyFrameIsNamed)
{
  Rig r;
  EXPECT_EQ(r.at("", 119.0), TfVerdict::NoFrame);
}

// Header stamps are any uint32 seconds a sender likes; ROS's Time - Time throws once the difference
// leaves 32-bit seconds (about 68 years). The rule answers at both ends of ROS time instead.
TEST(TfVerdict, StampsAtTheEndsOfRosTimeAreAnsweredNotThrown)
{
  Rig r;
  const double last = 4294967295.0;  // secs = 0xFFFFFFFF
  EXPECT_EQ(r.at("map", last, 120.0), TfVerdict::Future);
  EXPECT_EQ(tfVerdict(r.buffer, "map", "base_link", ros::Time(0xFFFFFFFFu, 999999999u), ros::Time(120.0), 1.0),
            TfVerdict::Future);
  EXPECT_EQ(r.at("laser", 1e-9, 120.0), TfVerdict::TooOld);  // (a zero stamp is tf's "the newest")
  EXPECT_NEAR(costmap_layers_ros::secondsBetween(ros::Time(last), ros::Time(0.0)), last, 1e-6);
  EXPECT_NEAR(costmap_layers_ros::secondsBetween(ros::Time(0.0), ros::Time(last)), -last, 1e-6);
  EXPECT_NEAR(costmap_layers_ros::secondsBetween(ros::Time(100, 5), ros::Time(99, 999999999)), 6e-9, 1e-15);
}

// A clock past 2^31 s (a simulation's, or after 2038) with transforms there: a reading stamped near
// 0 is older than anything tf keeps, whatever tf's own arithmetic does with the gap.
TEST(TfVerdict, AReadingDecadesOlderThanTheClockIsTooOld)
{
  tf2::BufferCore buffer{ros::Duration(10.0)};
  const double t0 = 4200000000.0;
  for (int k = 0; k <= 5; ++k)
    buffer.setTransform(tf("map", "base_link", t0 + k, 0.1 * k), "test");
  EXPECT_EQ(tfVerdict(buffer, "map", "base_link", ros::Time(1.0), ros::Time(t0 + 5.0), 1.0), TfVerdict::TooOld);
  EXPECT_EQ(tfVerdict(buffer, "map", "base_link", ros::Time(t0 + 4.5), ros::Time(t0 + 5.0), 1.0), TfVerdict::Ready);
}

// One /tf stamped years ahead (2100) would freeze its frame: tf2 then refuses every real-time transform
// of it as older than its newest minus the cache length. Refused when more than the cache length ahead
// of now; a static transform, or no clock yet (now 0), is not judged by now.
TEST(TfStampProblem, StampsMoreThanTheCacheLengthAheadOfNowAreRefused)
{
  const ros::Duration cache(10.0);
  const ros::Time now(1796220000, 0);
  const ros::Time year_2100(4102444800u, 0);
  const std::string p = costmap_layers_ros::tfStampProblem(year_2100, cache, now);
  EXPECT_NE(p.find("header.stamp 4102444800.000000000"), std::string::npos) << p;
  EXPECT_NE(p.find("ahead of now (1796220000.000000000 s)"), std::string::npos) << p;
  EXPECT_EQ(costmap_layers_ros::tfStampProblem(ros::Time(1796220010, 0), cache, now), "");  // exactly the cache length
  EXPECT_NE(costmap_layers_ros::tfStampProblem(ros::Time(1796220010, 1), cache, now), "");  // one nanosecond more
  EXPECT_EQ(costmap_layers_ros::tfStampProblem(ros::Time(5, 0), cache, now), "");           // old: tf2 judges it
  EXPECT_EQ(costmap_layers_ros::tfStampProblem(year_2100, cache, now, true), "");           // static
  EXPECT_EQ(costmap_layers_ros::tfStampProblem(year_2100, cache, ros::Time()), "");         // no clock yet
  // now at the end of ROS time: no overflow in now + cache length.
  EXPECT_EQ(
      costmap_layers_ros::tfStampProblem(ros::Time(0xFFFFFFFFu - 11u, 0u), cache, ros::Time(0xFFFFFFFFu, 999999999u)),
      "");

  // On a buffer: the frame that took the 2100 transform refuses the real one that follows, which is
  // what the listener now prevents.
  tf2::BufferCore buffer{cache};
  buffer.setTransform(tf("map", "base_link", year_2100.toSec(), 0.0), "test");
  EXPECT_FALSE(buffer.setTransform(tf("map", "base_link", now.toSec(), 1.0), "test"));
}

// The node's tf listener takes a transform only when tf2 can add its cache length to the stamp.
TEST(TfStampProblem, TheLastCacheLengthOfRosTimeIsRefused)
{
  const ros::Duration cache(10.0);
  EXPECT_EQ(costmap_layers_ros::tfStampProblem(ros::Time(0, 0), cache), "");
  EXPECT_EQ(costmap_layers_ros::tfStampProblem(ros::Time(1796220000, 5), cache), "");
  EXPECT_EQ(costmap_layers_ros::tfStampProblem(ros::Time(0xFFFFFFFFu - 10u, 999999999u), cache), "");  // the last
  const std::string after = costmap_layers_ros::tfStampProblem(ros::Time(0xFFFFFFFFu - 9u, 0u), cache);
  EXPECT_NE(after.find("header.stamp 4294967286.000000000"), std::string::npos) << after;
  EXPECT_NE(costmap_layers_ros::tfStampProblem(ros::Time(0xFFFFFFFFu, 999999999u), cache), "");
  // The sum tf2 computes for the last accepted stamp stays in range; one more nanosecond would not.
  EXPECT_NO_THROW(ros::Time(0xFFFFFFFFu - 10u, 999999999u) + cache);
  EXPECT_THROW(ros::Time(0xFFFFFFFFu - 9u, 0u) + cache, std::runtime_error);
}

// The gate's "ahead of now" rule is the layers' (0.5 s): a reading 0.6 s ahead is refused at the gate,
// where it used to pass (1 s) and be refused again by the layer under another key.
TEST(TfVerdict, TheGateRefusesWhatTheLayersWouldRefuseAsAheadOfNow)
{
  Rig r;
  auto gate = [&r](double stamp)
  {
    return costmap_layers_ros::gateVerdict(r.buffer, "map", "laser", "", ros::Time(stamp), ros::Time(119.0),
                                           costmap_layers_ros::kGateMaxAhead);
  };
  EXPECT_EQ(gate(119.4), TfVerdict::Ready);
  EXPECT_EQ(gate(119.5), TfVerdict::Ready);  // exactly the tolerance
  EXPECT_EQ(gate(119.6), TfVerdict::Future);
  EXPECT_EQ(gate(119.9), TfVerdict::Future);
}

// A source with sensor_frame: the gate lets a reading through only when tf can place the sensor frame
// at the stamp too, so that its delivery never waits for tf under the gate's lock.
TEST(TfVerdict, TheGateWaitsForTheSensorFrameToo)
{
  Rig r;
  // map -> mast from t = 111 s to 115 s only: it lags base_link's transforms (kept from 110 s to 120 s).
  for (int t = 111; t <= 115; ++t)
    r.buffer.setTransform(tf("map", "mast", t, 0.0), "test");
  auto gate = [&r](const std::string& sensor_frame, double stamp)
  {
    return costmap_layers_ros::gateVerdict(r.buffer, "map", "base_link", sensor_frame, ros::Time(stamp),
                                           ros::Time(120.0), 1.0);
  };
  EXPECT_EQ(gate("mast", 112.5), TfVerdict::Ready);
  EXPECT_EQ(gate("mast", 117.0), TfVerdict::Wait);  // base_link could, the mast cannot yet
  EXPECT_EQ(gate("", 117.0), TfVerdict::Ready);
  EXPECT_EQ(gate("base_link", 117.0), TfVerdict::Ready);
  EXPECT_EQ(gate("laser", 117.0), TfVerdict::Ready);
  EXPECT_EQ(gate("mast", 121.5), TfVerdict::Future);
  EXPECT_EQ(gate("", 100.0), TfVerdict::TooOld);
}
