// Sensor layer benchmarks, each next to a memcpy of the same grid measured in the same run (the
// machines are shared: compare ratios). A rolling local costmap cycle as move_base runs it: a 360-beam
// LaserScan delivered to the ObstacleLayer (parsed, projected, buffered), then updateMap (raytrace,
// mark, footprint clearing, merge, InflationLayer at 0.55 m). costmap_2d needs about 0.9 ms (200x200)
// and 2.4 ms (400x400) for that cycle. And a 640x480 PointCloud2 into the VoxelLayer, and what its
// voxel outputs (publish_voxel_map) cost when nobody reads them and when someone does.
#include <benchmark/benchmark.h>

#include "bench_stats.hpp"

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/layers/inflation_layer.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/data/voxel_grid_data.hpp"
#include "costmap_layers/core/layers/obstacle_layer.hpp"
#include "costmap_layers/core/layers/voxel_layer.hpp"
#include "fake_context.hpp"
#include "sensor_test_helpers.hpp"

using namespace costmap_layers;
using namespace costmap_layers_test;

namespace
{
constexpr double kPi = 3.14159265358979323846;

void BM_MemcpyGrid(benchmark::State& state)
{
  const std::size_t n = static_cast<std::size_t>(state.range(0)) * static_cast<std::size_t>(state.range(0));
  std::vector<uint8_t> a(n, 1), b(n, 2);
  for (auto _ : state)
  {
    std::memcpy(b.data(), a.data(), n);
    benchmark::DoNotOptimize(b.data());
    benchmark::ClobberMemory();
  }
}
COSTMAP_BENCH(BM_MemcpyGrid)->Arg(200)->Arg(400)->Unit(benchmark::kMicrosecond);

/// A room of walls 1.5 .. 6 m away with some clutter, as bench_inflation's scan.
LaserScanData roomScan()
{
  LaserScanData s;
  s.frame_id = "laser";
  s.angle_min = 0.0f;
  s.angle_increment = static_cast<float>(2.0 * kPi / 360.0);
  s.angle_max = s.angle_increment * 359.0f;
  s.range_min = 0.05f;
  s.range_max = 8.0f;
  for (int k = 0; k < 360; ++k)
  {
    const double a = 2.0 * kPi * k / 360.0;
    const double wall =
        std::min(4.0 / std::max(std::fabs(std::cos(a)), 1e-3), 3.0 / std::max(std::fabs(std::sin(a)), 1e-3));
    s.ranges.push_back(static_cast<float>(k % 17 == 0 ? 1.5 : std::min(wall, 6.0)));
  }
  return s;
}

void BM_RollingObstacleInflationCycle(benchmark::State& state)
{
  const unsigned size = static_cast<unsigned>(state.range(0));
  LayeredCostmap lc("odom", true, false);
  lc.resizeMap(size, size, 0.05, 0, 0);
  ParamValue p = paramMap({{"observation_sources", S("scan")}});
  p.set("scan", paramMap({{"data_type", S("LaserScan")}, {"clearing", B(true)}, {"marking", B(true)}}));
  auto ctx = std::make_shared<FakeContext>(p);
  auto obstacles = std::make_shared<ObstacleLayer>();
  obstacles->initialize(&lc, "obstacles", ctx);
  ctx->bind(*obstacles);
  lc.addPlugin(obstacles);
  auto inflation = std::make_shared<InflationLayer>();
  inflation->initialize(&lc, "inflation", std::make_shared<FakeContext>(paramMap({{"inflation_radius", D(0.55)}})));
  lc.addPlugin(inflation);
  lc.setFootprint({{-0.22, -0.22}, {0.22, -0.22}, {0.22, 0.22}, {-0.22, 0.22}});
  const LaserScanData scan = roomScan();
  double x = 0.0;
  for (auto _ : state)
  {
    x += 0.013;
    ctx->publishScan("scan", scan, poseAt(x, 0.5 * x, 0.2));
    lc.updateMap(x, 0.5 * x, 0.0);
    benchmark::ClobberMemory();
  }
  int lethal = 0;
  const Costmap2D& m = lc.getCostmap();
  for (std::size_t k = 0; k < m.cellCount(); ++k)
    lethal += m.data()[k] == LETHAL_OBSTACLE;
  state.counters["lethal"] = lethal;
}
COSTMAP_BENCH(BM_RollingObstacleInflationCycle)->Arg(200)->Arg(400)->Unit(benchmark::kMicrosecond);

/// A depth camera's cloud: 640x480 float32 points on a wall 2.5 m ahead with a box in front, 1.2 rad
/// wide, in the camera's frame (x forward).
PointCloud2Data cameraCloud()
{
  std::vector<XYZ> pts;
  pts.reserve(640 * 480);
  for (int v = 0; v < 480; ++v)
  {
    for (int u = 0; u < 640; ++u)
    {
      const double yaw = (u - 320) * (1.2 / 640), pitch = (v - 240) * (0.9 / 480);
      const double depth = (std::fabs(yaw) < 0.15 && pitch < 0.0) ? 1.2 : 2.5;
      if ((u * 7 + v * 3) % 97 == 0)
        pts.push_back({NAN, NAN, NAN});  // dropouts
      else
        pts.push_back({depth, depth * std::tan(yaw), depth * std::tan(pitch)});
    }
  }
  PointCloud2Data c = makeCloud(pts);
  c.width = 640;
  c.height = 480;
  c.row_step = c.point_step * 640;
  return c;
}

/// A 200x200 rolling costmap at 5 cm with one VoxelLayer (16 levels of 0.1 m) reading a camera cloud.
struct CameraVoxelRig
{
  explicit CameraVoxelRig(bool publish_voxel_map = false) : lc("odom", true, false)
  {
    lc.resizeMap(200, 200, 0.05, 0, 0);
    ParamValue p = paramMap({{"observation_sources", S("camera")},
                             {"z_voxels", I(16)},
                             {"z_resolution", D(0.1)},
                             {"publish_voxel_map", B(publish_voxel_map)}});
    p.set("camera", paramMap({{"data_type", S("PointCloud2")},
                              {"clearing", B(true)},
                              {"marking", B(true)},
                              {"min_obstacle_height", D(-1.0)}}));
    ctx = std::make_shared<FakeContext>(p);
    voxels = std::make_shared<VoxelLayer>();
    voxels->initialize(&lc, "voxels", ctx);
    ctx->bind(*voxels);
    lc.addPlugin(voxels);
  }
  LayeredCostmap lc;
  std::shared_ptr<FakeContext> ctx;
  std::shared_ptr<VoxelLayer> voxels;
};

void BM_VoxelLayerCameraCloud(benchmark::State& state)
{
  const bool parse_only = state.range(0) == 0;
  CameraVoxelRig rig;
  const PointCloud2Data cloud = cameraCloud();
  for (auto _ : state)
  {
    rig.ctx->publishCloud("camera", cloud, poseAt(0.0, 0.0, 0.5));
    if (!parse_only) rig.lc.updateMap(0.0, 0.0, 0.0);
    benchmark::ClobberMemory();
  }
  state.SetLabel(parse_only ? "parse+project+buffer" : "parse+project+buffer+raytrace+mark+merge");
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * 640 * 480);
}
COSTMAP_BENCH(BM_VoxelLayerCameraCloud)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
/// One rolling 200x200 voxel cycle on the camera cloud. Arg 0: publish_voxel_map false; 1: true, nobody
/// subscribed (the outputs must cost nothing); 2: true and the cube list wanted, its centres listed as
/// the host does for RViz.
void BM_VoxelOutputsOnDemand(benchmark::State& state)
{
  const int mode = static_cast<int>(state.range(0));
  CameraVoxelRig rig(mode > 0);
  auto& voxels = rig.voxels;
  std::vector<VoxelPoint> points;
  std::size_t drawn = 0;
  voxels->setOutputListener([&](const OutputEvent& e) {
    if (e.voxels) drawn += voxelCentres(*e.voxels, VoxelStatus::Marked, points);
  });
  if (mode == 2) voxels->setOutputWanted(VoxelLayer::kVoxelMarkersTopic, true);
  const PointCloud2Data cloud = cameraCloud();
  for (auto _ : state)
  {
    rig.ctx->publishCloud("camera", cloud, poseAt(0.0, 0.0, 0.5));
    rig.lc.updateMap(0.0, 0.0, 0.0);
    benchmark::ClobberMemory();
  }
  state.SetLabel(mode == 0 ? "no voxel outputs" : mode == 1 ? "outputs, nobody reads" : "cube list read");
  state.counters["voxels_drawn"] = static_cast<double>(drawn) / std::max<double>(1.0, state.iterations());
}
COSTMAP_BENCH(BM_VoxelOutputsOnDemand)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
