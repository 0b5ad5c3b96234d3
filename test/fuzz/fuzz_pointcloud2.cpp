// Fuzzes PointCloud2 readings: validatePointCloud2 and pointCloud2ToPoints directly, then the same
// cloud through an ObstacleLayer or VoxelLayer (the PointCloud2 subscription -> addPointCloud2 ->
// buffer) and update cycles, on a fixed or rolling LayeredCostmap.
// Input: layer kind, its parameters, master geometry, then clouds (fields with names, offsets,
// datatypes and counts; point_step, row_step, width, height, endianness; data of a matching,
// shorter or longer length) with their sensor poses, and update cycles.
// Invariants: the parser appends nothing on error and counts exactly what it appends (points +
// dropped = width * height on success); every point is finite; the master grid keeps its geometry.
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
PointCloud2Data decodeCloud(FuzzDecoder& in)
{
  static const char* const kNames[] = {"x", "y", "z", "intensity", "rgb", "X", ""};
  PointCloud2Data c;
  c.frame_id = "sensor";
  c.height = in.size();
  c.width = in.size();
  const uint32_t nfields = in.small(0, 6);
  for (uint32_t k = 0; k < nfields; ++k)
  {
    PointFieldData f;
    const uint8_t pick = in.u8();
    f.name = pick < 224 ? kNames[pick % 7] : in.str(4);
    f.offset = in.size();
    f.datatype = in.u8() % 10;  // 0 and 9 are not PointField types
    f.count = in.size();
    c.fields.push_back(f);
  }
  c.is_bigendian = in.flag();
  c.is_dense = in.flag();
  c.point_step = in.size();
  // row_step: exactly width * point_step, or anything.
  const uint64_t natural = static_cast<uint64_t>(c.width) * c.point_step;
  c.row_step = in.flag() ? static_cast<uint32_t>(natural) : in.size();
  // data: row_step * height bytes (when that is affordable), or an explicit length; payload from the
  // input, cycled.
  const uint64_t want = static_cast<uint64_t>(c.row_step) * c.height;
  const uint8_t how = in.u8() % 4;
  uint64_t n = how == 0 ? want : how == 1 ? (want > 0 ? want - 1 : 0) : how == 2 ? want + 1 : in.size();
  if (n > (1u << 18)) n = in.u8();  // an unaffordable length is still a mismatch, just a cheaper one
  const std::vector<uint8_t> src = in.bytes(static_cast<std::size_t>(n < 4096 ? n : 4096));
  c.data.resize(static_cast<std::size_t>(n));
  for (std::size_t k = 0; k < c.data.size(); ++k)
    c.data[k] = src.empty() ? 0 : src[k % src.size()];
  return c;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  FuzzDecoder in(data, size);
  const uint8_t kind = in.u8();
  const bool voxel = kind & 1, rolling = kind & 2;
  const ParamValue params = sensorLayerParams(in, "PointCloud2", voxel);
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
      const PointCloud2Data cloud = decodeCloud(in);
      std::vector<Point3f> points(3);  // the parser appends
      const ParseResult r = pointCloud2ToPoints(cloud, points);
      FUZZ_CHECK(r.ok() == validatePointCloud2(cloud).empty(), "pointCloud2ToPoints validates as validatePointCloud2");
      FUZZ_CHECK(points.size() == 3 + r.points, "the parser counts what it appends");
      if (r.ok())
        FUZZ_CHECK(r.points + r.dropped == static_cast<uint64_t>(cloud.width) * cloud.height,
                   "every point of a valid cloud is kept or dropped");
      else
        FUZZ_CHECK(r.points == 0, "nothing appended on error");
      for (std::size_t k = 3; k < points.size(); ++k)
        FUZZ_CHECK(std::isfinite(points[k].x) && std::isfinite(points[k].y) && std::isfinite(points[k].z),
                   "points are finite");
      ctx->publishCloud("sensor", cloud, decodeSensorPose(in));
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
