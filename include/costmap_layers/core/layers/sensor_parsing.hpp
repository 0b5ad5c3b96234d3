// Turning raw sensor readings (sensor_data.hpp) into points, with every check a hostile or broken
// driver needs: the parsers never trust a size, an offset or a count, never read past the data, and say
// what was wrong (field name and value) instead of crashing. All arithmetic on sizes is done in 64 bits.
#pragma once

#include <cstddef>
#include <cstdint>
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
}  // namespace costmap_layers
