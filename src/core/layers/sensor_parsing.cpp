#include "costmap_layers/core/layers/sensor_parsing.hpp"

#include <cmath>
#include <cstring>
#include <sstream>

namespace costmap_layers
{
namespace
{
template <class T>
std::string describe(const char* what, T value)
{
  std::ostringstream s;
  s << what << " (got " << value << ")";
  return s.str();
}
}  // namespace

bool hostIsBigEndian()
{
  const uint16_t one = 1;
  uint8_t first = 0;
  std::memcpy(&first, &one, 1);
  return first == 0;
}

std::string validateLaserScan(const LaserScanData& scan)
{
  if (!std::isfinite(scan.angle_min)) return describe("LaserScan angle_min is not finite", scan.angle_min);
  if (!std::isfinite(scan.angle_max)) return describe("LaserScan angle_max is not finite", scan.angle_max);
  if (!std::isfinite(scan.angle_increment))
    return describe("LaserScan angle_increment is not finite", scan.angle_increment);
  if (scan.angle_increment == 0.0f) return describe("LaserScan angle_increment is zero", scan.angle_increment);
  if (!std::isfinite(scan.range_min)) return describe("LaserScan range_min is not finite", scan.range_min);
  if (!std::isfinite(scan.range_max)) return describe("LaserScan range_max is not finite", scan.range_max);
  if (scan.range_min < 0.0f) return describe("LaserScan range_min is negative", scan.range_min);
  if (scan.range_max < scan.range_min) return describe("LaserScan range_max is below range_min", scan.range_max);

  const double span = static_cast<double>(scan.angle_max) - static_cast<double>(scan.angle_min);
  const double steps = span / static_cast<double>(scan.angle_increment);
  if (!std::isfinite(steps) || steps < -0.5)
    return describe("LaserScan angle_increment has the wrong sign for angle_min..angle_max", scan.angle_increment);
  if (steps > 1e9) return describe("LaserScan angle_increment describes too many beams", scan.angle_increment);
  const double expected = std::floor(steps + 0.5) + 1.0;
  const double got = static_cast<double>(scan.ranges.size());
  if (std::fabs(got - expected) > 1.0)
  {
    std::ostringstream s;
    s << "LaserScan ranges has " << scan.ranges.size() << " values but the angles describe " << expected << " beams";
    return s.str();
  }
  return {};
}

const BeamDirections& beamDirections(const LaserScanData& scan)
{
  thread_local BeamDirections dir;
  const std::size_t n = scan.ranges.size();
  // Compared bit for bit (a NaN angle never reaches here: the scan was validated).
  if (dir.cos.size() != n || dir.angle_min != scan.angle_min || dir.angle_increment != scan.angle_increment)
  {
    dir.angle_min = scan.angle_min;
    dir.angle_increment = scan.angle_increment;
    dir.cos.resize(n);
    dir.sin.resize(n);
    const double a0 = scan.angle_min, da = scan.angle_increment;
    for (std::size_t i = 0; i < n; ++i)
    {
      const double a = a0 + static_cast<double>(i) * da;
      dir.cos[i] = std::cos(a);
      dir.sin[i] = std::sin(a);
    }
  }
  return dir;
}

ParseResult laserScanToPoints(const LaserScanData& scan, bool inf_is_valid, std::vector<Point3f>& points,
                              std::vector<Point3f>& clear_only)
{
  ParseResult result;
  result.error = validateLaserScan(scan);
  if (!result.ok()) return result;
  points.reserve(points.size() + scan.ranges.size());
  forEachScanPoint(scan, inf_is_valid, result,
                   [&](const Point3f& p, bool only_clears) { (only_clears ? clear_only : points).push_back(p); });
  return result;
}

namespace
{
struct FieldView
{
  uint32_t offset = 0;
  uint8_t size = 0;  ///< 4 (FLOAT32) or 8 (FLOAT64)
};

/// Finds one coordinate field and checks it; returns an error or fills view.
std::string findField(const PointCloud2Data& cloud, const char* name, FieldView& view)
{
  const PointFieldData* found = nullptr;
  for (const auto& f : cloud.fields)
  {
    if (f.name == name)
    {
      found = &f;
      break;
    }
  }
  if (found == nullptr) return std::string("PointCloud2 has no field '") + name + "'";
  if (found->datatype == PointFieldData::FLOAT32)
    view.size = 4;
  else if (found->datatype == PointFieldData::FLOAT64)
    view.size = 8;
  else
    return std::string("PointCloud2 field '") + name + "' is not FLOAT32 or FLOAT64 (datatype " +
           std::to_string(found->datatype) + ")";
  // count 0 is what some drivers send for a scalar; more than one element uses the first.
  const uint64_t end = static_cast<uint64_t>(found->offset) + view.size;
  if (end > cloud.point_step)
    return std::string("PointCloud2 field '") + name + "' at offset " + std::to_string(found->offset) +
           " does not fit in point_step " + std::to_string(cloud.point_step);
  view.offset = found->offset;
  return {};
}

template <class T>
T readSwapped(const uint8_t* p, bool swap)
{
  uint8_t bytes[sizeof(T)];
  if (swap)
  {
    for (std::size_t k = 0; k < sizeof(T); ++k)
      bytes[k] = p[sizeof(T) - 1 - k];
  }
  else
  {
    std::memcpy(bytes, p, sizeof(T));
  }
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

std::string validateLayout(const PointCloud2Data& cloud, FieldView fields[3])
{
  const uint64_t count = static_cast<uint64_t>(cloud.width) * cloud.height;
  if (count > 0 && cloud.point_step == 0)
    return "PointCloud2 point_step is 0 with " + std::to_string(count) + " points";
  const char* names[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k)
  {
    std::string e = findField(cloud, names[k], fields[k]);
    if (!e.empty()) return e;
  }
  const uint64_t row_bytes = static_cast<uint64_t>(cloud.width) * cloud.point_step;
  if (static_cast<uint64_t>(cloud.row_step) < row_bytes)
    return "PointCloud2 row_step " + std::to_string(cloud.row_step) +
           " is below width * point_step = " + std::to_string(row_bytes);
  const uint64_t needed = static_cast<uint64_t>(cloud.row_step) * cloud.height;
  if (static_cast<uint64_t>(cloud.byteCount()) < needed)
    return "PointCloud2 data has " + std::to_string(cloud.byteCount()) + " bytes, row_step * height needs " +
           std::to_string(needed);
  return {};
}
}  // namespace

std::string validatePointCloud2(const PointCloud2Data& cloud)
{
  FieldView fields[3];
  return validateLayout(cloud, fields);
}

namespace detail
{
double readCloudCoordinate(const uint8_t* point, uint32_t offset, uint8_t size, bool swap)
{
  if (size == 4) return readSwapped<float>(point + offset, swap);
  return readSwapped<double>(point + offset, swap);
}

std::string cloudLayout(const PointCloud2Data& cloud, CloudLayout& layout)
{
  FieldView f[3];
  std::string error = validateLayout(cloud, f);
  if (!error.empty()) return error;
  for (int k = 0; k < 3; ++k)
  {
    layout.offset[k] = f[k].offset;
    layout.size[k] = f[k].size;
  }
  layout.swap = cloud.is_bigendian != hostIsBigEndian();
  return {};
}
}  // namespace detail

ParseResult pointCloud2ToPoints(const PointCloud2Data& cloud, std::vector<Point3f>& points)
{
  ParseResult result;
  detail::CloudLayout layout;
  result.error = detail::cloudLayout(cloud, layout);
  if (!result.ok()) return result;
  // The layout check bounds width * height by data.size() / point_step, so this reservation is safe.
  points.reserve(points.size() + static_cast<std::size_t>(cloud.width) * cloud.height);
  forEachCloudPoint(cloud, layout, result, [&](const Point3f& p) { points.push_back(p); });
  return result;
}

RangeInterpretation interpretRange(const RangeData& range, RangeInputType type, bool clear_on_max_reading)
{
  RangeInterpretation out;
  const double pi = 3.14159265358979323846;
  if (!std::isfinite(range.field_of_view) || range.field_of_view <= 0.0f || range.field_of_view > pi)
  {
    out.error = describe("Range field_of_view must be finite and in (0, pi]", range.field_of_view);
    return out;
  }
  if (!std::isfinite(range.min_range) || range.min_range < 0.0f)
  {
    out.error = describe("Range min_range must be finite and >= 0", range.min_range);
    return out;
  }
  if (!std::isfinite(range.max_range) || range.max_range < range.min_range)
  {
    out.error = describe("Range max_range must be finite and >= min_range", range.max_range);
    return out;
  }
  if (std::isnan(range.range))
  {
    out.error = describe("Range range is NaN", range.range);
    return out;
  }
  const bool fixed =
      type == RangeInputType::Fixed || (type == RangeInputType::All && range.min_range == range.max_range);
  if (fixed)
  {
    if (!std::isinf(range.range))
    {
      out.error =
          describe("Range from a fixed-distance ranger (min_range == max_range) must be -inf or +inf", range.range);
      return out;
    }
    if (range.range > 0)
    {
      if (!clear_on_max_reading) return out;  // nothing in view and no clearing asked for
      out.clear = true;
    }
    out.use = true;
    out.range = range.min_range;
    return out;
  }
  if (range.range < range.min_range || range.range > range.max_range) return out;  // ignored
  out.use = true;
  out.range = range.range;
  out.clear = clear_on_max_reading && range.range >= range.max_range;
  return out;
}
}  // namespace costmap_layers
