// Private to the distance engine: what one band of rows asks of the SIMD kernels (dt::Job), the
// constants both sides agree on, and the one entry into the kernels (distance_kernels.cpp, compiled
// once per Highway target; Highway's dispatcher picks the best target this CPU runs).
#pragma once

#include <cstddef>
#include <cstdint>

#include "costmap_layers/core/kernels/distance_transform.hpp"

namespace costmap_layers
{
namespace dt
{
/// Widest vector of any target, in bytes: the padding on both sides of a row.
constexpr int kMaxLanes = 64;
/// Up to this reach the row pass works in the cost domain with 16-entry byte tables: per column offset,
/// tablesPerOffset(reach) tables of 16 vertical distances each.
constexpr int kMaxCostDomainReach = 59;
/// Tables per column offset: vertical distances 16 k .. 16 k + 15 in table k, for distances up to
/// reach + 1 (the saturated "far", which costs 0).
constexpr int tablesPerOffset(int reach)
{
  return (reach + 1) / 16 + 1;
}
/// Up to this reach vertical distances are bytes and squared distances 16 bits.
constexpr int kMaxBandedReach = 254;
/// On targets with a byte permute across a whole vector (AVX-512 VBMI), from kMinWideReach to
/// kMaxWideReach the row pass works in the cost domain with one lookup of 128 entries per column offset
/// (wideTables()): a distance up to reach + 1 indexes it directly. It starts where a second 16-entry
/// table per offset would (one permute instead of two lookups: the whole update 14 % faster on willow
/// at reach 20, 9 % on warehouse at reach 19, on a Xeon with AVX-512 VBMI). Below, with one table per
/// offset, the permute was measured slower (reach 11, where the one-table path has no stop checks).
constexpr int kMinWideReach = 15;
constexpr int kMaxWideReach = 126;
static_assert(tablesPerOffset(kMinWideReach - 1) == 1 && tablesPerOffset(kMinWideReach) == 2,
              "the permute starts where a second 16-entry table would");
/// runJob's modes besides K tables of 16 entries (1-4) and 16-bit squared distances (0): the wide
/// lookup of 64 entries (reach <= 62) and of 128 entries.
constexpr int kWide64 = 8;
constexpr int kWide128 = 9;

/// From kMinPaintReach to kMaxPaintReach a block of a row may be costed from the columns that can matter
/// to it (listPainted, paintColumns: one vector load and maximum each) instead of column offset by
/// offset: when it has at most kPaintPercent % as many as the offsets it took the last time it ran them
/// (paintChoice). A row lists its columns while the row before painted at least 1 / kPaintRowShare of
/// its blocks, and looks again every kPaintProbe rows (runJob). Below kMinPaintReach the one-table
/// lookup per offset was measured faster than listing the columns at all. (Measured on willow, a
/// scanned map with ragged walls, painting every block with up to 2 x reach columns was slower than
/// the offsets; on warehouse and the synthetic map, with straight walls, far faster.)
constexpr int kMinPaintReach = 15;
constexpr int kMaxPaintReach = 126;
constexpr int kPaintPercent = 35;
constexpr int kPaintProbe = 16;
constexpr int kPaintRowShare = 2;
static_assert(tablesPerOffset(kMinPaintReach - 1) == 1 && tablesPerOffset(kMinPaintReach) == 2,
              "painting starts where a second table per offset would");
static_assert(kMaxCostDomainReach <= kMaxPaintReach,
              "gather_est (kept where painting can happen) exists wherever the stop checks read it");
static_assert(kMinWideReach >= kMinPaintReach && kMaxWideReach <= kMaxPaintReach,
              "the wide row pass paints (it needs the paint tables)");
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "listPainted moves mask bits between byte arrays and 64-bit words by memcpy");

/// One band of rows for the vector engine; buffers sized by the caller.
struct Job
{
  const uint8_t* const* src_rows;  ///< row y (in [ry0, ry1)) starts at src_rows[y - ry0], column cx0
  int ry0, ry1, cx0, cx1;          ///< the rows and columns read
  SourceRange source;
  DistanceWindow win;  ///< the rows and columns written (clipped, non-empty)
  int cap;             ///< the reach in cells, <= kMaxBandedReach
  const uint8_t* offset_tables;
  const uint8_t* table16;
  uint8_t* target;  ///< merge mode: row y at target + y * target_stride (column 0)
  std::ptrdiff_t target_stride;
  CostMergeRule rule;
  const CostRowSink* sink;  ///< sink mode (target == nullptr)
  uint8_t* out_row;         ///< sink mode: one window row
  uint8_t* rows;            ///< stripe rows, row_stride bytes each; window column 0 at offset pad
  int row_stride, pad, stripe;
  uint8_t* run;                   ///< band width
  uint8_t* up;                    ///< band width
  uint16_t* sq;                   ///< reach > kMaxCostDomainReach: squared vertical distances, row_stride entries
  uint16_t* acc;                  ///< reach > kMaxCostDomainReach: one block of squared distances
  uint8_t* costs;                 ///< reach > kMaxCostDomainReach: one block of costs
  const uint16_t* squares;        ///< 16-bit path: dx^2 eight times for each dx in [0, cap]
  const uint8_t* wide_tables;     ///< DistanceCosts::wideTables() (nullptr outside kMinWideReach..kMaxWideReach)
  const uint8_t* paint;           ///< DistanceCosts::paintTables() (nullptr outside kMinPaintReach..kMaxPaintReach)
  int paint_shift, paint_center;  ///< rows of 1 << paint_shift bytes
  uint8_t* gather_est;  ///< per block of the row: the offsets it took when it last ran them (see paintChoice, stopHint)
  int32_t* paint_list;  ///< see listPainted
  int* paint_counts;
};

/// In the cost domain a vertical distance v is stored as v + kBias: the 16-entry byte lookup of table
/// k at index (v + kBias - 16 k) then reads entry v - 16 k for v in [16 k, 16 k + 15], gives 0 above
/// (bit 7 set) and an entry of a farther distance below (bit 7 clear, k <= 7): never more than the
/// cost of v. So the largest of the K lookups is the cost of v, with no split of the row into bands.
constexpr uint8_t kBias = 112;
static_assert(kBias + 16 == 128 && kBias >= 16 * (tablesPerOffset(kMaxCostDomainReach) - 1) &&
                  kBias + kMaxCostDomainReach + 1 <= 255,
              "a band's own distances must index 0..15 with bit 7 clear, farther ones set bit 7");
/// Offsets after 0 go in groups of this many; a block may stop after each group.
constexpr int kGroup = 4;
}  // namespace dt

/// Runs one job on the best SIMD target this CPU runs (or the one simd_targets.hpp forces).
void runDistanceJob(const dt::Job& job);
}  // namespace costmap_layers
