// Shared pieces of the fuzz targets: a FakeContext that also takes map-update subscriptions, an
// invariant check that aborts (so libFuzzer records the input), and decoders for poses.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "costmap_layers/core/grid/costmap_2d.hpp"
#include "costmap_layers/core/grid/footprint.hpp"
#include "costmap_layers/core/data/grid_data.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "fake_context.hpp"
#include "fuzz_decoder.hpp"

#define FUZZ_CHECK(cond, what)                                                                            \
  do                                                                                                      \
  {                                                                                                       \
    if (!(cond))                                                                                          \
    {                                                                                                     \
      std::fprintf(stderr, "fuzz invariant failed at %s:%d: %s (%s)\n", __FILE__, __LINE__, #cond, what); \
      std::abort();                                                                                       \
    }                                                                                                     \
  } while (0)

namespace costmap_layers_fuzz
{
using namespace costmap_layers;

/// The fuzz targets' host: FakeContext, bound to each layer after it initialises.
using FuzzContext = costmap_layers_test::FakeContext;

/// A double from the input that tf or the robot's localisation could deliver: finite (non-finite
/// values become 0), any magnitude.
inline double finiteReal(FuzzDecoder& in)
{
  const double v = in.real();
  return std::isfinite(v) ? v : 0.0;
}

/// A master grid the fuzzed inputs are drawn into: 1..64 cells a side, resolution (1..256)/64 m,
/// origin within +-100 m (the costmap's own parameters are fuzzed by fuzz_params, not here).
struct MasterGeometry
{
  unsigned w = 1, h = 1;
  double res = 1.0, ox = 0.0, oy = 0.0;
  static MasterGeometry decode(FuzzDecoder& in)
  {
    MasterGeometry g;
    g.w = in.small(1, 64);
    g.h = in.small(1, 64);
    g.res = (1 + in.u8()) / 64.0;
    g.ox = in.i16() / 256.0;
    g.oy = in.i16() / 256.0;
    return g;
  }
};

/// A robot pose from the input: finite values, mostly near the grid.
inline void decodePose(FuzzDecoder& in, double& x, double& y, double& yaw)
{
  x = finiteReal(in);
  y = finiteReal(in);
  yaw = finiteReal(in);
}

/// The master grid's geometry must never change except through resizeMap.
/// An OccupancyGrid as a map or mask topic would deliver it: frame map or odom, any size, resolution,
/// origin and yaw, and data of the right length or not (gridValues).
inline OccupancyGridData decodeGrid(FuzzDecoder& in)
{
  OccupancyGridData m;
  m.frame_id = in.flag() ? "odom" : "map";
  m.width = in.size();
  m.height = in.size();
  m.resolution = in.real();
  m.origin_x = in.real();
  m.origin_y = in.real();
  m.origin_yaw = in.real();
  m.data = gridValues(in, static_cast<uint64_t>(m.width) * m.height, 1u << 16);
  return m;
}

inline void checkMasterUnchanged(const LayeredCostmap& lc, unsigned w, unsigned h, double res)
{
  const Costmap2D& m = lc.getCostmap();
  FUZZ_CHECK(m.getSizeInCellsX() == w && m.getSizeInCellsY() == h, "master grid size changed");
  FUZZ_CHECK(m.getResolution() == res, "master grid resolution changed");
}
}  // namespace costmap_layers_fuzz

#include "costmap_layers/core/layers/voxel_layer.hpp"

namespace costmap_layers_fuzz
{
/// Where a sensor reading was taken: a normalised rotation and a translation from the input (what tf
/// delivers: finite, unit quaternion).
inline SensorPose decodeSensorPose(FuzzDecoder& in)
{
  const double tx = finiteReal(in), ty = finiteReal(in), tz = finiteReal(in);
  double q[4] = {in.i16() / 32768.0, in.i16() / 32768.0, in.i16() / 32768.0, in.i16() / 32768.0};
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (n < 1e-6)
    q[0] = q[1] = q[2] = 0, q[3] = 1;
  else
    for (double& v : q)
      v /= n;
  SensorPose p;
  p.to_global = Transform3D::fromQuaternion(tx, ty, tz, q[0], q[1], q[2], q[3]);
  p.origin_x = tx, p.origin_y = ty, p.origin_z = tz;
  return p;
}

/// Parameters of an ObstacleLayer / VoxelLayer with one source "src" of the given data type
/// ("LaserScan" or "PointCloud2") on topic "sensor", from the input (valid ranges mostly; the
/// parameters themselves are fuzz_params' business).
inline ParamValue sensorLayerParams(FuzzDecoder& in, const char* data_type, bool voxel)
{
  ParamValue src = ParamValue::makeMap();
  src.set("topic", ParamValue::makeString("sensor"));
  src.set("data_type", ParamValue::makeString(data_type));
  const uint8_t bits = in.u8();
  src.set("marking", ParamValue::makeBool((bits & 1) == 0));
  src.set("clearing", ParamValue::makeBool(bits & 2));
  src.set("inf_is_valid", ParamValue::makeBool(bits & 4));
  src.set("min_obstacle_height", ParamValue::makeDouble(in.i16() / 256.0));
  src.set("max_obstacle_height", ParamValue::makeDouble(in.i16() / 256.0));
  src.set("obstacle_max_range", ParamValue::makeDouble(in.u8() / 8.0));
  src.set("raytrace_max_range", ParamValue::makeDouble(in.u8() / 8.0));
  src.set("raytrace_min_range", ParamValue::makeDouble(in.u8() / 64.0));
  src.set("obstacle_min_range", ParamValue::makeDouble(in.u8() / 64.0));
  if (bits & 8) src.set("sensor_frame", ParamValue::makeString("sensor_mount"));
  ParamValue p = ParamValue::makeMap();
  p.set("observation_sources", ParamValue::makeString("src"));
  p.set("src", src);
  p.set("combination_method", ParamValue::makeInt(in.small(0, 2)));
  p.set("footprint_clearing_enabled", ParamValue::makeBool(bits & 16));
  p.set("max_obstacle_height", ParamValue::makeDouble(in.i16() / 256.0));
  if (voxel)
  {
    p.set("origin_z", ParamValue::makeDouble(in.i16() / 256.0));
    p.set("z_resolution", ParamValue::makeDouble((1 + in.u8()) / 64.0));
    p.set("z_voxels", ParamValue::makeInt(in.small(1, 16)));
    p.set("unknown_threshold", ParamValue::makeInt(in.small(0, 16)));
    p.set("mark_threshold", ParamValue::makeInt(in.small(0, 16)));
  }
  return p;
}

/// The ObstacleLayer (or VoxelLayer) the sensor targets feed, initialised on lc with a 0.3 m round
/// robot; nullptr when the fuzzed parameters are refused (std::invalid_argument ends the input).
inline std::shared_ptr<ObstacleLayer> makeSensorLayer(LayeredCostmap& lc, const std::shared_ptr<FuzzContext>& ctx,
                                                      bool voxel)
{
  std::shared_ptr<ObstacleLayer> layer;
  if (voxel)
    layer = std::make_shared<VoxelLayer>();
  else
    layer = std::make_shared<ObstacleLayer>();
  try
  {
    layer->initialize(&lc, "obstacles", ctx);
    ctx->bind(*layer);
  }
  catch (const std::invalid_argument&)
  {
    return nullptr;
  }
  lc.addPlugin(layer);
  lc.setFootprint(makeFootprintFromRadius(0.3));
  return layer;
}
}  // namespace costmap_layers_fuzz
