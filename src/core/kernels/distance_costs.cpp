// The distance engine's cost table (DistanceCosts, see distance_transform.hpp): the cost of every
// squared distance up to the reach, looked up instead of computed per cell, and the byte tables the
// SIMD kernels read (dt::Job).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "costmap_layers/core/kernels/distance_transform.hpp"
#include "src/core/kernels/distance_job.hpp"

namespace costmap_layers
{
namespace
{
/// Squared distances above this are costed through the function, not a table.
constexpr uint64_t kMaxTable = uint64_t{1} << 20;
}  // namespace

DistanceCosts::DistanceCosts(int64_t max_cells, const std::function<uint8_t(uint64_t)>& cost) : cost_(cost)
{
  if (max_cells < 0) throw std::invalid_argument("DistanceCosts: max_cells must be >= 0");
  const uint64_t max_sq = static_cast<uint64_t>(max_cells) * static_cast<uint64_t>(max_cells);
  if (cost(0) == 0) return;
  any_ = true;
  // The reach: the largest d2 <= max_sq with a cost above 0 (the cost does not increase).
  uint64_t lo = 0, hi = max_sq;
  while (lo < hi)
  {
    const uint64_t mid = lo + (hi - lo + 1) / 2;
    if (cost(mid) > 0)
      lo = mid;
    else
      hi = mid - 1;
  }
  reach_sq_ = lo;
  reach_ = static_cast<int64_t>(std::sqrt(static_cast<double>(reach_sq_)));
  while (static_cast<uint64_t>(reach_) * static_cast<uint64_t>(reach_) < reach_sq_)
    ++reach_;
  while (reach_ > 0 && static_cast<uint64_t>(reach_ - 1) * static_cast<uint64_t>(reach_ - 1) >= reach_sq_)
    --reach_;
  const uint64_t entries = std::min(reach_sq_ + 1, kMaxTable);
  table_.resize(static_cast<std::size_t>(entries));
  for (uint64_t d2 = 0; d2 < entries; ++d2)
  {
    table_[d2] = cost(d2);
    if (d2 > 0 && table_[d2] > table_[d2 - 1])
      throw std::invalid_argument("DistanceCosts: the cost increases at squared distance " + std::to_string(d2));
  }
  if (reach_ <= dt::kMaxBandedReach)
  {
    table16_.assign(65536 + 3, 0);  // 3 bytes of slack: the engine gathers 32-bit words
    std::copy(table_.begin(), table_.end(), table16_.begin());
  }
  if (reach_ >= dt::kMinWideReach && reach_ <= dt::kMaxWideReach)
  {
    wide_tables_.resize(static_cast<std::size_t>(reach_ + 1));
    for (int64_t dx = 0; dx <= reach_; ++dx)
      for (int64_t v = 0; v < 128; ++v)
        wide_tables_[static_cast<std::size_t>(dx)].cost[v] = at(static_cast<uint64_t>(dx * dx + v * v));
  }
  if (reach_ >= dt::kMinPaintReach && reach_ <= dt::kMaxPaintReach)
  {
    // Entry k of row v: the column at paint_center_ seen from k; the engine reads one vector (up to
    // kMaxLanes) from center + x - c for c - x in [-reach, kMaxLanes - 1 + reach].
    paint_center_ = static_cast<int>(2 * dt::kMaxLanes + reach_);
    paint_shift_ = 6;
    while ((int64_t{1} << paint_shift_) < 3 * dt::kMaxLanes + 2 * reach_)
      ++paint_shift_;
    const int64_t paint_stride = int64_t{1} << paint_shift_;
    paint_tables_.assign(static_cast<std::size_t>(paint_stride * (reach_ + 1)), 0);
    for (int64_t v = 0; v <= reach_; ++v)
      for (int64_t k = 0; k < paint_stride; ++k)
      {
        const int64_t dx = k - paint_center_;
        if (dx * dx <= static_cast<int64_t>(reach_sq_))
          paint_tables_[static_cast<std::size_t>(v * paint_stride + k)] = at(static_cast<uint64_t>(dx * dx + v * v));
      }
  }
  if (reach_ <= dt::kMaxCostDomainReach)
  {
    const int64_t k_count = dt::tablesPerOffset(static_cast<int>(reach_));
    offset_tables_.assign(static_cast<std::size_t>(16 * k_count * (reach_ + 1)), 0);
    for (int64_t dx = 0; dx <= reach_; ++dx)
      for (int64_t k = 0; k < k_count; ++k)
        for (int64_t j = 0; j < 16; ++j)
        {
          const int64_t v = 16 * k + j;
          offset_tables_[static_cast<std::size_t>(16 * (k_count * dx + k) + j)] =
              at(static_cast<uint64_t>(dx * dx + v * v));
        }
  }
}

uint8_t DistanceCosts::at(uint64_t d2) const
{
  if (!any_ || d2 > reach_sq_) return 0;
  if (d2 < table_.size()) return table_[d2];
  return cost_(d2);
}
}  // namespace costmap_layers
