#include "costmap_layers/core/layers/denoise_layer.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/grid/costmap_2d.hpp"

// Which cells of a row are obstacles, as bits: written once with Highway (foreach_target.h compiles it
// per target; HWY_DYNAMIC_DISPATCH picks one at run time), as the distance engine's kernels are.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/core/layers/denoise_layer.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace costmap_layers
{
namespace HWY_NAMESPACE
{
namespace hn = hwy::HWY_NAMESPACE;

/// Bit k % 8 of bits[k / 8] set when p[k] is an obstacle code (253, 254 and, with span 3, 255), for
/// k < n; the other bits of the last byte are zero. bits has room for (n + 7) / 8 bytes.
void ObstacleBits(const uint8_t* HWY_RESTRICT p, std::size_t n, uint8_t span, uint8_t* HWY_RESTRICT bits)
{
  const hn::ScalableTag<uint8_t> d;
  const std::size_t N = hn::Lanes(d);
  std::size_t k = 0;
  if (N % 8 == 0)  // whole bytes of mask bits per vector (not the one-lane scalar target)
  {
    // x = v + 3 wraps 253, 254, 255 to 0, 1, 2: an obstacle is x <= span - 1, i.e. min(x, span - 1) == x.
    const auto three = hn::Set(d, 3), top = hn::Set(d, static_cast<uint8_t>(span - 1));
    for (; k + N <= n; k += N)
    {
      const auto x = hn::Add(hn::LoadU(d, p + k), three);
      hn::StoreMaskBits(d, hn::Eq(hn::Min(x, top), x), bits + k / 8);
    }
  }
  if (k < n) std::memset(bits + k / 8, 0, (n + 7) / 8 - k / 8);
  for (; k < n; ++k)
    bits[k / 8] |= static_cast<uint8_t>((static_cast<uint8_t>(p[k] - INSCRIBED_INFLATED_OBSTACLE) < span) << (k % 8));
}
}  // namespace HWY_NAMESPACE
}  // namespace costmap_layers
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace costmap_layers
{
HWY_EXPORT(ObstacleBits);

DenoiseConfig parseDenoiseConfig(const ParamReader& params)
{
  DenoiseConfig cfg;
  cfg.minimal_group_size =
      params.getInt("minimal_group_size", cfg.minimal_group_size, 0, std::numeric_limits<int32_t>::max());
  cfg.group_connectivity_type = params.getInt("group_connectivity_type", cfg.group_connectivity_type, 4, 8);
  // Nav2 falls back to 8 with a warning; a typo here would silently change which cells form a group.
  if (cfg.group_connectivity_type != 4 && cfg.group_connectivity_type != 8)
    params.fail("group_connectivity_type", "must be 4 or 8");
  return cfg;
}

void DenoiseLayer::onInitialize()
{
  config_ = parseDenoiseConfig(ParamReader(context_->params(), name_));
}

void DenoiseLayer::onReconfigure(const ParamValue& params)
{
  config_ = parseDenoiseConfig(ParamReader(params, name_));  // throws before anything changes
}

std::vector<ParamSpec> DenoiseLayer::tunableLayerParameters(const ParamValue& params) const
{
  return recordParameters(params, name_, [](const ParamReader& r) { parseDenoiseConfig(r); });
}

void DenoiseLayer::updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j)
{
  current_ = true;
  min_i = std::max(min_i, 0);
  min_j = std::max(min_j, 0);
  max_i = std::min(max_i, static_cast<int>(master_grid.getSizeInCellsX()));
  max_j = std::min(max_j, static_cast<int>(master_grid.getSizeInCellsY()));
  if (min_i >= max_i || min_j >= max_j) return;
  ObstacleGroupRemover::Rule rule;
  rule.minimal_group_size = config_.minimal_group_size;
  rule.eight_connected = config_.group_connectivity_type == 8;
  // Nav2's rule: with an unknown-free default (track_unknown_space false) an unknown cell is an obstacle.
  rule.unknown_is_obstacle = master_grid.getDefaultValue() != NO_INFORMATION;
  remover_.remove(master_grid.data(), master_grid.getSizeInCellsX(), min_i, min_j, max_i, max_j, rule);
}

