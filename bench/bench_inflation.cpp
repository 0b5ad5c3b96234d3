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

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/grid/costmap_2d.hpp"
#include "costmap_layers/core/kernels/distance_transform.hpp"
#include "costmap_layers/core/grid/footprint.hpp"
#include "costmap_layers/core/layers/inflation_layer.hpp"
#include "costmap_layers/core/costmap/layer_context.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/kernels/simd_targets.hpp"
#include "costmap_layers/core/layers/static_layer.hpp"
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
/// scripts/bench.sh sets to the synthetic 4000x4000 map it writes with scripts/dev/make_synthetic_map.py.
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

ParamValue inflationParams(double radius = 0.55, double factor = 10.0)
{
  ParamValue p = ParamValue::makeMap();
  p.set("inflation_radius", ParamValue::makeDouble(radius));
  p.set("cost_scaling_factor", ParamValue::makeDouble(factor));
  return p;
}

Footprint squareFootprint()
{
  return {{-0.22, -0.22}, {0.22, -0.22}, {0.22, 0.22}, {-0.22, 0.22}};
}

/// What costmap_tool builds from `robot_radius: 0.22` and the default footprint_padding 0.01.
Footprint toolFootprint()
{
  Footprint f = makeFootprintFromRadius(0.22);
  padFootprint(f, 0.01);
  return f;
}

/// A static layer fed with the bench map, then an inflation layer, on a non-rolling costmap. The map
/// may be read at another resolution than its file's (resolution > 0): the same cells, so the same
/// memcpy, with the radius spanning another number of cells.
struct StaticRig
{
  explicit StaticRig(double radius = 0.55, double factor = 10.0, double resolution = 0.0,
                     const Footprint& footprint = squareFootprint())
      : lc("map", false, true), footprint(footprint)
  {
    auto grid = std::make_shared<OccupancyGridData>(syntheticMap().grid);
    if (resolution > 0.0) grid->resolution = resolution;
    map = grid;
    lc.resizeMap(1, 1, map->resolution, 0, 0);
    static_ctx = std::make_shared<BenchContext>(ParamValue::makeMap());
    static_layer = std::make_shared<StaticLayer>();
    static_layer->initialize(&lc, "static", static_ctx);
    lc.addPlugin(static_layer);
    inflation = std::make_shared<InflationLayer>();
    inflation->initialize(&lc, "inflation", std::make_shared<BenchContext>(inflationParams(radius, factor)));
    lc.addPlugin(inflation);
    lc.setFootprint(footprint);
    static_layer->setMap(map);
    lc.updateMap(0, 0, 0);
  }
  /// One update as costmap_tool --repeat times it: the footprint and the map handed over again (the
  /// map converted into the static layer's grid), then the whole update (master reset, static copy,
  /// inflation of every cell).
  void toolUpdate()
  {
    lc.setFootprint(footprint);
    static_layer->setMap(map);
    lc.updateMap(0, 0, 0);
  }
  LayeredCostmap lc;
  Footprint footprint;
  std::shared_ptr<const OccupancyGridData> map;
  std::shared_ptr<BenchContext> static_ctx;
  std::shared_ptr<StaticLayer> static_layer;
  std::shared_ptr<InflationLayer> inflation;
};

/// A memcpy of the bench map's grid (one byte per cell): the baseline of every map benchmark here.
void BM_MemcpyMap(benchmark::State& state)
{
  if (!syntheticMap().ok)
  {
    state.SkipWithError(syntheticMap().error.c_str());
    return;
  }
  const std::size_t n = syntheticMap().grid.data.size();
  std::vector<uint8_t> a(n, 7), b(n, 0);
  for (auto _ : state)
  {
    std::memcpy(b.data(), a.data(), n);
    benchmark::DoNotOptimize(b.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * n));
  state.SetLabel(std::to_string(syntheticMap().grid.width) + "x" + std::to_string(syntheticMap().grid.height));
}
COSTMAP_BENCH(BM_MemcpyMap)->Unit(benchmark::kMillisecond);

/// A memcpy of a size x size grid, the baseline of the rolling-window benchmarks of that size.
void BM_Memcpy(benchmark::State& state)
{
  const std::size_t n = static_cast<std::size_t>(state.range(0)) * static_cast<std::size_t>(state.range(0));
  std::vector<uint8_t> a(n, 7), b(n, 0);
  for (auto _ : state)
  {
    std::memcpy(b.data(), a.data(), n);
    benchmark::DoNotOptimize(b.data());
    benchmark::ClobberMemory();
  }
}
COSTMAP_BENCH(BM_Memcpy)->Arg(200)->Arg(400)->Unit(benchmark::kMicrosecond);

/// Full inflation of the map: the layer's updateCosts over the whole grid. Inflating an inflated grid
/// does exactly the same work (the sources do not change), so the grid is not restored in between.
void BM_InflationFull(benchmark::State& state)
{
  if (!syntheticMap().ok)
  {
    state.SkipWithError(syntheticMap().error.c_str());
    return;
  }
  StaticRig rig;
  Costmap2D& master = rig.lc.getCostmap();
  const int w = static_cast<int>(master.getSizeInCellsX()), h = static_cast<int>(master.getSizeInCellsY());
  for (auto _ : state)
  {
    rig.inflation->updateCosts(master, 0, 0, w, h);
    benchmark::ClobberMemory();
  }
  state.SetLabel(simdTarget());
}
COSTMAP_BENCH(BM_InflationFull)->Unit(benchmark::kMillisecond);

