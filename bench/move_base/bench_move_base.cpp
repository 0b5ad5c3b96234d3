// The move_base bridge's overhead per update: a GradientLayer hosted in costmap_2d through LayerBridge
// (updateBounds + updateCosts on costmap_2d's master) against the same core layer updating the same
// window of a grid it owns, each next to a memcpy of the window, all three timed in turn in the same
// iterations (the machines are shared: the counters compare figures taken side by side).
// overhead_x_memcpy = (bridge - direct) / memcpy of the window: the target is <= 1.
// Needs a ROS master (the bridge reads its parameters from it): scripts/bench.sh starts one.
#include <benchmark/benchmark.h>
#include <costmap_2d/layered_costmap.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>

#include <chrono>
#include <cstring>
#include <memory>
#include <vector>

#include "costmap_layers/core/layers/gradient_layer.hpp"
#include "costmap_layers/core/costmap/layer_context.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/move_base/layer_bridge.hpp"

namespace
{
constexpr unsigned kMaster = 2048;

/// What a core layer needs outside ROS: no parameters (the defaults), no transforms.
class BenchContext : public costmap_layers::LayerContext
{
public:
  const costmap_layers::ParamValue& params() const override { return params_; }
  const std::string& globalFrame() const override { return frame_; }
  double transformTolerance() const override { return 0.3; }
  std::optional<costmap_layers::Transform2D> lookupTransform(const std::string&, const std::string&,
                                                             std::string* error) override
  {
    if (error) *error = "no transforms here";
    return std::nullopt;
  }
  uint64_t nowNs() const override { return 0; }
  void report(costmap_layers::Severity, const std::string&, const std::string&) override {}

private:
  costmap_layers::ParamValue params_ = costmap_layers::ParamValue::makeMap();
  std::string frame_ = "map";
};

double seconds(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

void BM_MoveBaseBridgeOverhead(benchmark::State& state)
{
  const int side = static_cast<int>(state.range(0));
  // Inside costmap_2d, as move_base runs it.
  costmap_2d::LayeredCostmap lc("map", false, false);
  lc.resizeMap(kMaster, kMaster, 0.05, 0.0, 0.0);
  tf2_ros::Buffer tf;
  auto bridge = std::make_shared<costmap_layers::move_base::LayerBridge>(
      std::make_shared<costmap_layers::GradientLayer>(), "GradientLayer");
  bridge->initialize(&lc, "bench_costmap/gradient", &tf);
  // The same core layer on a grid of its own.
  costmap_layers::LayeredCostmap own("map", false, false);
  own.resizeMap(kMaster, kMaster, 0.05, 0.0, 0.0);
  auto direct = std::make_shared<costmap_layers::GradientLayer>();
  direct->initialize(&own, "gradient", std::make_shared<BenchContext>());
  own.addPlugin(direct);
  // A memcpy of the window, row by row as a window is laid out in the grid.
  std::vector<uint8_t> from(static_cast<std::size_t>(kMaster) * kMaster, 1), to(from.size(), 2);

  const int x0 = 100, y0 = 100, xn = x0 + side, yn = y0 + side;
  double t_bridge = 0, t_direct = 0, t_memcpy = 0;
  for (auto _ : state)
  {
    double a0 = 1e30, b0 = 1e30, a1 = -1e30, b1 = -1e30;
    auto t0 = std::chrono::steady_clock::now();
    bridge->updateBounds(1.0, 1.0, 0.0, &a0, &b0, &a1, &b1);
    bridge->updateCosts(*lc.getCostmap(), x0, y0, xn, yn);
    benchmark::DoNotOptimize(lc.getCostmap()->getCharMap());
    auto t1 = std::chrono::steady_clock::now();
    double c0 = 1e30, d0 = 1e30, c1 = -1e30, d1 = -1e30;
    direct->updateBounds(1.0, 1.0, 0.0, &c0, &d0, &c1, &d1);
    direct->updateCosts(own.getCostmap(), x0, y0, xn, yn);
    benchmark::DoNotOptimize(own.getCostmap().data());
    auto t2 = std::chrono::steady_clock::now();
    for (int y = y0; y < yn; ++y)
      std::memcpy(to.data() + static_cast<std::size_t>(y) * kMaster + x0,
                  from.data() + static_cast<std::size_t>(y) * kMaster + x0, static_cast<std::size_t>(side));
    benchmark::DoNotOptimize(to.data());
    benchmark::ClobberMemory();
    auto t3 = std::chrono::steady_clock::now();
    t_bridge += seconds(t0, t1);
    t_direct += seconds(t1, t2);
    t_memcpy += seconds(t2, t3);
    state.SetIterationTime(seconds(t0, t1));
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["bridge_us"] = t_bridge / n * 1e6;
  state.counters["direct_us"] = t_direct / n * 1e6;
  state.counters["memcpy_us"] = t_memcpy / n * 1e6;
  state.counters["overhead_x_memcpy"] = (t_bridge - t_direct) / t_memcpy;
  // Both wrote the same pattern into the same window: the bridge wrote into costmap_2d's grid.
  const uint8_t* a = lc.getCostmap()->getCharMap();
  const uint8_t* b = own.getCostmap().data();
  for (int y = y0; y < yn; ++y)
    if (std::memcmp(a + static_cast<std::size_t>(y) * kMaster + x0, b + static_cast<std::size_t>(y) * kMaster + x0,
                    static_cast<std::size_t>(side)) != 0)
    {
      state.SkipWithError("the bridge's window differs from the core layer's");
      break;
    }
}
BENCHMARK(BM_MoveBaseBridgeOverhead)->Arg(32)->Arg(128)->Arg(512)->Arg(1536)->UseManualTime();
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "bench_move_base", ros::init_options::AnonymousName | ros::init_options::NoSigintHandler);
  if (!ros::master::check())
  {
    std::fprintf(stderr, "bench_move_base: no ROS master at %s (scripts/bench.sh starts one)\n",
                 ros::master::getURI().c_str());
    return 1;
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
