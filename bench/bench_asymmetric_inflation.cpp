// AsymmetricInflationLayer (issue 37) on random grids of 1000x1000 and 4000x4000 cells of 0.05 m at 1 %
// and 5 % lethal cells, with a winding plan across the grid (one pose per 5 cm, as a grid planner gives),
// inflation_radius 0.55 m, factors 3 (left) and 10 (right): the whole grid in one update. Next to it, the
// InflationLayer alone with factor 10 (the symmetric first pass) and a memcpy of the same grid, measured
// in the same run (the machines are shared: compare ratios, not absolute times). Arguments: side
// [cells], density [%]. Run with scripts/bench.sh.
#include <benchmark/benchmark.h>

#include "bench_stats.hpp"

#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/layers/asymmetric_inflation_layer.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;

namespace
{
constexpr double kResolution = 0.05;

std::vector<uint8_t> randomGrid(int side, int density_percent)
{
  std::mt19937 rng(static_cast<unsigned>(side * 100 + density_percent));
  std::bernoulli_distribution lethal(density_percent / 100.0);
  std::vector<uint8_t> g(static_cast<std::size_t>(side) * static_cast<std::size_t>(side));
  for (auto& c : g)
    c = lethal(rng) ? LETHAL_OBSTACLE : FREE_SPACE;
  return g;
}

/// A sine across the grid, left to right, one pose per 5 cm.
std::shared_ptr<PathData> windingPlan(int side)
{
  auto p = std::make_shared<PathData>();
  p->frame_id = "map";
  const double length = side * kResolution;
  for (double x = 0.0; x <= length; x += 0.05)
    p->poses.push_back({x, length / 2 + length / 4 * std::sin(x / length * 6.283)});
  return p;
}

void BM_Memcpy(benchmark::State& state)
{
  const auto side = static_cast<std::size_t>(state.range(0));
  std::vector<uint8_t> a(side * side, 1), b(side * side, 2);
  for (auto _ : state)
  {
    std::memcpy(b.data(), a.data(), a.size());
    benchmark::DoNotOptimize(b.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(a.size()));
}

/// One whole-grid update of `layer`; the grid is restored outside the timing.
template <class L>
void inflate(benchmark::State& state, const ParamValue& params, bool with_plan)
{
  const int side = static_cast<int>(state.range(0));
  const std::vector<uint8_t> source = randomGrid(side, static_cast<int>(state.range(1)));
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(static_cast<unsigned>(side), static_cast<unsigned>(side), kResolution, 0.0, 0.0);
  lc.setFootprint({{-0.2, -0.2}, {0.2, -0.2}, {0.2, 0.2}, {-0.2, 0.2}});
  auto ctx = std::make_shared<FakeContext>(params);
  auto layer = std::make_shared<L>();
  layer->initialize(&lc, "inflation", ctx);
  ctx->bind(*layer);
  if (with_plan) ctx->publishPath(*windingPlan(side));
  Costmap2D& grid = lc.getCostmap();
  for (auto _ : state)
  {
    state.PauseTiming();
    std::memcpy(grid.data(), source.data(), source.size());
    state.ResumeTiming();
    double a = 0, b = 0, c = 0, d = 0;
    layer->reset();  // the whole grid, every time
    layer->updateBounds(-1e3, -1e3, 0.0, &a, &b, &c, &d);
    layer->updateCosts(grid, 0, 0, side, side);
    benchmark::DoNotOptimize(grid.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(source.size()));
}

void BM_SymmetricInflation(benchmark::State& state)
{
  ParamValue p = ParamValue::makeMap();
  p.set("inflation_radius", ParamValue::makeDouble(0.55));
  p.set("cost_scaling_factor", ParamValue::makeDouble(10.0));
  inflate<InflationLayer>(state, p, false);
}
void BM_AsymmetricInflation(benchmark::State& state)
{
  ParamValue p = ParamValue::makeMap();
  p.set("inflation_radius", ParamValue::makeDouble(0.55));
  p.set("cost_scaling_factor_left", ParamValue::makeDouble(3.0));
  p.set("cost_scaling_factor_right", ParamValue::makeDouble(10.0));
  inflate<AsymmetricInflationLayer>(state, p, true);
}

void gridArgs(benchmark::internal::Benchmark* b)
{
  for (int side : {1000, 4000})
    for (int density : {1, 5})
      b->Args({side, density});
}
}  // namespace

COSTMAP_BENCH(BM_Memcpy)->Apply(gridArgs)->Unit(benchmark::kMillisecond);
COSTMAP_BENCH(BM_SymmetricInflation)->Apply(gridArgs)->Unit(benchmark::kMillisecond);
COSTMAP_BENCH(BM_AsymmetricInflation)->Apply(gridArgs)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
