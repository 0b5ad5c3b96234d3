// Filter benchmarks on 4000x4000 grids, each next to a memcpy of the same grid measured in the same
// run (the machines are shared: compare ratios, not absolute times). Run with scripts/bench.sh.
//  - BM_LanesRecompute: what LanesFilter does once per new mask (distance transform from the lane
//    cells, costs per mask cell), for a grid of lanes, with lane_border_width 0.5 m (Arg 50: a band of
//    10 cells, 8-bit engine) and 1.5 m (Arg 150: 30 cells, 16-bit engine), at 5 cm.
//  - BM_LanesFullUpdate: a LanesFilter update over the whole 4000x4000 master, costs already computed.
//  - BM_SpeedMaskArrives: what a republished 4000x4000 speed mask costs the update loop: the mask
//    handed over, then one update cycle of the filter (bounds and costs: SpeedFilter writes nothing).
#include <benchmark/benchmark.h>

#include "bench_stats.hpp"

#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "costmap_layers/core/filters/lanes_filter.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/filters/speed_filter.hpp"
#include "costmap_layers/core/zones/zone_shapes.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;

namespace
{
constexpr unsigned kSize = 4000;
constexpr double kRes = 0.05;

/// Makes the per-mask computation callable from the benchmark.
class BenchLanesFilter : public LanesFilter
{
public:
  std::size_t recompute(const OccupancyGridData& mask, std::vector<uint8_t>& costs)
  {
    return computeCosts(mask, costs);
  }
};

/// A warehouse-like grid of lanes: 1 m wide lanes every 5 m in both directions, forbidden elsewhere,
/// with a few "no opinion" blocks and soft patches.
std::shared_ptr<OccupancyGridData> laneGridMask()
{
  auto m = std::make_shared<OccupancyGridData>();
  m->frame_id = "map";
  m->width = kSize;
  m->height = kSize;
  m->resolution = kRes;
  m->data.resize(static_cast<std::size_t>(kSize) * kSize);
  for (unsigned y = 0; y < kSize; ++y)
    for (unsigned x = 0; x < kSize; ++x)
    {
      int8_t v = 100;
      if (x % 100 < 20 || y % 100 < 20)
        v = 0;
      else if (x % 400 >= 40 && x % 400 < 80 && y % 400 >= 40 && y % 400 < 80)
        v = -1;
      else if (x % 300 >= 50 && x % 300 < 60 && y % 300 >= 50 && y % 300 < 60)
        v = 60;
      m->data[static_cast<std::size_t>(y) * kSize + x] = v;
    }
  return m;
}

ParamValue lanesParams(double width)
{
  ParamValue p = ParamValue::makeMap();
  p.set("lane_border_width", ParamValue::makeDouble(width));
  return p;
}

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

void BM_LanesRecompute(benchmark::State& state)
{
  LayeredCostmap lc("map", false, false);
  auto filter = std::make_shared<BenchLanesFilter>();
  filter->initialize(&lc, "lanes", std::make_shared<FakeContext>(lanesParams(state.range(0) / 100.0)));
  const auto mask = laneGridMask();
  std::vector<uint8_t> costs;
  filter->recompute(*mask, costs);  // grow the buffers once, as a running filter has
  for (auto _ : state)
  {
    benchmark::DoNotOptimize(filter->recompute(*mask, costs));
    benchmark::DoNotOptimize(costs.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * kSize * kSize);
}

void BM_LanesFullUpdate(benchmark::State& state)
{
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(kSize, kSize, kRes, 0.0, 0.0);
  auto ctx = std::make_shared<FakeContext>(lanesParams(0.5));
  auto filter = std::make_shared<LanesFilter>();
  filter->initialize(&lc, "lanes", ctx);
  ctx->bind(*filter);
  lc.addFilter(filter);
  filter->setMask(laneGridMask());
  Costmap2D master(kSize, kSize, kRes, 0.0, 0.0, 0);
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  filter->updateBounds(100, 100, 0, &x0, &y0, &x1, &y1);
  filter->updateCosts(master, 0, 0, kSize, kSize);  // the costs of this mask, computed once
  for (auto _ : state)
  {
    filter->updateCosts(master, 0, 0, kSize, kSize);
    benchmark::DoNotOptimize(master.data());
    benchmark::ClobberMemory();
  }
  if (filter->costComputations() != 1) state.SkipWithError("costs were recomputed during updates");
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * kSize * kSize);
}
void BM_SpeedMaskArrives(benchmark::State& state)
{
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(kSize, kSize, kRes, 0.0, 0.0);
  auto ctx = std::make_shared<FakeContext>(ParamValue::makeMap());
  auto filter = std::make_shared<SpeedFilter>();
  filter->initialize(&lc, "speed", ctx);
  ctx->bind(*filter);
  lc.addFilter(filter);
  // Areas 1..4 in quarters of the map.
  auto mask = std::make_shared<OccupancyGridData>();
  mask->frame_id = "map";
  mask->width = kSize;
  mask->height = kSize;
  mask->resolution = kRes;
  mask->data.resize(static_cast<std::size_t>(kSize) * kSize);
  for (unsigned y = 0; y < kSize; ++y)
    for (unsigned x = 0; x < kSize; ++x)
      mask->data[static_cast<std::size_t>(y) * kSize + x] =
          static_cast<int8_t>(1 + (x >= kSize / 2) + 2 * (y >= kSize / 2));
  Costmap2D& master = lc.getCostmap();
  bool redraw = false;
  for (auto _ : state)
  {
    filter->setMask(mask);
    double x0 = 1e30, y0 = 1e30, x1 = -1e30, y1 = -1e30;
    filter->updateBounds(50.0, 50.0, 0.0, &x0, &y0, &x1, &y1);
    redraw = redraw || x0 <= x1;
    filter->updateCosts(master, 0, 0, 0, 0);
    benchmark::ClobberMemory();
  }
  if (redraw) state.SkipWithError("a new speed mask asked for a redraw");
}
/// zone_server's work for one handle drag at the limit of vertex pairs (limits::kMaxZoneVertexPairs:
/// 20 polygons of 1000 vertices, 0.05 m/cell): the checked edit, then the mask drawn.
void BM_ZoneDragAtTheLimit(benchmark::State& state)
{
  ZoneLayout layout;
  layout.resolution = 0.05;
  for (int k = 0; k < 20; ++k)
  {
    ZoneShape s;
    s.name = "p" + std::to_string(k);
    for (int v = 0; v < 1000; ++v)
      s.points.push_back({3.0 * k + std::cos(2.0 * M_PI * v / 1000), std::sin(2.0 * M_PI * v / 1000)});
    layout.shapes.push_back(s);
  }
  ZoneSet set(layout);
  std::size_t drags = 0;
  for (auto _ : state)
  {
    const double dx = (drags++ % 2) ? 0.0 : 0.2;
    if (!set.moveHandle("p7", 0, 22.0 + dx, 0.0).ok()) state.SkipWithError("the drag was refused");
    benchmark::DoNotOptimize(set.rasterize().data.data());
  }
}
}  // namespace

COSTMAP_BENCH(BM_ZoneDragAtTheLimit)->Unit(benchmark::kMillisecond);
COSTMAP_BENCH(BM_SpeedMaskArrives)->Unit(benchmark::kMillisecond);
COSTMAP_BENCH(BM_Memcpy)->Unit(benchmark::kMillisecond);
COSTMAP_BENCH(BM_LanesRecompute)->Arg(50)->Arg(150)->Unit(benchmark::kMillisecond);
COSTMAP_BENCH(BM_LanesFullUpdate)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
