// Fuzzes LaserScan readings: validateLaserScan and laserScanToPoints directly, then the same scan
// through an ObstacleLayer or VoxelLayer (the LaserScan subscription -> addLaserScan -> buffer) and
// update cycles, on a fixed or rolling LayeredCostmap.
// Input: layer kind, its parameters, master geometry, then readings (angles, ranges with their
// special values, counts that disagree with the angles, intensities) with their sensor poses, and
// update cycles.
// Invariants: the parser appends nothing on error and counts exactly what it appends; every point
// is finite; a hit lies within range_max of the sensor; the master grid keeps its geometry.
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>

#include "costmap_layers/core/layers/sensor_parsing.hpp"
#include "fuzz_common.hpp"

using namespace costmap_layers;
using namespace costmap_layers_fuzz;

namespace
{
LaserScanData decodeScan(FuzzDecoder& in)
{
  LaserScanData s;
  s.frame_id = "laser";
  s.angle_min = in.real32();
  s.angle_max = in.real32();
  s.angle_increment = in.real32();
  s.time_increment = in.real32();
  s.scan_time = in.real32();
  s.range_min = in.real32();
  s.range_max = in.real32();
  const uint32_t n = in.size();
  const uint32_t take = n < 2048 ? n : 2048;
  // Ranges: a pattern of up to 8 values repeated over the beams (keeps inputs short), or one value per
  // beam when the flag says so.
  if (in.flag())
    for (uint32_t k = 0; k < take && !in.empty(); ++k)
      s.ranges.push_back(in.real32());
  else
  {
    std::vector<float> pattern(in.small(1, 8));
    for (float& v : pattern)
      v = in.real32();
    for (uint32_t k = 0; k < take; ++k)
      s.ranges.push_back(pattern[k % pattern.size()]);
  }
  s.intensities.assign(in.small(0, 3) == 0 ? s.ranges.size() : in.small(0, 4), 1.0f);
  return s;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  FuzzDecoder in(data, size);
  const uint8_t kind = in.u8();
  const bool voxel = kind & 1, rolling = kind & 2;
  const ParamValue params = sensorLayerParams(in, "LaserScan", voxel);
  const MasterGeometry g = MasterGeometry::decode(in);

  LayeredCostmap lc("map", rolling, (kind & 4) != 0);
  lc.resizeMap(g.w, g.h, g.res, g.ox, g.oy);
  auto ctx = std::make_shared<FuzzContext>(params);
  const std::shared_ptr<ObstacleLayer> layer = makeSensorLayer(lc, ctx, voxel);
  if (!layer) return 0;

  for (int op = 0; op < 6 && !in.empty(); ++op)
  {
    if (in.u8() % 3 != 0)
    {
      const LaserScanData scan = decodeScan(in);
      const bool inf_is_valid = layer->config().sources[0].inf_is_valid;
      std::vector<Point3f> points(1), clear_only(2);  // the parser appends
      const ParseResult r = laserScanToPoints(scan, inf_is_valid, points, clear_only);
      FUZZ_CHECK(r.ok() == validateLaserScan(scan).empty(), "laserScanToPoints validates as validateLaserScan");
      FUZZ_CHECK(points.size() == 1 + r.points && clear_only.size() == 2 + r.clear_only,
                 "the parser counts what it appends");
      if (!r.ok()) FUZZ_CHECK(r.points == 0 && r.clear_only == 0, "nothing appended on error");
      for (std::size_t k = 1; k < points.size(); ++k)
      {
        const Point3f& p = points[k];
        FUZZ_CHECK(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z), "points are finite");
        FUZZ_CHECK(std::hypot(p.x, p.y) <= scan.range_max * (1 + 1e-5) + 1e-5, "a hit lies within range_max");
      }
      for (std::size_t k = 2; k < clear_only.size(); ++k)
        FUZZ_CHECK(std::isfinite(clear_only[k].x) && std::isfinite(clear_only[k].y), "clearing points are finite");
      ctx->publishScan("sensor", scan, decodeSensorPose(in));
    }
    else
    {
      double x, y, yaw;
      decodePose(in, x, y, yaw);
      lc.updateMap(x, y, yaw);
      checkMasterUnchanged(lc, g.w, g.h, g.res);
    }
  }
  return 0;
}
