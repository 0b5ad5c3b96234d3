// Turning raw sensor readings (sensor_data.hpp) into points, with every check a hostile or broken
// driver needs: the parsers never trust a size, an offset or a count, never read past the data, and say
// what was wrong (field name and value) instead of crashing. All arithmetic on sizes is done in 64 bits.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "costmap_layers/core/data/sensor_data.hpp"

namespace costmap_layers
{
/// A point [m] in whatever frame the caller says.
struct Point3f
{
  float x = 0, y = 0, z = 0;
};

/// What a parser did. `error` is empty when the reading was valid (some points may still have been
/// dropped, e.g. NaN ranges); otherwise nothing was appended to the outputs.
struct ParseResult
{
  std::string error;
  std::size_t points = 0;      ///< points appended to `points`
  std::size_t clear_only = 0;  ///< points appended to `clear_only` (LaserScan with inf_is_valid)
  std::size_t dropped = 0;     ///< readings skipped (NaN, out of range, non-finite coordinates)
  bool ok() const { return error.empty(); }
};

/// Checks a LaserScan without projecting it: angle_min, angle_max, angle_increment, range_min and
/// range_max finite; angle_increment non-zero and of the sign of angle_max - angle_min; range_min >= 0
/// and <= range_max; ranges.size() within one of the beam count the angles describe
/// (round((angle_max - angle_min) / angle_increment) + 1; drivers disagree on the last beam).
/// @return an empty string when valid, else the reason naming the field and its value.
std::string validateLaserScan(const LaserScanData& scan);

/// Projects a LaserScan into its own frame (beam i at angle_min + i * angle_increment, z = 0) and
/// appends the points. Like laser_geometry, a finite range is a hit when range_min <= r < range_max and
/// is dropped otherwise; NaN and -inf are dropped; +inf (no return) becomes a point at range_max in
/// `clear_only` (rays clear up to it, nothing is marked) when inf_is_valid, and is dropped otherwise.
ParseResult laserScanToPoints(const LaserScanData& scan, bool inf_is_valid, std::vector<Point3f>& points,
                              std::vector<Point3f>& clear_only);

/// The cosine and sine of every beam angle of a scan (angle_min + i * angle_increment, in double), kept
/// per thread and recomputed only when angle_min, angle_increment or the beam count change: a scanner
/// sends the same angles in every message, and the trigonometry was most of a scan's cost.
struct BeamDirections
{
  float angle_min = 0, angle_increment = 0;
  std::vector<double> cos, sin;
};
const BeamDirections& beamDirections(const LaserScanData& scan);

/// laserScanToPoints without the intermediate vectors: sink(point, clear_only) gets each point in
/// beam order (the same points, bit for bit). The scan must be valid (validateLaserScan).
template <class Sink>
void forEachScanPoint(const LaserScanData& scan, bool inf_is_valid, ParseResult& result, Sink&& sink);

/// pointCloud2ToPoints without the intermediate vector: sink(point) gets each point with finite
/// coordinates in storage order. The cloud's layout must be valid (validatePointCloud2).
template <class Sink>
void forEachCloudPoint(const PointCloud2Data& cloud, ParseResult& result, Sink&& sink);

/// Checks a PointCloud2's layout: fields x, y and z present, each FLOAT32 or FLOAT64 with its bytes
/// inside point_step; point_step > 0 when there are points; row_step >= width * point_step;
/// data.size() >= row_step * height.
/// @return an empty string when valid, else the reason naming the field and its value.
std::string validatePointCloud2(const PointCloud2Data& cloud);
/// Whether this machine stores numbers big-endian (what a cloud's is_bigendian is compared with).
bool hostIsBigEndian();

/// Appends every point of a valid cloud whose x, y and z are finite (others count as dropped), in the
/// cloud's own frame. Big-endian clouds are byte-swapped on little-endian hosts (and vice versa).
ParseResult pointCloud2ToPoints(const PointCloud2Data& cloud, std::vector<Point3f>& points);

/// How RangeSensorLayer reads Range messages (Nav2's input_sensor_type).
enum class RangeInputType
{
  All,       ///< min_range == max_range: FIXED, else VARIABLE
  Variable,  ///< a distance in [min_range, max_range]
  Fixed,     ///< +inf: nothing in view, -inf: something in view (at min_range)
};

/// What a Range reading means for the cone update.
struct RangeInterpretation
{
  std::string error;   ///< non-empty: malformed reading (nothing to do)
  bool use = false;    ///< update the cone (false also for well-formed readings that say nothing)
  bool clear = false;  ///< clear the whole cone (a max reading with clear_on_max_reading)
  double range = 0;    ///< [m] the distance the sensor model uses
  bool ok() const { return error.empty(); }
};

/// Nav2's rules: field_of_view must be finite and in (0, pi], min_range and max_range finite with
/// 0 <= min_range <= max_range, range not NaN. VARIABLE: ranges outside [min_range, max_range] are
/// ignored; range == max_range clears the cone when clear_on_max_reading. FIXED: only +-inf are valid;
/// -inf is a detection at min_range, +inf clears the cone when clear_on_max_reading (else ignored).
RangeInterpretation interpretRange(const RangeData& range, RangeInputType type, bool clear_on_max_reading);

// ---- The point loops (templates: the sink is inlined into them).
template <class Sink>
void forEachScanPoint(const LaserScanData& scan, bool inf_is_valid, ParseResult& result, Sink&& sink)
{
  const BeamDirections& dir = beamDirections(scan);
  const std::size_t n = scan.ranges.size();
  const float rmin = scan.range_min, rmax = scan.range_max;
  for (std::size_t i = 0; i < n; ++i)
  {
    const float r = scan.ranges[i];
    float use;
    bool clearing_only = false;
    if (std::isnan(r))
    {
      ++result.dropped;
      continue;
    }
    if (std::isinf(r))
    {
      if (r < 0 || !inf_is_valid)
      {
        ++result.dropped;
        continue;
      }
      use = rmax;
      clearing_only = true;
    }
    else if (r < rmin || r >= rmax)
    {
      ++result.dropped;
      continue;
    }
    else
    {
      use = r;
    }
    Point3f p;
    p.x = static_cast<float>(use * dir.cos[i]);
    p.y = static_cast<float>(use * dir.sin[i]);
    ++(clearing_only ? result.clear_only : result.points);
    sink(p, clearing_only);
  }
}

namespace detail
{
/// Where x, y and z sit in a point, and how to read them (see validatePointCloud2).
struct CloudLayout
{
  uint32_t offset[3] = {0, 0, 0};
  uint8_t size[3] = {4, 4, 4};  ///< 4 (FLOAT32) or 8 (FLOAT64)
  bool swap = false;
};
/// The layout of a cloud validatePointCloud2 accepts ("" and the layout), else the reason.
std::string cloudLayout(const PointCloud2Data& cloud, CloudLayout& layout);
double readCloudCoordinate(const uint8_t* point, uint32_t offset, uint8_t size, bool swap);
}  // namespace detail

template <class Sink>
void forEachCloudPoint(const PointCloud2Data& cloud, const detail::CloudLayout& f, ParseResult& result, Sink&& sink)
{
  const bool all_float = f.size[0] == 4 && f.size[1] == 4 && f.size[2] == 4 && !f.swap;
  for (uint32_t row = 0; row < cloud.height; ++row)
  {
    const uint8_t* p = cloud.bytes() + static_cast<std::size_t>(row) * cloud.row_step;
    for (uint32_t col = 0; col < cloud.width; ++col, p += cloud.point_step)
    {
      Point3f q;
      if (all_float)
      {
        std::memcpy(&q.x, p + f.offset[0], 4);
        std::memcpy(&q.y, p + f.offset[1], 4);
        std::memcpy(&q.z, p + f.offset[2], 4);
      }
      else
      {
        // Doubles beyond float's range become infinite here and are dropped with the rest.
        q.x = static_cast<float>(detail::readCloudCoordinate(p, f.offset[0], f.size[0], f.swap));
        q.y = static_cast<float>(detail::readCloudCoordinate(p, f.offset[1], f.size[1], f.swap));
        q.z = static_cast<float>(detail::readCloudCoordinate(p, f.offset[2], f.size[2], f.swap));
      }
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
      {
        ++result.dropped;
        continue;
      }
      ++result.points;
      sink(q);
    }
  }
}

template <class Sink>
void forEachCloudPoint(const PointCloud2Data& cloud, ParseResult& result, Sink&& sink)
{
  detail::CloudLayout layout;
  result.error = detail::cloudLayout(cloud, layout);
  if (result.ok()) forEachCloudPoint(cloud, layout, result, sink);
}
}  // namespace costmap_layers
