// What the obstacle and voxel layers share of their rays, written once: where a ray from a sensor
// origin is cut by the grid's box (2-D for the obstacle layer, 3-D for the voxel layer), and the box
// of what a pass over an observation changed, which the layer adds to its update bounds.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace costmap_layers
{
/// The fraction t in [0, 1] of the ray o -> o + dir that stays inside the box [lo, hi] (per axis),
/// starting from the fraction `t` already allowed (1, or less when a range cuts the ray first). The
/// origin must lie inside the box: then each divisor is non-zero when it is used. Axes are cut in
/// order, low side before high side, so 2-D and 3-D give the same t on the axes they share.
template <std::size_t N>
double clipRayToBox(const double (&o)[N], const double (&dir)[N], const double (&lo)[N], const double (&hi)[N],
                    double t)
{
  for (std::size_t i = 0; i < N; ++i)
  {
    if (o[i] + t * dir[i] < lo[i]) t = (lo[i] - o[i]) / dir[i];
    if (o[i] + t * dir[i] > hi[i]) t = (hi[i] - o[i]) / dir[i];
  }
  return std::max(0.0, std::min(1.0, t));
}

// A walk's step k lies k * step (in cells) along its line; a range keeps the steps whose k * step,
// computed in double as a step-by-step walk would, lies within it. k * step grows with k, so they are
// one run of steps, and its two ends are found once per ray instead of tested at every step.

/// The first step k >= 0 whose k * step is >= bound; step > 0.
inline int64_t firstStepAtLeast(double step, double bound)
{
  if (!(bound > 0.0)) return 0;
  int64_t k = static_cast<int64_t>(std::min(std::ceil(bound / step), 4e18));
  while (k > 0 && static_cast<double>(k - 1) * step >= bound)
    --k;
  while (static_cast<double>(k) * step < bound)
    ++k;
  return k;
}

/// The last step k whose k * step is <= bound (-1 for none; a NaN bound has none); step > 0.
inline int64_t lastStepAtMost(double step, double bound)
{
  if (!(bound >= 0.0)) return -1;
  int64_t k = static_cast<int64_t>(std::min(std::floor(bound / step), 4e18));
  while (k >= 0 && static_cast<double>(k) * step > bound)
    --k;
  while (static_cast<double>(k + 1) * step <= bound)
    ++k;
  return k;
}

/// The box of the points a pass touched (in cells or in metres): starts empty, or at one point.
template <class T>
struct TouchedBox
{
  T min_x = std::numeric_limits<T>::max(), min_y = std::numeric_limits<T>::max();
  T max_x = std::numeric_limits<T>::lowest(), max_y = std::numeric_limits<T>::lowest();

  TouchedBox() = default;
  TouchedBox(T x, T y) : min_x(x), min_y(y), max_x(x), max_y(y) {}
  void add(T x, T y)
  {
    min_x = std::min(min_x, x);
    min_y = std::min(min_y, y);
    max_x = std::max(max_x, x);
    max_y = std::max(max_y, y);
  }
  bool empty() const { return min_x > max_x; }
};
}  // namespace costmap_layers
