// A planned path and the robot's odometry as the core sees them (nav_msgs/Path, nav_msgs/Odometry
// without ROS), their checks, and the geometry of Nav2's speed-filter path lookahead: how far ahead to
// look at a speed and which path poses lie within that distance.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/core/rules/limits.hpp"

namespace costmap_layers
{
/// nav_msgs/Path: the positions of its poses [m] in frame_id (orientations are not used).
struct PathData
{
  std::string frame_id;
  uint64_t stamp_ns = 0;
  struct Point
  {
    double x = 0.0, y = 0.0;
  };
  std::vector<Point> poses;
  /// How many poses the message held, when more than poses keeps: a host copies at most
  /// limits::kMaxPathPoses + 1 of them, enough for validatePath() to refuse the path by its true size.
  std::size_t message_poses = 0;
};

/// nav_msgs/Odometry: the twist the robot reports, in child_frame_id (the robot's base frame).
struct OdometryData
{
  std::string frame_id;
  std::string child_frame_id;
  uint64_t stamp_ns = 0;
  double linear_x = 0.0;   ///< [m/s]
  double linear_y = 0.0;   ///< [m/s]
  double angular_z = 0.0;  ///< [rad/s]
};

/// A path is usable when frame_id is set (unless it has no poses), it has at most kMaxPathPoses poses,
/// and every position is finite with |x|, |y| <= limits::kMaxCoordinate.
/// @return ok(), or the field at fault ("header.frame_id", "poses", "poses[i].pose.position") and a line
///         naming it and its value.
InputError validatePath(const PathData& path);
/// Odometry is usable when its twist is finite and within limits::kMaxSpeed.
/// @return ok(), or the field at fault ("twist.twist.linear") and a line naming its value.
InputError validateOdometry(const OdometryData& odom);

/// Nav2's lookahead distance [m] at speed v [m/s]: with max_decel < 0 [m/s^2] the braking distance
/// v^2 / (2 |max_decel|) clamped to [min_lookahead, max_lookahead]; with max_decel >= 0 max_lookahead.
double lookaheadDistance(double v, double max_decel, double min_lookahead, double max_lookahead);

/// Index i of the path segment (poses i, i + 1) nearest to (x, y), searched from segment `start` to
/// the end (Nav2's distance_from_path: the robot only moves forward along a path); the first of equally
/// near segments wins. 0 for a path of fewer than two poses; `start` past the end searches from 0.
std::size_t closestSegment(const std::vector<PathData::Point>& poses, double x, double y, std::size_t start);

/// One past the last pose, walking from pose `first`, whose distance along the path from pose
/// `first` is at most `distance` [m] (Nav2's walk: pose first is always included).
std::size_t lookaheadEnd(const std::vector<PathData::Point>& poses, std::size_t first, double distance);
}  // namespace costmap_layers