namespace
{
/// Obstacle codes are the top of the byte range: 253, 254 and, when it counts, 255. `span` is 2 or 3.
inline bool isObstacle(uint8_t v, unsigned span)
{
  return static_cast<uint8_t>(v - INSCRIBED_INFLATED_OBSTACLE) < span;
}

/// Writes where the runs of obstacle cells of row[min_i, max_i) begin and end (alternately, in column
/// order; a run reaching max_i ends there) and returns one past the last edge written. `edge` has room
/// for max_i - min_i + 1 edges; `bits` for the row's obstacle bits, whole 64-bit words. Runs are read
/// from the bits' transitions, so that a random grid costs no mispredicted branch per cell.
int32_t* scanRow(const uint8_t* row, int min_i, int max_i, unsigned span, int32_t* edge, uint8_t* bits)
{
  int32_t* const first = edge;
  const auto n = static_cast<std::size_t>(max_i - min_i);
  HWY_DYNAMIC_DISPATCH(ObstacleBits)(row + min_i, n, static_cast<uint8_t>(span), bits);
  uint64_t carry = 0;  // whether the cell before this word is an obstacle
  for (std::size_t w = 0; 64 * w < n; ++w)
  {
    // Bytes in little-endian order, as the bits were stored (no unaligned or type-punned load).
    uint64_t m = 0;
    const std::size_t bytes = std::min<std::size_t>(8, (n - 64 * w + 7) / 8);
    for (std::size_t b = 0; b < bytes; ++b)
      m |= static_cast<uint64_t>(bits[8 * w + b]) << (8 * b);
    uint64_t flips = m ^ ((m << 1) | carry);  // a set bit: a run begins or ends there
    carry = m >> 63;
    const int i0 = min_i + static_cast<int>(64 * w);
    while (flips != 0)
    {
      *edge++ = i0 + __builtin_ctzll(flips);
      flips &= flips - 1;
    }
  }
  if ((edge - first) % 2 != 0) *edge++ = max_i;
  return edge;
}
}  // namespace

inline int32_t ObstacleGroupRemover::findRoot(int32_t r)
{
  while (parent_[r] >= 0)
  {
    const int32_t up = parent_[r];
    if (parent_[up] >= 0) parent_[r] = parent_[up];  // path halving
    r = up;
  }
  return r;
}

inline void ObstacleGroupRemover::unite(int32_t a, int32_t b, int32_t cap)
{
  a = findRoot(a);
  b = findRoot(b);
  if (a == b) return;
  if (a > b) std::swap(a, b);  // the earlier run stays the root
  // Counts are stored negated in the roots; only "reached the minimal size" matters, so they saturate.
  const int64_t total = static_cast<int64_t>(-parent_[a]) + static_cast<int64_t>(-parent_[b]);
  parent_[a] = -static_cast<int32_t>(std::min<int64_t>(total, cap));
  parent_[b] = a;
}

std::size_t ObstacleGroupRemover::removeSingles(uint8_t* cells, std::size_t stride, int min_i, int min_j, int max_i,
                                                int max_j, unsigned span, int reach)
{
  // Only runs of one cell can be groups of one: such a cell goes when no cell of the rows above and
  // below within reach is an obstacle. Clearing in place is safe: a cleared cell had no obstacle
  // neighbour, so it is nobody's neighbour.
  const std::size_t row_edges_max = static_cast<std::size_t>(max_i - min_i) + 1;
  if (edges_.size() < row_edges_max) edges_.resize(row_edges_max);
  if (bits_.size() < row_edges_max / 8 + 8) bits_.resize(row_edges_max / 8 + 8);
  std::size_t cleared = 0;
  for (int j = min_j; j < max_j; ++j)
  {
    uint8_t* row = cells + static_cast<std::size_t>(j) * stride;
    const int32_t* const end = scanRow(row, min_i, max_i, span, edges_.data(), bits_.data());
    for (const int32_t* e = edges_.data(); e != end; e += 2)
    {
      if (e[1] - e[0] != 1) continue;
      const int lo = std::max(e[0] - reach, min_i), hi = std::min(e[0] + reach, max_i - 1);
      bool alone = true;
      for (int i = lo; i <= hi; ++i)
      {
        if (j > min_j) alone = alone && !isObstacle(row[i - static_cast<std::ptrdiff_t>(stride)], span);
        if (j + 1 < max_j) alone = alone && !isObstacle(row[i + static_cast<std::ptrdiff_t>(stride)], span);
      }
      if (!alone) continue;
      row[e[0]] = FREE_SPACE;
      ++cleared;
    }
  }
  return cleared;
}

