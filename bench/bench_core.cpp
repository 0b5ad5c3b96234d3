// Core benchmarks on a 4000x4000 grid, each next to a memcpy of the same grid measured in the same
// run (the machines are shared: compare ratios, not absolute times). Run with scripts/bench.sh.
#include <benchmark/benchmark.h>

#include "bench_stats.hpp"

#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/costmap/costmap_layer.hpp"
#include "costmap_layers/core/layers/gradient_layer.hpp"
#include "costmap_layers/core/filters/keepout_filter.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;

namespace
{
constexpr unsigned kSize = 4000;

/// A CostmapLayer whose own grid is filled once with random costs (a quarter of them unknown).
class FilledLayer : public CostmapLayer
{
public:
  void updateBounds(double, double, double, double*, double*, double*, double*) override {}
  void updateCosts(Costmap2D& master, int min_i, int min_j, int max_i, int max_j) override
  {
    updateWithMax(master, min_i, min_j, max_i, max_j);
  }
  void fillRandom()
  {
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> cost(0, 255);
    uint8_t* d = costmap_.data();
    for (std::size_t k = 0; k < costmap_.cellCount(); ++k)
      d[k] = static_cast<uint8_t>(cost(rng));
  }
};

void BM_Memcpy(benchmark::State& state)
{
  std::vector<uint8_t> a(kSize * kSize, 1), b(kSize * kSize, 2);
  for (auto _ : state)
  {
    std::memcpy(b.data(), a.data(), a.size());
    benchmark::DoNotOptimize(b.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(a.size()));
}

void BM_GradientFullUpdate(benchmark::State& state)
{
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(kSize, kSize, 0.05, 0.0, 0.0);
  auto layer = std::make_shared<GradientLayer>();
  layer->initialize(&lc, "gradient", std::make_shared<FakeContext>());
  lc.addPlugin(layer);
  for (auto _ : state)
  {
    layer->onFootprintChanged();  // asks for the whole map again
    lc.updateMap(100.0, 100.0, 0.0);
    benchmark::DoNotOptimize(lc.getCostmap().data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * kSize * kSize);
}

void BM_UpdateWithMax(benchmark::State& state)
{
  LayeredCostmap lc("map", false, true);
  lc.resizeMap(kSize, kSize, 0.05, 0.0, 0.0);
  auto layer = std::make_shared<FilledLayer>();
  layer->initialize(&lc, "filled", std::make_shared<FakeContext>());
  lc.addPlugin(layer);
  layer->matchSize();
  layer->fillRandom();
  Costmap2D master(kSize, kSize, 0.05, 0.0, 0.0, 100);
  for (auto _ : state)
  {
    layer->updateWithMax(master, 0, 0, kSize, kSize);
    benchmark::DoNotOptimize(master.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * kSize * kSize);
}

/// KeepoutFilter over the whole master grid with a mask of the same resolution, or of another
/// resolution and offset (state.range(0) == 1).
void BM_KeepoutFilter(benchmark::State& state)
{
  const bool other_resolution = state.range(0) == 1;
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(kSize, kSize, 0.05, 0.0, 0.0);
  auto ctx = std::make_shared<FakeContext>();
  auto filter = std::make_shared<KeepoutFilter>();
  filter->initialize(&lc, "keepout", ctx);
  ctx->bind(*filter);
  lc.addFilter(filter);
  filter->matchSize();
  auto mask = std::make_shared<OccupancyGridData>();
  mask->frame_id = "map";
  mask->resolution = other_resolution ? 0.07 : 0.05;
  mask->origin_x = other_resolution ? -1.33 : -2.0;
  mask->origin_y = other_resolution ? -0.71 : -1.0;
  mask->width = static_cast<uint32_t>(210.0 / mask->resolution);
  mask->height = static_cast<uint32_t>(210.0 / mask->resolution);
  mask->data.resize(static_cast<std::size_t>(mask->width) * mask->height);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> v(-1, 100);
  for (auto& c : mask->data)
    c = static_cast<int8_t>(v(rng) < 60 ? 0 : v(rng));
  filter->setMask(mask);
  Costmap2D master(kSize, kSize, 0.05, 0.0, 0.0, 0);
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  filter->updateBounds(100, 100, 0, &x0, &y0, &x1, &y1);
  for (auto _ : state)
  {
    filter->updateCosts(master, 0, 0, kSize, kSize);
    benchmark::DoNotOptimize(master.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * kSize * kSize);
}
}  // namespace

COSTMAP_BENCH(BM_Memcpy)->Unit(benchmark::kMillisecond);
COSTMAP_BENCH(BM_GradientFullUpdate)->Unit(benchmark::kMillisecond);
COSTMAP_BENCH(BM_UpdateWithMax)->Unit(benchmark::kMillisecond);
COSTMAP_BENCH(BM_KeepoutFilter)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
