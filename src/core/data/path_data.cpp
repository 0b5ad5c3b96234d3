#include "costmap_layers/core/data/path_data.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "costmap_layers/core/rules/limits.hpp"

namespace costmap_layers
{
InputError validatePath(const PathData& path)
{
  const std::size_t poses = std::max(path.poses.size(), path.message_poses);
  if (poses > limits::kMaxPathPoses)
    return InputError::of("poses", "poses has " + std::to_string(poses) + " entries, more than the " +
                                       std::to_string(limits::kMaxPathPoses) + " a path may have");
  if (!path.poses.empty() && path.frame_id.empty())
    return InputError::of("header.frame_id", "header.frame_id is empty: the poses cannot be placed");
  for (std::size_t i = 0; i < path.poses.size(); ++i)
  {
    const PathData::Point& p = path.poses[i];
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::fabs(p.x) <= limits::kMaxCoordinate &&
        std::fabs(p.y) <= limits::kMaxCoordinate)
      continue;
    std::ostringstream s;
    s << "poses[" << i << "].pose.position must be finite, |x| and |y| at most " << limits::kMaxCoordinate
      << " m (got x=" << p.x << " y=" << p.y << ")";
    return InputError::of("poses[i].pose.position", s.str());
  }
  return InputError::none();
}

InputError validateOdometry(const OdometryData& odom)
{
  for (const double v : {odom.linear_x, odom.linear_y})
    if (!(std::fabs(v) <= limits::kMaxSpeed))  // NaN too
    {
      std::ostringstream s;
      s << "twist.twist.linear must be finite and at most " << limits::kMaxSpeed << " m/s (got x=" << odom.linear_x
        << " y=" << odom.linear_y << ")";
      return InputError::of("twist.twist.linear", s.str());
    }
  if (!std::isfinite(odom.angular_z))
  {
    std::ostringstream s;
    s << "twist.twist.angular.z must be finite (got " << odom.angular_z << ")";
    return InputError::of("twist.twist.angular", s.str());
  }
  return InputError::none();
}

double lookaheadDistance(double v, double max_decel, double min_lookahead, double max_lookahead)
{
  if (!(max_decel < 0.0)) return max_lookahead;
  const double braking = v * v / (2.0 * -max_decel);
  return std::clamp(braking, min_lookahead, max_lookahead);
}

namespace
{
/// Squared distance from (x, y) to the segment a-b.
double squaredDistanceToSegment(double x, double y, const PathData::Point& a, const PathData::Point& b)
{
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0.0 ? ((x - a.x) * dx + (y - a.y) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const double px = a.x + t * dx - x, py = a.y + t * dy - y;
  return px * px + py * py;
}
}  // namespace

std::size_t closestSegment(const std::vector<PathData::Point>& poses, double x, double y, std::size_t start)
{
  if (poses.size() < 2) return 0;
  if (start >= poses.size() - 1) start = 0;
  std::size_t best = start;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = start; i + 1 < poses.size(); ++i)
  {
    const double d2 = squaredDistanceToSegment(x, y, poses[i], poses[i + 1]);
    if (d2 < best_d2)
    {
      best_d2 = d2;
      best = i;
    }
  }
  return best;
}

std::size_t lookaheadEnd(const std::vector<PathData::Point>& poses, std::size_t first, double distance)
{
  if (first >= poses.size()) return poses.size();
  double along = 0.0;
  std::size_t i = first;
  while (true)
  {
    ++i;
    if (i >= poses.size()) return poses.size();
    along += std::hypot(poses[i].x - poses[i - 1].x, poses[i].y - poses[i - 1].y);
    if (along > distance) return i;
  }
}
}  // namespace costmap_layers
