// Sensor readings as the core receives them: plain copies of sensor_msgs LaserScan, PointCloud2 and
// Range, and the rigid transform that takes the sensor's frame into the costmap's global frame. The
// ROS adapter fills them (after tf2 found the transform at the reading's stamp); the core parses and
// validates them, so malformed readings are rejected in one place that tests can reach.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace costmap_layers
{
/// A rigid 3-D transform: p' = R p + t (R row-major).
struct Transform3D
{
  double r[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double t[3] = {0, 0, 0};

  void apply(double x, double y, double z, double& ox, double& oy, double& oz) const
  {
    ox = r[0] * x + r[1] * y + r[2] * z + t[0];
    oy = r[3] * x + r[4] * y + r[5] * z + t[1];
    oz = r[6] * x + r[7] * y + r[8] * z + t[2];
  }
  /// From a translation and a unit quaternion (x, y, z, w).
  static Transform3D fromQuaternion(double tx, double ty, double tz, double qx, double qy, double qz, double qw)
  {
    Transform3D T;
    T.t[0] = tx, T.t[1] = ty, T.t[2] = tz;
    T.r[0] = 1 - 2 * (qy * qy + qz * qz), T.r[1] = 2 * (qx * qy - qz * qw), T.r[2] = 2 * (qx * qz + qy * qw);
    T.r[3] = 2 * (qx * qy + qz * qw), T.r[4] = 1 - 2 * (qx * qx + qz * qz), T.r[5] = 2 * (qy * qz - qx * qw);
    T.r[6] = 2 * (qx * qz - qy * qw), T.r[7] = 2 * (qy * qz + qx * qw), T.r[8] = 1 - 2 * (qx * qx + qy * qy);
    return T;
  }
};

/// sensor_msgs/LaserScan.
struct LaserScanData
{
  std::string frame_id;
  uint64_t stamp_ns = 0;
  float angle_min = 0, angle_max = 0, angle_increment = 0;  ///< [rad]
  float time_increment = 0, scan_time = 0;                  ///< [s]
  float range_min = 0, range_max = 0;                       ///< [m]
  std::vector<float> ranges;                                ///< [m]
  std::vector<float> intensities;
};

/// sensor_msgs/PointField.
struct PointFieldData
{
  enum : uint8_t
  {
    INT8 = 1,
    UINT8 = 2,
    INT16 = 3,
    UINT16 = 4,
    INT32 = 5,
    UINT32 = 6,
    FLOAT32 = 7,
    FLOAT64 = 8
  };
  std::string name;
  uint32_t offset = 0;
  uint8_t datatype = 0;
  uint32_t count = 0;
};

/// sensor_msgs/PointCloud2. Its bytes are either in `data` or, received from a message, borrowed from it
/// (`view`, `view_size`, the message kept alive by `keep`): a cloud is read once, where it arrived, and
/// copying megabytes per message was what a cloud cost most. Read them through bytes() / byteCount().
struct PointCloud2Data
{
  std::string frame_id;
  uint64_t stamp_ns = 0;
  uint32_t height = 0, width = 0;
  std::vector<PointFieldData> fields;
  bool is_bigendian = false;
  uint32_t point_step = 0, row_step = 0;
  std::vector<uint8_t> data;
  bool is_dense = false;
  const uint8_t* view = nullptr;  ///< when set, the bytes (data stays empty)
  std::size_t view_size = 0;
  std::shared_ptr<const void> keep;  ///< owns what view points into

  const uint8_t* bytes() const { return view != nullptr ? view : data.data(); }
  std::size_t byteCount() const { return view != nullptr ? view_size : data.size(); }
};

/// sensor_msgs/Range.
struct RangeData
{
  enum : uint8_t
  {
    ULTRASOUND = 0,
    INFRARED = 1
  };
  std::string frame_id;
  uint64_t stamp_ns = 0;
  uint8_t radiation_type = ULTRASOUND;
  float field_of_view = 0;             ///< [rad] full cone angle
  float min_range = 0, max_range = 0;  ///< [m]
  float range = 0;                     ///< [m]
};

/// Where a reading was taken: the transform from its frame into the global frame at its stamp, and the
/// sensor origin in the global frame (from `sensor_frame` when the layer set one, else the reading's frame).
struct SensorPose
{
  Transform3D to_global;
  double origin_x = 0, origin_y = 0, origin_z = 0;  ///< [m] global frame
};
}  // namespace costmap_layers
