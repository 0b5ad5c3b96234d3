// How a run of repeated timings is summarised, in one place: costmap_tool --repeat reports the median
// and the minimum of its timed updates with these, and the benchmarks in bench/ add the same minimum
// (and a median by the same rule) to Google Benchmark's repetition statistics, so that both speak of
// the same numbers. std only.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <vector>

namespace costmap_layers
{
/// The median of the values (the mean of the two middle ones for an even count); 0 for none.
inline double medianOf(std::vector<double> values)
{
  if (values.empty()) return 0.0;
  const std::size_t n = values.size();
  std::nth_element(values.begin(), values.begin() + n / 2, values.end());
  const double upper = values[n / 2];
  if (n % 2) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + n / 2));
}

/// The smallest value; 0 for none.
inline double minOf(const std::vector<double>& values)
{
  return values.empty() ? 0.0 : *std::min_element(values.begin(), values.end());
}

struct RunTimes
{
  std::vector<double> ms;  ///< each timed run [ms]
  double median_ms() const { return medianOf(ms); }
  double min_ms() const { return minOf(ms); }
};

/// Runs fn(k) for k = 0 .. warm_ups + runs - 1 and times each call on the steady clock; the first
/// warm_ups calls are not kept.
template <class Fn>
RunTimes timeRuns(int warm_ups, int runs, Fn&& fn)
{
  using Clock = std::chrono::steady_clock;
  RunTimes t;
  t.ms.reserve(static_cast<std::size_t>(std::max(runs, 0)));
  for (int k = 0; k < warm_ups + runs; ++k)
  {
    const auto t0 = Clock::now();
    fn(k);
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    if (k >= warm_ups) t.ms.push_back(ms);
  }
  return t;
}
}  // namespace costmap_layers
