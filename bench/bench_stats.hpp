// Every benchmark here registers through COSTMAP_BENCH: Google Benchmark's repetitions then also
// report "min", computed by the same code as costmap_tool --repeat's update_ms_min
// (costmap_layers/tool/run_timing.hpp), next to its own mean and median.
#pragma once

#include <benchmark/benchmark.h>

#include "costmap_layers/tool/run_timing.hpp"

#define COSTMAP_BENCH(fn) BENCHMARK(fn)->ComputeStatistics("min", &costmap_layers::minOf)
