// DenoiseLayer's pass (issue 37) on random salt-and-pepper grids of 1000x1000 and 4000x4000 cells at
// 5 % and 30 % lethal cells, each next to a memcpy of the same grid measured in the same run (the
// machines are shared: compare ratios, not absolute times). Arguments: side [cells], density [%].
// Run with scripts/bench.sh.
#include <benchmark/benchmark.h>

#include "bench_stats.hpp"

#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/layers/denoise_layer.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;

namespace
{
std::vector<uint8_t> noisyGrid(int side, int density_percent)
{
  std::mt19937 rng(static_cast<unsigned>(side * 100 + density_percent));
  std::bernoulli_distribution lethal(density_percent / 100.0);
  std::vector<uint8_t> g(static_cast<std::size_t>(side) * static_cast<std::size_t>(side));
  for (auto& c : g)
    c = lethal(rng) ? LETHAL_OBSTACLE : FREE_SPACE;
  return g;
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

/// The remover alone on the whole grid; the noisy grid is restored outside the timing.
void removeGroups(benchmark::State& state, int minimal_group_size, bool eight)
{
  const int side = static_cast<int>(state.range(0));
  const std::vector<uint8_t> source = noisyGrid(side, static_cast<int>(state.range(1)));
  std::vector<uint8_t> work = source;
  ObstacleGroupRemover remover;
  ObstacleGroupRemover::Rule rule;
  rule.minimal_group_size = minimal_group_size;
  rule.eight_connected = eight;
  std::size_t cleared = 0;
  for (auto _ : state)
  {
    state.PauseTiming();
    std::memcpy(work.data(), source.data(), source.size());
    state.ResumeTiming();
    cleared = remover.remove(work.data(), static_cast<std::size_t>(side), 0, 0, side, side, rule);
    benchmark::DoNotOptimize(work.data());
    benchmark::ClobberMemory();
  }
  state.SetLabel(std::to_string(cleared) + " cells cleared");
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(source.size()));
}

/// Nav2's defaults: minimal_group_size 2, 8-connected.
void BM_Denoise8Size2(benchmark::State& state)
{
  removeGroups(state, 2, true);
}
void BM_Denoise4Size2(benchmark::State& state)
{
  removeGroups(state, 2, false);
}
void BM_Denoise8Size5(benchmark::State& state)
{
  removeGroups(state, 5, true);
}

/// The whole layer in a LayeredCostmap with the grid below it: what a costmap cycle pays for it on top
/// of the layer that wrote the grid (here a copy of the noisy grid, the master's reset included).
class CopyLayer : public Layer
{
public:
  explicit CopyLayer(const std::vector<uint8_t>& g) : g_(g) {}
  void updateBounds(double, double, double, double* min_x, double* min_y, double* max_x, double* max_y) override
  {
    *min_x = -1e9;
    *min_y = -1e9;
    *max_x = 1e9;
    *max_y = 1e9;
  }
  void updateCosts(Costmap2D& master, int, int, int, int) override { std::memcpy(master.data(), g_.data(), g_.size()); }

private:
  const std::vector<uint8_t>& g_;
};

void layerUpdate(benchmark::State& state, bool with_denoise)
{
  const int side = static_cast<int>(state.range(0));
  const std::vector<uint8_t> source = noisyGrid(side, static_cast<int>(state.range(1)));
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(static_cast<unsigned>(side), static_cast<unsigned>(side), 0.05, 0.0, 0.0);
  lc.addPlugin(std::make_shared<CopyLayer>(source));
  if (with_denoise)
  {
    auto denoise = std::make_shared<DenoiseLayer>();
    denoise->initialize(&lc, "denoise", std::make_shared<FakeContext>());
    lc.addPlugin(denoise);
  }
  for (auto _ : state)
  {
    lc.updateMap(1.0, 1.0, 0.0);
    benchmark::DoNotOptimize(lc.getCostmap().data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(source.size()));
}
void BM_CycleWithoutDenoise(benchmark::State& state)
{
  layerUpdate(state, false);
}
void BM_CycleWithDenoise(benchmark::State& state)
{
  layerUpdate(state, true);
}

void gridArgs(benchmark::internal::Benchmark* b)
{
  for (int side : {1000, 4000})
    for (int density : {5, 30})
      b->Args({side, density});
}
}  // namespace

COSTMAP_BENCH(BM_Memcpy)->Apply(gridArgs)->Unit(benchmark::kMillisecond);
COSTMAP_BENCH(BM_Denoise8Size2)->Apply(gridArgs)->Unit(benchmark::kMillisecond);
COSTMAP_BENCH(BM_Denoise4Size2)->Apply(gridArgs)->Unit(benchmark::kMillisecond);
COSTMAP_BENCH(BM_Denoise8Size5)->Apply(gridArgs)->Unit(benchmark::kMillisecond);
COSTMAP_BENCH(BM_CycleWithoutDenoise)->Apply(gridArgs)->Unit(benchmark::kMillisecond);
COSTMAP_BENCH(BM_CycleWithDenoise)->Apply(gridArgs)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
