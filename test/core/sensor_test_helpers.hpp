// Builders for sensor readings shared by the sensor layer tests and benchmarks.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "costmap_layers/core/config/param_value.hpp"
#include "costmap_layers/core/data/sensor_data.hpp"

namespace costmap_layers_test
{
using namespace costmap_layers;

struct XYZ
{
  double x, y, z;
};

/// A PointCloud2 with float32 (or float64) x, y, z and a padding field, in the given byte order.
inline PointCloud2Data makeCloud(const std::vector<XYZ>& pts, bool float64 = false, bool big_endian = false,
                                 uint64_t stamp_ns = 0)
{
  PointCloud2Data c;
  c.frame_id = "sensor";
  c.stamp_ns = stamp_ns;
  c.height = 1;
  c.width = static_cast<uint32_t>(pts.size());
  const uint32_t size = float64 ? 8 : 4;
  const uint8_t type = float64 ? PointFieldData::FLOAT64 : PointFieldData::FLOAT32;
  c.fields = {{"x", 0, type, 1}, {"y", size, type, 1}, {"z", 2 * size, type, 1}, {"intensity", 3 * size, type, 1}};
  c.point_step = 4 * size;
  c.row_step = c.point_step * c.width;
  c.is_bigendian = big_endian;
  c.data.assign(static_cast<std::size_t>(c.row_step), 0);
  auto put = [&](std::size_t at, double v)
  {
    uint8_t bytes[8];
    if (float64)
      std::memcpy(bytes, &v, 8);
    else
    {
      const float f = static_cast<float>(v);
      std::memcpy(bytes, &f, 4);
    }
    const uint16_t one = 1;
    uint8_t first;
    std::memcpy(&first, &one, 1);
    const bool host_big = first == 0;
    for (uint32_t k = 0; k < size; ++k)
      c.data[at + k] = bytes[host_big == big_endian ? k : size - 1 - k];
  };
  for (std::size_t i = 0; i < pts.size(); ++i)
  {
    put(i * c.point_step, pts[i].x);
    put(i * c.point_step + size, pts[i].y);
    put(i * c.point_step + 2 * size, pts[i].z);
  }
  return c;
}

/// A scan of n beams evenly over [angle_min, angle_max], every range set to r.
inline LaserScanData makeScan(std::size_t n, float angle_min, float angle_max, float r, float range_min = 0.05f,
                              float range_max = 10.0f)
{
  LaserScanData s;
  s.frame_id = "laser";
  s.angle_min = angle_min;
  s.angle_max = angle_max;
  s.angle_increment = n > 1 ? (angle_max - angle_min) / static_cast<float>(n - 1) : 0.01f;
  s.range_min = range_min;
  s.range_max = range_max;
  s.ranges.assign(n, r);
  return s;
}

/// A sensor pose with the sensor at (x, y, z) in the global frame, rotated by yaw.
inline SensorPose poseAt(double x, double y, double z, double yaw = 0.0)
{
  SensorPose p;
  p.to_global = Transform3D::fromQuaternion(x, y, z, 0, 0, std::sin(yaw / 2), std::cos(yaw / 2));
  p.origin_x = x;
  p.origin_y = y;
  p.origin_z = z;
  return p;
}

inline ParamValue paramMap(std::initializer_list<std::pair<const char*, ParamValue>> items)
{
  ParamValue p = ParamValue::makeMap();
  for (const auto& it : items)
    p.set(it.first, it.second);
  return p;
}
/// The message of the E that fn throws, or "" when it throws nothing.
template <class E = std::exception, class Fn>
std::string thrownMessage(Fn fn)
{
  try
  {
    fn();
  }
  catch (const E& e)
  {
    return e.what();
  }
  return "";
}

inline ParamValue S(const std::string& s)
{
  return ParamValue::makeString(s);
}
inline ParamValue D(double d)
{
  return ParamValue::makeDouble(d);
}
inline ParamValue I(int64_t i)
{
  return ParamValue::makeInt(i);
}
inline ParamValue B(bool b)
{
  return ParamValue::makeBool(b);
}
}  // namespace costmap_layers_test