/// The whole static + inflation update, as costmap_tool --repeat times it (see StaticRig::toolUpdate),
/// with the tutorial's parameters (radius 0.55 m, cost_scaling_factor 10, a 0.22 m square robot).
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
    rig.toolUpdate();
    benchmark::ClobberMemory();
  }
  state.SetLabel(simdTarget());
}
COSTMAP_BENCH(BM_StaticPlusInflationFull)->Unit(benchmark::kMillisecond);

/// The sweep: the whole update (as BM_StaticPlusInflationFull) with robot_radius 0.22 (costmap_tool's
/// footprint), for inflation_radius [mm] x resolution [mm, 0 = the map file's own] x
/// cost_scaling_factor.
void BM_StaticInflationSweep(benchmark::State& state)
{
  if (!syntheticMap().ok)
  {
    state.SkipWithError(syntheticMap().error.c_str());
    return;
  }
  StaticRig rig(state.range(0) / 1000.0, static_cast<double>(state.range(2)), state.range(1) / 1000.0, toolFootprint());
  for (auto _ : state)
  {
    rig.toolUpdate();
    benchmark::ClobberMemory();
  }
  state.SetLabel(simdTarget() + " radius " + std::to_string(rig.inflation->cellInflationRadius()) + " cells, reach " +
                 std::to_string(rig.inflation->costReach()));
}
void sweepArgs(benchmark::internal::Benchmark* b)
{
  // COSTMAP_LAYERS_BENCH_RESOLUTIONS=native reads the map at its own resolution only (the real maps);
  // otherwise the sweep reads it at 0.025, 0.05 and 0.1 m.
  const char* res = std::getenv("COSTMAP_LAYERS_BENCH_RESOLUTIONS");
  const bool native = res != nullptr && std::string(res) == "native";
  const std::vector<int64_t> resolutions = native ? std::vector<int64_t>{0} : std::vector<int64_t>{25, 50, 100};
  for (int64_t factor : {3, 10})
    for (int64_t r : resolutions)
      for (int64_t radius : {300, 550, 1000, 2000, 3000})
        b->Args({radius, r, factor});
}
COSTMAP_BENCH(BM_StaticInflationSweep)->Apply(sweepArgs)->Unit(benchmark::kMillisecond);

/// Full inflation at 1.0 m, factor 3 (robot_radius 0.22) with num_threads = state.range(0): the
/// speed-up of two threads on a big map.
void BM_InflationThreads(benchmark::State& state)
{
  if (!syntheticMap().ok)
  {
    state.SkipWithError(syntheticMap().error.c_str());
    return;
  }
  StaticRig rig(1.0, 3.0, 0.0, toolFootprint());
  InflationConfig cfg = rig.inflation->config();
  cfg.num_threads = static_cast<int>(state.range(0));
  rig.inflation->setConfig(cfg);
  Costmap2D& master = rig.lc.getCostmap();
  const int w = static_cast<int>(master.getSizeInCellsX()), h = static_cast<int>(master.getSizeInCellsY());
  for (auto _ : state)
  {
    rig.inflation->updateCosts(master, 0, 0, w, h);
    benchmark::ClobberMemory();
  }
  state.SetLabel(simdTarget() + ", " + std::to_string(state.range(0)) + " thread(s)");
}
COSTMAP_BENCH(BM_InflationThreads)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

/// Full inflation on one SIMD target (each target this build compiled that the CPU runs, measured, not
/// assumed): radius [mm] and factor as arguments, robot_radius 0.22.
void inflationOnTarget(benchmark::State& state, const std::string& target)
{
  if (!syntheticMap().ok)
  {
    state.SkipWithError(syntheticMap().error.c_str());
    return;
  }
  if (!setSimdTarget(target))
  {
    state.SkipWithError("target not available");
    return;
  }
  {
    StaticRig rig(state.range(0) / 1000.0, static_cast<double>(state.range(1)), 0.0, toolFootprint());
    Costmap2D& master = rig.lc.getCostmap();
    const int w = static_cast<int>(master.getSizeInCellsX()), h = static_cast<int>(master.getSizeInCellsY());
    for (auto _ : state)
    {
      rig.inflation->updateCosts(master, 0, 0, w, h);
      benchmark::ClobberMemory();
    }
    state.SetLabel(simdTarget());
  }
  setSimdTarget("");
}

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
  state.SetLabel(simdTarget());
}
COSTMAP_BENCH(BM_RollingScanInflation)->Arg(200)->Arg(400)->Unit(benchmark::kMicrosecond);
}  // namespace

int main(int argc, char** argv)
{
  for (const std::string& target : simdTargets())
    benchmark::RegisterBenchmark(("BM_InflationTarget_" + target).c_str(),
                                 [target](benchmark::State& s) { inflationOnTarget(s, target); })
        ->Args({550, 10})
        ->Args({1000, 3})
        ->Args({3000, 3})
        ->ComputeStatistics("min", &costmap_layers::minOf)
        ->Unit(benchmark::kMillisecond);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  // COSTMAP_LAYERS_BENCH_TARGET=AVX3 (a name simdTargets() lists): every benchmark on that target, so
  // that two targets can be compared by the same binary in the same minutes.
  if (const char* forced = std::getenv("COSTMAP_LAYERS_BENCH_TARGET"); forced != nullptr && *forced != '\0')
    if (!setSimdTarget(forced))
    {
      std::fprintf(stderr, "COSTMAP_LAYERS_BENCH_TARGET=%s: not a target this build compiled and this CPU runs\n",
                   forced);
      return 1;
    }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
