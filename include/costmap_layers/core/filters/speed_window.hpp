// The odometry speed window of SpeedFilter's path lookahead: the forward speeds of the last 0.3 s,
// averaged as Nav2's odometry smoother does.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>

namespace costmap_layers
{
/// The samples of the last kWindowNs, oldest first. Not thread-safe: SpeedFilter guards it with its
/// motion mutex (odometry arrives on an input thread, the mean is taken on the update thread).
class OdometrySpeedWindow
{
public:
  static constexpr uint64_t kWindowNs = 300'000'000;  ///< Nav2's odometry smoother averages 0.3 s
  /// A bound on memory should odometry arrive faster than the window drains (20 samples per ms).
  static constexpr std::size_t kMaxSamples = 1000;

  bool empty() const { return samples_.empty(); }
  /// The header stamp of the newest sample [ns]; only when !empty().
  uint64_t newestStamp() const { return samples_.back().stamp_ns; }

  /// Adds a sample received at received_ns [ns, the node's clock], then drops the samples received
  /// more than kWindowNs before it (the newest always stays) and any beyond kMaxSamples.
  void add(uint64_t received_ns, uint64_t stamp_ns, double linear_x);
  void clear() { samples_.clear(); }

  struct Mean
  {
    std::size_t samples = 0;          ///< 0: no odometry
    uint64_t newest_received_ns = 0;  ///< when the newest sample came [ns]
    double linear_x = 0.0;            ///< [m/s], signed
  };
  /// The mean linear_x of the samples received within kWindowNs of the newest one.
  Mean mean() const;

private:
  struct Sample
  {
    uint64_t received_ns;
    uint64_t stamp_ns;
    double linear_x;
  };
  std::deque<Sample> samples_;
};
}  // namespace costmap_layers