std::size_t ObstacleGroupRemover::remove(uint8_t* cells, std::size_t stride, int min_i, int min_j, int max_i, int max_j,
                                         const Rule& rule)
{
  if (rule.minimal_group_size <= 1 || min_i >= max_i || min_j >= max_j) return 0;
  const unsigned span = rule.unknown_is_obstacle ? 3u : 2u;
  const int32_t cap = rule.minimal_group_size;
  const int32_t reach = rule.eight_connected ? 1 : 0;  // runs touching at a corner join under 8
  const std::size_t row_edges_max = static_cast<std::size_t>(max_i - min_i) + 1;
  if (cap == 2) return removeSingles(cells, stride, min_i, min_j, max_i, max_j, span, reach);
  if (bits_.size() < row_edges_max / 8 + 8) bits_.resize(row_edges_max / 8 + 8);
  row_first_.clear();
  std::size_t runs = 0;  // runs found so far; run r is [edges_[2r], edges_[2r + 1])

  for (int j = min_j; j < max_j; ++j)
  {
    const uint8_t* row = cells + static_cast<std::size_t>(j) * stride;
    const std::size_t first = runs;
    row_first_.push_back(first);
    // Room for every edge this row can have, so that the scan below writes without checks. The buffers
    // only grow (kept between updates, like the costmap's own grids).
    const std::size_t need = 2 * runs + row_edges_max;
    if (edges_.size() < need || parent_.size() < need / 2 + 1)
    {
      edges_.resize(std::max(need, 2 * edges_.size()));  // removeSingles() may have grown edges_ alone
      parent_.resize(edges_.size() / 2 + 1);
    }
    int32_t* const row_edges = edges_.data() + 2 * runs;
    const int32_t* const edge = scanRow(row, min_i, max_i, span, row_edges, bits_.data());
    runs += static_cast<std::size_t>(edge - row_edges) / 2;
    for (std::size_t r = first; r < runs; ++r)
      parent_[r] = -std::min<int32_t>(edges_[2 * r + 1] - edges_[2 * r], cap);
    if (j == min_j) continue;
    // Join with the overlapping runs of the row above, both lists in column order. The run that ends
    // first can meet no later run of the other row (runs of a row are at least one free cell apart, so
    // the next one starts beyond this one's reach); on a tie both move on.
    std::size_t a = row_first_[row_first_.size() - 2], c = first;
    const std::size_t a_end = first, c_end = runs;
    while (a < a_end && c < c_end)
    {
      const int32_t up_begin = edges_[2 * a], up_end = edges_[2 * a + 1];
      const int32_t here_begin = edges_[2 * c], here_end = edges_[2 * c + 1];
      if (up_begin < here_end + reach && here_begin < up_end + reach)
        unite(static_cast<int32_t>(a), static_cast<int32_t>(c), cap);
      a += static_cast<std::size_t>(up_end <= here_end);
      c += static_cast<std::size_t>(here_end <= up_end);
    }
  }
  row_first_.push_back(runs);

  std::size_t cleared = 0;
  for (std::size_t r = 0; r + 1 < row_first_.size(); ++r)
  {
    uint8_t* row = cells + static_cast<std::size_t>(min_j + static_cast<int>(r)) * stride;
    for (std::size_t k = row_first_[r]; k < row_first_[r + 1]; ++k)
    {
      if (-parent_[findRoot(static_cast<int32_t>(k))] >= cap) continue;
      const auto length = static_cast<std::size_t>(edges_[2 * k + 1] - edges_[2 * k]);
      std::memset(row + edges_[2 * k], FREE_SPACE, length);
      cleared += length;
    }
  }
  return cleared;
}
}  // namespace costmap_layers
#endif  // HWY_ONCE
