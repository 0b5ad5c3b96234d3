// A planar rigid transform (x, y, yaw): what the core needs of tf.
#pragma once

#include <cmath>

namespace costmap_layers
{
struct Transform2D
{
  double x = 0.0;    ///< [m]
  double y = 0.0;    ///< [m]
  double yaw = 0.0;  ///< [rad]

  /// Maps a point given in the source frame into the target frame.
  void apply(double px, double py, double& ox, double& oy) const
  {
    const double c = std::cos(yaw), s = std::sin(yaw);
    ox = x + c * px - s * py;
    oy = y + s * px + c * py;
  }
  Transform2D inverse() const
  {
    const double c = std::cos(yaw), s = std::sin(yaw);
    return {-(c * x + s * y), s * x - c * y, -yaw};
  }
  bool isIdentity() const { return x == 0.0 && y == 0.0 && yaw == 0.0; }
};
}  // namespace costmap_layers
