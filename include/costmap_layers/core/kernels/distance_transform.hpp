// The core's one distance engine: exact Euclidean distances (between cell centres) from every cell of a
// window of a byte grid to the nearest "source" cell, turned into costs by a non-increasing table and
// either merged into the grid in place (inflation) or streamed out row by row (lanes). Every layer or
// filter that needs distances calls it; the choice of method happens inside, in one place.
//
// Only distances with a non-zero cost matter: DistanceCosts finds the reach (the largest squared
// distance with a cost above 0, e.g. min(inflation_radius, inscribed + ln(252) / factor) for
// inflation), and nothing beyond it is computed. The engine then works in three steps:
//  - a vertical pass per column, saturating at reach + 1 cells, streamed through cache in stripes of
//    rows (the grid is read forward, once, plus reach rows of lookahead per stripe);
//  - a row pass per row: the lower envelope of the parabolas dx^2 + g(x + dx)^2 over the columns
//    within reach, as a min-plus over the column offsets -- in the cost domain, one to four 16-entry
//    byte lookups per offset (as many as the offset has bands of 16 vertical distances with a cost;
//    distances are stored biased so that each band reads the same row), for a reach up to 59 cells
//    (cost(min d2) = max cost since the table does not increase), in 16-bit squared
//    distances up to 254 cells, and with the scalar envelope of Meijster, Roerdink and Hesselink
//    beyond. Blocks of cells with no source within reach are skipped, and a block stops early once no
//    further offset can change any of its results: a cell's cost is final, or (merging) what the cell
//    holds already is at least what any further offset could give, or a special cell can no longer
//    reach special_threshold;
//  - the cost table lookup and the merge rule.
// The SIMD kernels are written once with Highway and compiled for every target Highway attains
// (simd_targets.hpp lists and switches them); the dispatcher is Highway's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace costmap_layers
{
/// The byte values that count as sources: lo <= value <= hi (lo <= hi).
struct SourceRange
{
  uint8_t lo = 1;
  uint8_t hi = 255;
  bool contains(uint8_t v) const { return static_cast<uint8_t>(v - lo) <= static_cast<uint8_t>(hi - lo); }
};

/// The output window [x0, x1) x [y0, y1) (clipped to the grid by the engine).
struct DistanceWindow
{
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

/// The cost of each squared cell distance, prepared once (per parameter change) for the engine.
class DistanceCosts
{
public:
  /// Nothing costs anything.
  DistanceCosts() = default;
  /// @param max_cells  distances beyond this many cells cost 0 (>= 0)
  /// @param cost       the cost at squared cell distance d2 (called for d2 <= max_cells^2 only); it must
  ///                   not increase with d2 (std::invalid_argument otherwise)
  DistanceCosts(int64_t max_cells, const std::function<uint8_t(uint64_t)>& cost);

  /// Whether any distance costs something (else the engine writes nothing).
  bool any() const { return any_; }
  /// The largest squared distance whose cost is above 0 (0 when !any()).
  uint64_t reachSquared() const { return reach_sq_; }
  /// The smallest whole number of cells r with r^2 >= reachSquared(): the engine's band.
  int64_t reach() const { return reach_; }
  /// The cost at squared distance d2 (0 beyond the reach).
  uint8_t at(uint64_t d2) const;

  /// For the engine (reach <= 59): per column offset dx in [0, reach], (reach + 1) / 16 + 1 tables of
  /// 16 bytes, table k holding the costs of dx^2 + v^2 for v = 16 k .. 16 k + 15; and (reach <= 254)
  /// the cost of every 16-bit squared distance.
  const uint8_t* offsetTables() const { return offset_tables_.data(); }
  const uint8_t* table16() const { return table16_.data(); }
  /// For targets with a byte permute across a whole 64-byte vector (15 <= reach <= 126): per column offset
  /// dx in [0, reach], 128 bytes, entry v the cost of dx^2 + v^2 (0 past the reach), from a 64-byte
  /// boundary on; else nullptr.
  const uint8_t* wideTables() const { return wide_tables_.empty() ? nullptr : wide_tables_.front().cost; }
  /// For the engine (15 <= reach <= 126, else nullptr): per vertical distance v in [0, reach],
  /// 2^paintShift() bytes, entry k the cost of (k - paintCenter())^2 + v^2 (0 past the reach): the costs
  /// one column gives a row.
  const uint8_t* paintTables() const { return paint_tables_.empty() ? nullptr : paint_tables_.data(); }
  int paintShift() const { return paint_shift_; }
  int paintCenter() const { return paint_center_; }

private:
  bool any_ = false;
  uint64_t reach_sq_ = 0;
  int64_t reach_ = 0;
  std::vector<uint8_t> table_;  ///< cost by squared distance up to reach_sq_, when small enough
  std::vector<uint8_t> table16_;
  std::vector<uint8_t> offset_tables_;
  struct alignas(64) WideTable
  {
    uint8_t cost[128];
  };
  std::vector<WideTable> wide_tables_;
  std::vector<uint8_t> paint_tables_;
  int paint_shift_ = 0, paint_center_ = 0;
  std::function<uint8_t(uint64_t)> cost_;  ///< past table_ (huge reaches only)
};

/// How distanceCostMerge() writes a cost c into a cell holding old:
///   old == special ? (c >= special_threshold ? c : special) : max(old, c).
/// special_threshold must be >= 1 (a cell then never changes where c == 0).
struct CostMergeRule
{
  uint8_t special = 255;
  uint8_t special_threshold = 253;
  /// The rule for one cell (the engine applies it many cells at a time).
  uint8_t apply(uint8_t old, uint8_t c) const
  {
    if (old == special) return c >= special_threshold ? c : special;
    return old > c ? old : c;
  }
};

/// Buffers reused across calls (they grow to the largest size used, then nothing is allocated).
/// One per calling thread; the engine's own worker threads have theirs inside.
class DistanceTransformScratch
{
public:
  DistanceTransformScratch();
  ~DistanceTransformScratch();
  DistanceTransformScratch(DistanceTransformScratch&&) noexcept;
  DistanceTransformScratch& operator=(DistanceTransformScratch&&) noexcept;
  DistanceTransformScratch(const DistanceTransformScratch&) = delete;
  DistanceTransformScratch& operator=(const DistanceTransformScratch&) = delete;

  struct Buffers;
  std::unique_ptr<Buffers> buffers;
};

/// For every cell of the window (clipped to the grid), with d2 its squared distance to the nearest
/// source (sources outside the window count, and the grid is read only within reach of the window):
/// c = costs.at(d2), written by `rule`. Every row is read before it is written; writing must not change
/// which cells are sources.
/// @param threads  worker threads (>= 1): the window is cut into bands of rows (about four per thread),
///                 each thread taking the next band when done with one; the result is the same for
///                 any count
void distanceCostMerge(uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source,
                       const DistanceCosts& costs, const DistanceWindow& window, CostMergeRule rule,
                       DistanceTransformScratch& scratch, int threads = 1);

/// Called once per window row by distanceCostRows() with the costs of columns [x0, x1) of that row
/// (costs[0] is column x0). Rows come in an unspecified order, each exactly once; the pointer is valid
/// during the call only.
using CostRowSink = std::function<void(int y, const uint8_t* costs)>;

/// The costs of distanceCostMerge() without the merge, streamed to sink row by row; grid is only read.
/// A row whose vertical distances equal those of the row handed over before it reuses that row's
/// costs (straight lanes, open space) instead of running the row pass again.
void distanceCostRows(const uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source,
                      const DistanceCosts& costs, const DistanceWindow& window, DistanceTransformScratch& scratch,
                      const CostRowSink& sink);
}  // namespace costmap_layers
