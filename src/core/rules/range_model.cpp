#include "costmap_layers/core/rules/range_model.hpp"

#include <algorithm>
#include <cmath>

namespace costmap_layers
{
namespace range_model
{
double gamma(double theta, double max_angle)
{
  if (std::fabs(theta) > max_angle) return 0.0;
  const double q = theta / max_angle;
  return 1.0 - q * q;
}

double delta(double phi, double phi_v)
{
  return 1.0 - (1.0 + std::tanh(2.0 * (phi - phi_v))) / 2.0;
}

double sensorModel(double r, double phi, double theta, double max_angle, double phi_v, double resolution)
{
  const double lambda = delta(phi, phi_v) * gamma(theta, max_angle);
  const double band = resolution * r;                                   // Nav2: delta = resolution, band = delta * r
  if (phi >= 0.0 && phi < r - 2.0 * band) return (1.0 - lambda) * 0.5;  // free ahead of the reading
  if (phi < r - band)
  {
    const double q = (phi - (r - 2.0 * band)) / band;
    return lambda * 0.5 * q * q + (1.0 - lambda) * 0.5;
  }
  if (phi < r + band)
  {
    const double j = (r - phi) / band;
    return lambda * ((1.0 - 0.5 * j * j) - 0.5) + 0.5;  // the obstacle band
  }
  return 0.5;  // behind the reading: no information
}
}  // namespace range_model
}  // namespace costmap_layers
