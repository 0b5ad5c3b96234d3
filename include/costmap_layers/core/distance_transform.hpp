// Exact Euclidean distance transforms on byte grids, in integer cell units (squared distances).
//
// Two engines share one notion of "source cell" (a byte value inside a SourceRange):
//  - squaredDistanceTransform(): the separable exact transform of Meijster et al. (a vertical
//    distance pass, then a lower envelope of parabolas per row, in integers), for any distance,
//    optionally capped. Works on any sub-window of a larger grid through its row stride.
//  - cappedSquaredDistanceRows8/16(): the same transform when only distances up to a small cap
//    matter (inflation, lanes). The vertical pass saturates at cap + 1 and the row pass is a
//    min-plus over the 2 * cap + 1 neighbouring columns, in 8- or 16-bit lanes, so that the compiler
//    vectorises every loop. Rows are streamed to a sink, and only the band of the grid within cap of
//    the requested window is read.
//  - cappedCostMerge8(): the banded transform for caps up to kMaxBandedCap8, mapped through a
//    non-increasing cost table and merged into the grid in place (inflation). Since the table does not
//    increase, cost(min over candidates of d^2) = max over candidates of cost(d^2): the row pass works
//    in the cost domain, one 16-entry lookup per column offset (a byte shuffle on SSE4.1 / AVX2 /
//    AVX-512 / NEON), blocks with no source within cap are skipped, and the vertical pass streams
//    through cache in stripes of rows. cappedCostRows8() streams the same costs to a sink instead.
// All are exact: every reported squared distance equals min over sources of dx^2 + dy^2.
// None allocates once its scratch has grown to the largest size used.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
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

/// Reported for cells without any source (or farther than the cap) by squaredDistanceTransform().
constexpr uint32_t kFarSquaredDistance = 0xFFFFFFFFu;

/// The largest caps the banded engines accept (8-bit: 2 * cap^2 + 1 <= 255; 16-bit: a band of at most
/// 2 * 180 + 1 columns, 2 * cap^2 + 1 <= 65535).
constexpr int kMaxBandedCap8 = 11;
constexpr int kMaxBandedCap16 = 180;

/// Buffers reused across calls; one per thread.
struct DistanceTransformScratch
{
  std::vector<int64_t> row_f;      ///< per column: squared vertical distance, or -1 for none
  std::vector<int32_t> env_s;      ///< envelope: apex columns
  std::vector<int32_t> env_t;      ///< envelope: first column each parabola owns
  std::vector<uint8_t> run;        ///< banded: running vertical distance of one row
  std::vector<uint8_t> up;         ///< banded: upward vertical distances of the output rows
  std::vector<uint8_t> row8;       ///< banded 8-bit: padded squared vertical distances of one row
  std::vector<uint8_t> acc8;       ///< banded 8-bit: output row
  std::vector<uint16_t> row16;     ///< banded 16-bit: padded squared vertical distances of one row
  std::vector<uint16_t> acc16;     ///< banded 16-bit: output row
  std::vector<uint8_t> merge_g;    ///< cost merge: one stripe of padded vertical-distance rows
  std::vector<uint8_t> merge_lut;  ///< cost merge: the per-offset 16-entry cost tables
  std::vector<uint8_t> merge_out;  ///< cost rows: the row handed to the sink
};

/// Exact squared Euclidean distance from every cell of a width x height grid to the nearest source.
/// @param grid         first byte of the grid (or sub-window); row y starts at grid + y * stride
/// @param source       which byte values are sources
/// @param out          first cell of the output; row y starts at out + y * out_stride
/// @param max_sq_dist  cells whose squared distance exceeds this get kFarSquaredDistance
/// Cells with no source at all also get kFarSquaredDistance. width, height >= 0.
void squaredDistanceTransform(const uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source,
                              uint32_t* out, std::ptrdiff_t out_stride, uint32_t max_sq_dist,
                              DistanceTransformScratch& scratch);

/// Convenience form for a dense 0/1 (zero / non-zero) mask, no cap.
inline void squaredDistanceTransform(const uint8_t* is_source, int width, int height, uint32_t* out_sq_dist,
                                     DistanceTransformScratch& scratch)
{
  squaredDistanceTransform(is_source, width, height, width, SourceRange{1, 255}, out_sq_dist, width,
                           kFarSquaredDistance, scratch);
}

