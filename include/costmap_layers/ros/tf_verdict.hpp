// The rule of the sensor inputs' tf gate, apart from its subscriptions and timers so that it can be
// unit-tested on a hand-filled tf2::BufferCore: can tf place a reading now, later, or never?
#pragma once

#include <ros/time.h>
#include <tf2/buffer_core.h>

#include <string>

#include "costmap_layers/core/rules/stamp_order.hpp"

namespace costmap_layers_ros
{
/// [s] How far ahead of now the tf gate lets a sensor reading's stamp lie: the layers' own rule
/// (kFutureStampToleranceNs), so that what passes the gate is not refused again by the layer under
/// another key.
constexpr double kGateMaxAhead = static_cast<double>(costmap_layers::kFutureStampToleranceNs) * 1e-9;

enum class TfVerdict
{
  Ready,      ///< tf can transform the reading's frame at its stamp
  Wait,       ///< not yet: the transform may still arrive
  TooOld,     ///< older than every transform tf keeps: it never will
  Future,     ///< stamped more than max_ahead after now: a wrong clock, or the clock jumped back
  NoFrame,    ///< header.frame_id is empty
  PushedOut,  ///< waited until the gate's queue was full of newer readings
  BadStamp    ///< tf could not work at the stamp (beyond what ROS time arithmetic holds)
};

/// a - b in seconds, for any two stamps. ROS's own Time - Time throws when the difference leaves 32-bit
/// seconds (about 68 years), and any stamp a sender puts in a header can be that far from now.
inline double secondsBetween(const ros::Time& a, const ros::Time& b)
{
  return static_cast<double>(static_cast<int64_t>(a.toNSec() - b.toNSec())) * 1e-9;
}

/// Whether tf can transform `frame` into `target` at `stamp`, given the time `now`.
/// @param max_ahead  [s] how far a stamp may lie ahead of now: tf's canTransform() is true at any
///                   stamp between a frame and itself, so a reading from the future would pass.
/// Uses only tf2's public, locked calls (canTransform, lookupTransform, getCacheLength; the last is not
/// const in tf2, hence the non-const buffer).
TfVerdict tfVerdict(tf2::BufferCore& tf, const std::string& target, const std::string& frame, const ros::Time& stamp,
                    const ros::Time& now, double max_ahead);

/// The gate's verdict on a reading in `frame` whose origin is `sensor_frame` (empty: the frame
/// itself): Ready only when tf can place both at the stamp, so that delivering it never waits for tf
/// (a look-up that waited would hold the gate, and a spinner thread, while more readings queue).
TfVerdict gateVerdict(tf2::BufferCore& tf, const std::string& target, const std::string& frame,
                      const std::string& sensor_frame, const ros::Time& stamp, const ros::Time& now, double max_ahead);
}  // namespace costmap_layers_ros
