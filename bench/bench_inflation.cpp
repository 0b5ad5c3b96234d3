// Inflation benchmarks: full inflation of the 4000 x 4000 synthetic indoor map next to a memcpy of the
// same grid (the ratio is what matters), the whole static + inflation update, and rolling local
// costmaps after a 360-beam scan.
#include <benchmark/benchmark.h>

#include "bench_stats.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "costmap_layers/core/cost_values.hpp"
#include "costmap_layers/core/costmap_2d.hpp"
#include "costmap_layers/core/distance_transform.hpp"
#include "costmap_layers/core/inflation_layer.hpp"
#include "costmap_layers/core/layer_context.hpp"
#include "costmap_layers/core/layered_costmap.hpp"
#include "costmap_layers/core/static_layer.hpp"
#include "costmap_layers/io/map_file.hpp"

using namespace costmap_layers;

namespace
{
/// Parameters from a ParamValue; the benchmark hands grids to the layers directly.
class BenchContext : public LayerContext
{
public:
  explicit BenchContext(ParamValue p) : params_(std::move(p)) {}
  const ParamValue& params() const override { return params_; }
  const std::string& globalFrame() const override { return frame_; }
  double transformTolerance() const override { return 0.3; }
  std::optional<Transform2D> lookupTransform(const std::string&, const std::string&, std::string*) override
  {
    return Transform2D{};
  }
  uint64_t nowNs() const override { return 0; }
  void report(Severity, const std::string&, const std::string& message) override
  {
    std::fprintf(stderr, "report: %s\n", message.c_str());
  }

private:
  ParamValue params_;
  std::string frame_ = "map";
};

/// The big map of the benchmarks, loaded once: the map file named by $COSTMAP_LAYERS_BENCH_MAP, which
/// scripts/bench.sh sets to the synthetic 4000x4000 map it writes with scripts/make_synthetic_map.py.
/// Any map_server YAML works (e.g. a robot's own map).
struct BenchMap
{
  bool ok = false;
  std::string error;
  OccupancyGridData grid;
};

const BenchMap& syntheticMap()
{
  static const BenchMap map = []
  {
    BenchMap m;
    const char* path = std::getenv("COSTMAP_LAYERS_BENCH_MAP");
    if (path == nullptr || *path == '\0')
    {
      m.error = "set COSTMAP_LAYERS_BENCH_MAP to a map YAML (scripts/bench.sh does)";
      return m;
    }
    try
    {
      m.grid = io::loadMapFile(path);
      m.ok = true;
    }
    catch (const std::exception& e)
    {
      m.error = e.what();
    }
    return m;
  }();
  return map;
}

ParamValue inflationParams()
{
  ParamValue p = ParamValue::makeMap();
  p.set("inflation_radius", ParamValue::makeDouble(0.55));
  p.set("cost_scaling_factor", ParamValue::makeDouble(10.0));
  return p;
}

Footprint squareFootprint()
{
  return {{-0.22, -0.22}, {0.22, -0.22}, {0.22, 0.22}, {-0.22, 0.22}};
}

/// A static layer fed with the synthetic map, then an inflation layer, on a non-rolling costmap.
struct StaticRig
{
  StaticRig() : lc("map", false, true)
  {
    lc.resizeMap(1, 1, 0.05, 0, 0);
    static_ctx = std::make_shared<BenchContext>(ParamValue::makeMap());
    static_layer = std::make_shared<StaticLayer>();
    static_layer->initialize(&lc, "static", static_ctx);
    lc.addPlugin(static_layer);
    inflation = std::make_shared<InflationLayer>();
    inflation->initialize(&lc, "inflation", std::make_shared<BenchContext>(inflationParams()));
    lc.addPlugin(inflation);
    lc.setFootprint(squareFootprint());
    static_layer->setMap(std::make_shared<const OccupancyGridData>(syntheticMap().grid));
    lc.updateMap(0, 0, 0);
  }
  LayeredCostmap lc;
  std::shared_ptr<BenchContext> static_ctx;
  std::shared_ptr<StaticLayer> static_layer;
  std::shared_ptr<InflationLayer> inflation;
};

void BM_Memcpy16M(benchmark::State& state)
{
  const std::size_t n = 4000u * 4000u;
  std::vector<uint8_t> a(n, 7), b(n, 0);
  for (auto _ : state)
  {
    std::memcpy(b.data(), a.data(), n);
    benchmark::DoNotOptimize(b.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * n));
}
COSTMAP_BENCH(BM_Memcpy16M)->Unit(benchmark::kMillisecond);

/// Full inflation of the map: the layer's updateCosts over the whole grid. Inflating an inflated grid
/// does exactly the same work (the sources do not change), so the grid is not restored in between.
void BM_InflationFull(benchmark::State& state)
{
  if (!syntheticMap().ok)
  {
    state.SkipWithError(syntheticMap().error.c_str());
    return;
  }
  setDistanceTransformSimd(state.range(0) != 0);
  StaticRig rig;
  Costmap2D& master = rig.lc.getCostmap();
  const int w = static_cast<int>(master.getSizeInCellsX()), h = static_cast<int>(master.getSizeInCellsY());
  for (auto _ : state)
  {
    rig.inflation->updateCosts(master, 0, 0, w, h);
    benchmark::ClobberMemory();
  }
  state.SetLabel(distanceTransformKernel());
  setDistanceTransformSimd(true);
}
COSTMAP_BENCH(BM_InflationFull)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

/// The whole update: reset, static layer copy, inflation, over the whole map.
void BM_StaticPlusInflationFull(benchmark::State& state)
{
  if (!syntheticMap().ok)
  {
    state.SkipWithError(syntheticMap().error.c_str());
    return;
  }
  StaticRig rig;
  for (auto _ : state)
  {
    rig.static_layer->reset();  // asks for the whole map again
    rig.lc.updateMap(0, 0, 0);
    benchmark::ClobberMemory();
  }
  state.SetLabel(distanceTransformKernel());
}
COSTMAP_BENCH(BM_StaticPlusInflationFull)->Unit(benchmark::kMillisecond);

/// Marks the end points of a 360-beam scan (a synthetic room) around the robot, every cycle.
class ScanLayer : public Layer
{
public:
  double rx = 0, ry = 0;
  std::vector<double> ranges;
  void updateBounds(double robot_x, double robot_y, double, double* min_x, double* min_y, double* max_x,
                    double* max_y) override
  {
    rx = robot_x;
    ry = robot_y;
    *min_x = std::min(*min_x, robot_x - 20.0);
    *min_y = std::min(*min_y, robot_y - 20.0);
    *max_x = std::max(*max_x, robot_x + 20.0);
    *max_y = std::max(*max_y, robot_y + 20.0);
  }
  void updateCosts(Costmap2D& master, int min_i, int min_j, int max_i, int max_j) override
  {
    for (std::size_t k = 0; k < ranges.size(); ++k)
    {
      const double a = 2.0 * M_PI * static_cast<double>(k) / static_cast<double>(ranges.size());
      unsigned mx, my;
      if (!master.worldToMap(rx + ranges[k] * std::cos(a), ry + ranges[k] * std::sin(a), mx, my)) continue;
      if (int(mx) < min_i || int(mx) >= max_i || int(my) < min_j || int(my) >= max_j) continue;
      master.setCost(mx, my, LETHAL_OBSTACLE);
    }
  }
};

void BM_RollingScanInflation(benchmark::State& state)
{
  const unsigned size = static_cast<unsigned>(state.range(0));
  LayeredCostmap lc("odom", true, false);
  lc.resizeMap(size, size, 0.05, 0, 0);
  auto scan = std::make_shared<ScanLayer>();
  scan->initialize(&lc, "scan", std::make_shared<BenchContext>(ParamValue::makeMap()));
  // A room of walls 1.5 .. 6 m away, with some clutter.
  for (int k = 0; k < 360; ++k)
  {
    const double a = 2.0 * M_PI * k / 360.0;
    const double wall =
        std::min(4.0 / std::max(std::fabs(std::cos(a)), 1e-3), 3.0 / std::max(std::fabs(std::sin(a)), 1e-3));
    scan->ranges.push_back(k % 17 == 0 ? 1.5 : std::min(wall, 6.0));
  }
  lc.addPlugin(scan);
  auto inflation = std::make_shared<InflationLayer>();
  inflation->initialize(&lc, "inflation", std::make_shared<BenchContext>(inflationParams()));
  lc.addPlugin(inflation);
  lc.setFootprint(squareFootprint());
  double x = 0.0;
  for (auto _ : state)
  {
    x += 0.013;
    lc.updateMap(x, 0.5 * x, 0.0);
    benchmark::ClobberMemory();
  }
  state.SetLabel(distanceTransformKernel());
}
COSTMAP_BENCH(BM_RollingScanInflation)->Arg(200)->Arg(400)->Unit(benchmark::kMicrosecond);
}  // namespace

BENCHMARK_MAIN();