/// The output window [x0, x1) x [y0, y1) of a banded transform (inside the grid).
struct DistanceWindow
{
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

/// Called once per output row, in increasing y, with the squared distances of columns [x0, x1) of
/// that row (sq_dist[0] is column x0). A value > cap * cap means "farther than cap". The pointer is
/// valid during the call only.
using DistanceRowSink8 = std::function<void(int y, const uint8_t* sq_dist)>;
using DistanceRowSink16 = std::function<void(int y, const uint16_t* sq_dist)>;

/// Banded exact transform, 8-bit lanes, cap in [0, kMaxBandedCap8] cells (a larger cap throws
/// std::invalid_argument). Sources outside `window` but within cap of it are taken into account (the
/// grid is read only there); the window is clipped to the grid.
/// @param grid  the whole grid, width x height, row y at grid + y * stride
void cappedSquaredDistanceRows8(const uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source,
                                int cap, const DistanceWindow& window, DistanceTransformScratch& scratch,
                                const DistanceRowSink8& sink);

/// As cappedSquaredDistanceRows8, 16-bit lanes, cap in [0, kMaxBandedCap16] cells.
void cappedSquaredDistanceRows16(const uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source,
                                 int cap, const DistanceWindow& window, DistanceTransformScratch& scratch,
                                 const DistanceRowSink16& sink);

/// How cappedCostMerge8() writes a cost c into a cell holding old:
///   old == special ? (c >= special_threshold ? c : special) : max(old, c).
/// special_threshold must be >= 1 (a cell then never changes where c == 0).
struct CostMergeRule
{
  uint8_t special = 255;
  uint8_t special_threshold = 253;
};

/// Exact capped transform, mapped through a cost table and merged into the grid, in place.
/// For every cell of the window (clipped to the grid), with d2 its squared distance to the nearest
/// source (sources outside the window but within cap count): c = cost_by_sq_dist[d2] if d2 <= cap^2,
/// else 0, written by `rule`. Every row is read before it is written, so writing may change sources.
/// @param cost_by_sq_dist  cap^2 + 1 entries, non-increasing (else std::invalid_argument)
/// @param cap              in [0, kMaxBandedCap8] (else std::invalid_argument)
void cappedCostMerge8(uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source, int cap,
                      const DistanceWindow& window, const uint8_t* cost_by_sq_dist, CostMergeRule rule,
                      DistanceTransformScratch& scratch);

/// Called once per window row by cappedCostRows8() with the costs of columns [x0, x1) of that row
/// (costs[0] is column x0). Rows come in an unspecified order, each exactly once; the pointer is valid
/// during the call only.
using CostRowSink = std::function<void(int y, const uint8_t* costs)>;

/// The costs of cappedCostMerge8() without the merge: for every cell of the window (clipped to the
/// grid), c = cost_by_sq_dist[d2] if d2 <= cap^2, else 0, streamed to sink row by row; grid is only
/// read (the sources stay where they are, so it may be a mask of which only some values are sources).
/// A row whose vertical distances equal those of the row handed over before it reuses that row's
/// costs (straight lanes, open space) instead of running the row pass again.
/// Same requirements on cost_by_sq_dist and cap (else std::invalid_argument).
void cappedCostRows8(const uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source, int cap,
                     const DistanceWindow& window, const uint8_t* cost_by_sq_dist, DistanceTransformScratch& scratch,
                     const CostRowSink& sink);

/// Whether the banded kernels may use a wider instruction set chosen at run time (SSE4.1, AVX2 or
/// AVX-512BW on x86, NEON on AArch64). The default is true; false forces "portable".
void setDistanceTransformSimd(bool allow);
/// The kernels this machine runs, "portable" first, then in increasing width ("sse4.1", "avx2",
/// "avx512bw" on x86; "neon" on AArch64).
std::vector<const char*> distanceTransformKernels();
/// Forces one kernel of distanceTransformKernels() (tests compare each with "portable"); an empty
/// name or nullptr returns to the automatic choice (the widest). Returns false, changing nothing, for
/// a kernel this machine does not run.
bool setDistanceTransformKernel(const char* name);
/// The kernel the banded engines use now. cappedSquaredDistanceRows8/16 run their AVX2 clone when
/// this is "avx2" or "avx512bw", else their portable form.
const char* distanceTransformKernel();
}  // namespace costmap_layers
