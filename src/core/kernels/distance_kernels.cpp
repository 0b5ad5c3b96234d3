// The distance engine's SIMD kernels (see distance_transform.hpp), written once with Highway:
// foreach_target.h compiles this file once per target, HWY_DYNAMIC_DISPATCH picks one at run time.
// The rest of the engine (cost table, scratch buffers, bands and threads, the envelope path for long
// reaches) is plain C++ in distance_costs.cpp and distance_transform.cpp.
#include <algorithm>
#include <cstring>

#include "src/core/kernels/distance_job.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/core/kernels/distance_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace costmap_layers
{
namespace HWY_NAMESPACE
{
namespace hn = hwy::HWY_NAMESPACE;

/// dst[k] = source(src[k]) ? base : min(above[k] + 1, far): one step of a vertical sweep (distances
/// stored as base + v). above may be dst (the rows above the window run in place).
HWY_INLINE void verticalStep(const uint8_t* HWY_RESTRICT src, const uint8_t* above, uint8_t* dst, int cw, uint8_t lo,
                             uint8_t span, uint8_t base, uint8_t far)
{
  const hn::ScalableTag<uint8_t> d;
  const int N = static_cast<int>(hn::Lanes(d));
  const auto vlo = hn::Set(d, lo), vspan = hn::Set(d, span), vfar = hn::Set(d, far), one = hn::Set(d, 1);
  const auto vbase = hn::Set(d, base);
  int k = 0;
  for (; k + N <= cw; k += N)
  {
    const auto rel = hn::Sub(hn::LoadU(d, src + k), vlo);
    const auto is_src = hn::Eq(hn::Min(rel, vspan), rel);
    const auto next = hn::Min(hn::SaturatedAdd(hn::LoadU(d, above + k), one), vfar);
    hn::StoreU(hn::IfThenElse(is_src, vbase, next), d, dst + k);
  }
  for (; k < cw; ++k)
  {
    const uint8_t r = static_cast<uint8_t>(std::min<int>(above[k] + 1, far));
    dst[k] = static_cast<uint8_t>(src[k] - lo) <= span ? base : r;
  }
}

/// up[k] = min(up[k], source(src[k]) ? dist : far): the lookahead below a stripe.
HWY_INLINE void lookaheadStep(const uint8_t* HWY_RESTRICT src, uint8_t* HWY_RESTRICT up, int cw, uint8_t lo,
                              uint8_t span, uint8_t dist, uint8_t far)
{
  const hn::ScalableTag<uint8_t> d;
  const int N = static_cast<int>(hn::Lanes(d));
  const auto vlo = hn::Set(d, lo), vspan = hn::Set(d, span), vfar = hn::Set(d, far), vdist = hn::Set(d, dist);
  int k = 0;
  for (; k + N <= cw; k += N)
  {
    const auto rel = hn::Sub(hn::LoadU(d, src + k), vlo);
    const auto is_src = hn::Eq(hn::Min(rel, vspan), rel);
    hn::StoreU(hn::Min(hn::LoadU(d, up + k), hn::IfThenElse(is_src, vdist, vfar)), d, up + k);
  }
  for (; k < cw; ++k)
  {
    const uint8_t v = static_cast<uint8_t>(src[k] - lo) <= span ? dist : far;
    up[k] = std::min(up[k], v);
  }
}

/// dst[k] = min(dst[k], below[k] + 1, far): the upward sweep.
HWY_INLINE void upwardStep(const uint8_t* HWY_RESTRICT below, uint8_t* HWY_RESTRICT dst, int cw, uint8_t far)
{
  const hn::ScalableTag<uint8_t> d;
  const int N = static_cast<int>(hn::Lanes(d));
  const auto vfar = hn::Set(d, far), one = hn::Set(d, 1);
  int k = 0;
  for (; k + N <= cw; k += N)
  {
    const auto next = hn::Min(hn::SaturatedAdd(hn::LoadU(d, below + k), one), vfar);
    hn::StoreU(hn::Min(hn::LoadU(d, dst + k), next), d, dst + k);
  }
  for (; k < cw; ++k)
    dst[k] = static_cast<uint8_t>(std::min<int>(dst[k], std::min<int>(below[k] + 1, far)));
}

/// The merge rule on one vector of costs c, written to out (N cells).
template <class D, class V>
HWY_INLINE V mergeRule(D d, V old, V c, const CostMergeRule& rule)
{
  const auto special = hn::Set(d, rule.special);
  const auto threshold = hn::Set(d, rule.special_threshold);
  const auto for_special = hn::IfThenElse(hn::Eq(hn::Max(c, threshold), c), c, special);
  return hn::IfThenElse(hn::Eq(old, special), for_special, hn::Max(old, c));
}

/// Writes n (<= Lanes(d)) merged cells: whole vectors directly, a short tail through a copy.
template <class D, class V>
HWY_INLINE void mergeStore(D d, V c, uint8_t* HWY_RESTRICT out, int n, const CostMergeRule& rule)
{
  const int N = static_cast<int>(hn::Lanes(d));
  if (n >= N)
  {
    hn::StoreU(mergeRule(d, hn::LoadU(d, out), c, rule), d, out);
    return;
  }
  HWY_ALIGN uint8_t tmp[dt::kMaxLanes];
  std::memcpy(tmp, out, static_cast<std::size_t>(n));
  hn::Store(mergeRule(d, hn::Load(d, tmp), c, rule), d, tmp);
  std::memcpy(out, tmp, static_cast<std::size_t>(n));
}

/// Whether any vertical distance in [g - cap, g + N + cap) is below far.
template <class D>
HWY_INLINE bool anyNear(D d, const uint8_t* g, int cap, uint8_t far)
{
  const int N = static_cast<int>(hn::Lanes(d));
  auto near = hn::LoadU(d, g - cap);
  for (int o = N - cap;; o += N)
  {
    const int oo = o < cap ? o : cap;
    near = hn::Min(near, hn::LoadU(d, g + oo));
    if (oo == cap) break;
  }
  return !hn::AllTrue(d, hn::Eq(near, hn::Set(d, far)));
}

/// One 16-entry table lookup of each lane; an index with its top bit set gives 0.
template <class D, class V>
HWY_INLINE V lookup16(D d, const uint8_t* table, V idx)
{
#if HWY_TARGET == HWY_SCALAR
  const uint8_t i = hn::GetLane(idx);
  return hn::Set(d, i >= 0x80 ? uint8_t{0} : table[i & 15]);
#else
  return hn::TableLookupBytesOr0(hn::LoadDup128(d, table), idx);
#endif
}

/// The floor of the stop checks for the block at out (n cells left in the row): what the merge keeps
/// whatever the cost. A cell ends at max(old, cost), so old is a floor; a special cell only takes a
/// cost from special_threshold on. The last, partial block of a row takes no floor.
template <class D>
HWY_INLINE hn::Vec<D> mergeFloor(D d, const uint8_t* out, int n, const CostMergeRule& rule, hn::Mask<D>& is_special)
{
  const bool whole = n >= static_cast<int>(hn::Lanes(d));
  const auto old = whole ? hn::LoadU(d, out) : hn::Zero(d);
  is_special = whole ? hn::Eq(old, hn::Set(d, rule.special)) : hn::FirstN(d, 0);
  return hn::IfThenZeroElse(is_special, old);
}

/// Whether a block may stop: no further offset gives more than top (the next offset's cost at vertical
/// distance 0), and every lane has that much (c0, c1) or keeps it anyway (floor), or is special while
/// top is below special_threshold.
template <class D, class V>
HWY_INLINE bool blockDone(D d, V c0, V c1, V floor, hn::Mask<D> is_special, uint8_t top, const CostMergeRule& rule)
{
  const auto kept = hn::Max(hn::Max(c0, c1), floor);
  auto done = hn::Eq(hn::Max(kept, hn::Set(d, top)), kept);
  if (top < rule.special_threshold) done = hn::Or(done, is_special);
  return hn::AllTrue(d, done);
}

/// The number of bits set. Highway's targets do not enable the popcnt instruction, so the builtin would
/// be a library call on x86: every x86 processor with SSE4.2 has the instruction, older ones get a few
/// shifts and adds.
HWY_INLINE int bitCount(uint64_t x)
{
#if HWY_ARCH_X86_64 && HWY_TARGET <= HWY_SSE4
  uint64_t r;
  asm("popcnt %1, %0" : "=r"(r) : "r"(x) : "cc");
  return static_cast<int>(r);
#elif HWY_ARCH_X86
  x = x - ((x >> 1) & 0x5555555555555555ull);
  x = (x & 0x3333333333333333ull) + ((x >> 2) & 0x3333333333333333ull);
  x = (x + (x >> 4)) & 0x0F0F0F0F0F0F0F0Full;
  return static_cast<int>((x * 0x0101010101010101ull) >> 56);
#else
  return __builtin_popcountll(x);
#endif
}

#if HWY_TARGET == HWY_AVX2
/// Highway 1.0.3's Compress of 32-bit lanes on AVX2 keeps its table of lane indices in a local constexpr
/// array that GCC 12 copies onto the stack (1 KiB, rep movsq) on every call: a quarter of the row pass's
/// time where it paints. The same permutation (vpermd) from a table of static storage: entry m holds, 4
/// bits each, the lanes set in m in order.
struct CompressIndices
{
  uint32_t packed[256];
};
constexpr CompressIndices makeCompressIndices()
{
  CompressIndices t{};
  for (uint32_t m = 0; m < 256; ++m)
  {
    uint32_t packed = 0, k = 0;
    for (uint32_t lane = 0; lane < 8; ++lane)
      if ((m >> lane) & 1u) packed |= lane << (4 * k++);
    t.packed[m] = packed;
  }
  return t;
}
alignas(64) constexpr CompressIndices kCompressIndices = makeCompressIndices();
alignas(32) constexpr uint32_t kNibbleShifts[8] = {0, 4, 8, 12, 16, 20, 24, 28};

/// hn::Compress(v, mask) for the 8 lanes of mask_bits (the lanes past the count are unspecified).
HWY_INLINE hn::Vec<hn::ScalableTag<int32_t>> compress32(hn::Vec<hn::ScalableTag<int32_t>> v, uint64_t mask_bits)
{
  const hn::ScalableTag<int32_t> d;
  const hn::ScalableTag<uint32_t> du;
  const auto packed = hn::Set(du, kCompressIndices.packed[mask_bits & 0xFF]);
  const auto lanes = hn::And(hn::Shr(packed, hn::Load(du, kNibbleShifts)), hn::Set(du, 7));
  return hn::TableLookupLanes(v, hn::IndicesFromVec(d, hn::BitCast(d, lanes)));
}
#endif

/// How many chunks of N32 columns (see listPainted) the columns within reach of a block span.
HWY_INLINE int paintChunks(int cap)
{
  const int N = static_cast<int>(hn::Lanes(hn::ScalableTag<uint8_t>()));
  const int N32 = static_cast<int>(hn::Lanes(hn::ScalableTag<int32_t>()));
  return (N + 2 * cap + N32 - 1) / N32;
}

/// The columns of one row that a block may have to paint (see paintColumns), listed once per row: for
/// each column c from -cap on with a source within reach (v < far) and a neighbour farther from one,
/// (v << paint_shift) - c, in column order; counts[i] = how many come before column -cap + i * N32.
/// Why only those: a column c with v(c - 1) <= v(c) gives no cell left of it less than column c - 1
/// does ((x - c + 1)^2 + v(c - 1)^2 < (x - c)^2 + v(c)^2 for x < c), and likewise on the right.
/// Following such neighbours from any column towards a cell x ends at x itself or at a listed column
/// between them. So the costs of a block are those of its own columns and of the listed ones within
/// reach of it, whatever the others hold.
HWY_INLINE void listPainted(const uint8_t* g, int n, const dt::Job& j, uint8_t base, uint8_t far)
{
  const hn::ScalableTag<uint8_t> d;
  const hn::ScalableTag<int32_t> d32;
  const hn::Rebind<uint8_t, decltype(d32)> d8;
  const int N = static_cast<int>(hn::Lanes(d));
  const int N32 = static_cast<int>(hn::Lanes(d32));
  const int cap = j.cap;
  const int chunks = ((n + N - 1) / N - 1) * N / N32 + paintChunks(cap);
  const auto far8 = hn::Set(d, far);
  const auto vbase = hn::Set(d32, base);
  const auto iota = hn::Iota(d32, 0);  // a constant (Iota from a variable start goes through memory)
  int32_t* HWY_RESTRICT list = j.paint_list;
  int* HWY_RESTRICT counts = j.paint_counts;
  int k = 0;
  // A vector of columns at a time (the mask, its count); its chunks of N32 columns only when it lists any.
  for (int i = 0; i < chunks; i += N / N32)
  {
    const uint8_t* gc = g - cap + i * N32;
    const auto v8 = hn::LoadU(d, gc);
    const auto side8 = hn::Max(hn::Max(hn::LoadU(d, gc - 1), hn::LoadU(d, gc + 1)), v8);
    uint8_t mask_bytes[8] = {};
    hn::StoreMaskBits(d, hn::And(hn::Ne(v8, far8), hn::Ne(side8, v8)), mask_bytes);
    uint64_t bits;
    std::memcpy(&bits, mask_bytes, sizeof(bits));
    for (int q = 0; q < N / N32 && i + q <= chunks; ++q)
    {
      const int before = k + bitCount(q * N32 >= 64 ? bits : bits & ((uint64_t{1} << (q * N32)) - 1));
      counts[i + q] = before;
      const uint64_t own = N32 >= 64 ? bits : (bits >> (q * N32)) & ((uint64_t{1} << N32) - 1);
      if (own == 0 || i + q == chunks) continue;
      const auto v = hn::PromoteTo(d32, hn::LoadU(d8, gc + q * N32));
      const auto column = hn::Add(iota, hn::Set(d32, -cap + (i + q) * N32));
      const auto entries = hn::Sub(hn::ShiftLeftSame(hn::Sub(v, vbase), j.paint_shift), column);
      // Compress, then a whole-vector store (a compressing store to memory is slow on some processors);
      // the next chunk's store overwrites what lies past this one's entries.
#if HWY_TARGET == HWY_AVX2
      hn::StoreU(compress32(entries, own), d32, list + before);
#else
      // The chunk's own bits of the mask above (little-endian, as the mask was read).
      uint8_t own_bytes[8];
      std::memcpy(own_bytes, &own, sizeof(own));
      hn::StoreU(hn::Compress(entries, hn::LoadMaskBits(d32, own_bytes)), d32, list + before);
#endif
    }
    k += bitCount(bits);
  }
  if (chunks % (N / N32) == 0) counts[chunks] = k;
}

/// The entries [lo, hi) of the list of one row (see listPainted) for the block at x.
HWY_INLINE void paintRange(const dt::Job& j, int x, int& lo, int& hi)
{
  const int N32 = static_cast<int>(hn::Lanes(hn::ScalableTag<int32_t>()));
  lo = j.paint_counts[x / N32];
  hi = j.paint_counts[x / N32 + paintChunks(j.cap)];
}

/// The largest cost the listed columns within reach (entries [lo, hi)) give each cell of the block at
/// x: per column c, its row of costs for v(c) (paintTables) read from the entry of cell x on.
template <class D>
HWY_INLINE hn::Vec<D> paintColumns(D d, int x, int lo, int hi, const dt::Job& j)
{
  const uint8_t* at = j.paint + j.paint_center + x;
  const int32_t* list = j.paint_list;
  auto c0 = hn::Zero(d), c1 = hn::Zero(d);
  int i = lo;
  for (; i + 1 < hi; i += 2)
  {
    c0 = hn::Max(c0, hn::LoadU(d, at + list[i]));
    c1 = hn::Max(c1, hn::LoadU(d, at + list[i + 1]));
  }
  if (i < hi) c0 = hn::Max(c0, hn::LoadU(d, at + list[i]));
  return hn::Max(c0, c1);
}

/// How a row pass that paints (see listPainted) costs the block at x: kSkip (no source within reach),
/// kPaint or kOffsets. Painting takes one load and maximum per listed column (plus listing them), the
/// offsets a few lookups each and stop early: the block paints when its listed columns are at most
/// kPaintPercent % of the offsets the block took the last time it ran them (gather_est; see runJob).
enum class BlockWay
{
  kSkip,
  kPaint,
  kOffsets
};
template <class D>
HWY_INLINE BlockWay paintChoice(D d, const uint8_t* g, int x, const dt::Job& j, uint8_t far, int& lo, int& hi)
{
  paintRange(j, x, lo, hi);
  if (hi == lo && hn::AllTrue(d, hn::Eq(hn::LoadU(d, g + x), hn::Set(d, far)))) return BlockWay::kSkip;
  const int est = j.gather_est[x / static_cast<int>(hn::Lanes(d))];
  return (hi - lo) * 100 <= est * dt::kPaintPercent ? BlockWay::kPaint : BlockWay::kOffsets;
}

/// A block of a row that paints: true when it is done (no source within reach, or painted; see
/// paintChoice), false when it is to run the offsets. own() gives its own columns' costs.
template <class D, class Own>
HWY_INLINE bool paintedBlock(D d, const uint8_t* g, uint8_t* out, int x, int n, const dt::Job& j, uint8_t far,
                             const Own& own, int& painted)
{
  int lo, hi;
  const BlockWay way = paintChoice(d, g, x, j, far, lo, hi);
  if (way != BlockWay::kPaint) return way == BlockWay::kSkip;
  auto c = own();
  if (hi > lo) c = hn::Max(c, paintColumns(d, x, lo, hi, j));
  mergeStore(d, c, out + x, std::min(static_cast<int>(hn::Lanes(d)), n - x), j.rule);
  painted += hi > lo;
  return true;
}

/// Whether a block that has taken offsets up to e - 1 checks whether it may stop (blockDone), given
/// hint, the offsets the same block took in the row costed before (gather_est; the reach before the
/// first). Rows next to each other mostly stop at the same offset: checking from one group before it on
/// (a block may need fewer than its neighbour row) halves the checks and their mispredicted exits
/// against checking after every group (on willow at reach 20 the whole update 7 % faster on AVX-512
/// VBMI, 10 % on AVX-512, 6 % on AVX2). Any e gives the same costs (the check is exact).
HWY_INLINE bool stopHint(int e, int hint)
{
  return e - 1 >= hint - dt::kGroup;
}

/// The cost at column offset dx from biased vertical distances (see kBias), by the first KK of the
/// offset's tables (those past its last non-zero one hold zeros).
template <int KK, class D>
HWY_INLINE hn::Vec<D> offsetCost(D d, const uint8_t* t, const uint8_t* gx, int dx)
{
  const auto m = hn::Min(hn::LoadU(d, gx - dx), hn::LoadU(d, gx + dx));
  auto c = lookup16(d, t, m);
  for (int k = 1; k < KK; ++k)
    c = hn::Max(c, lookup16(d, t + 16 * k, hn::Sub(m, hn::Set(d, static_cast<uint8_t>(16 * k)))));
  return c;
}

/// Offsets [dx, dx + count) (count <= kGroup) by KK tables each, into two accumulators.
template <int KK, class D, class V>
HWY_INLINE void offsetGroup(D d, const uint8_t* tables, std::ptrdiff_t tstride, const uint8_t* gx, int dx, int count,
                            V& c0, V& c1)
{
  const uint8_t* t = tables + tstride * dx;
  if (count == dt::kGroup)
  {
    for (int i = 0; i < dt::kGroup; i += 2)
    {
      c1 = hn::Max(c1, offsetCost<KK>(d, t + i * tstride, gx, dx + i));
      c0 = hn::Max(c0, offsetCost<KK>(d, t + (i + 1) * tstride, gx, dx + i + 1));
    }
    return;
  }
  for (int i = 0; i < count; ++i)
    c1 = hn::Max(c1, offsetCost<KK>(d, t + i * tstride, gx, dx + i));
}

/// Row pass in the cost domain (reach <= kMaxCostDomainReach): c = max over dx of
/// cost(dx^2 + min(g[x - dx], g[x + dx])^2), merged into out. g holds biased distances and is
/// readable on [-pad, n + pad). KMAX: tables per offset; group_tables[i]: the tables the offsets of
/// group i (offsets 1 + kGroup i ...) need, non-increasing, 0 past the last offset with a cost.
template <int KMAX, bool PAINT>
HWY_INLINE int rowPassCost8(const uint8_t* HWY_RESTRICT g, uint8_t* HWY_RESTRICT out, int n, const dt::Job& j,
                            const uint8_t* group_tables)
{
  const hn::ScalableTag<uint8_t> d;
  const int N = static_cast<int>(hn::Lanes(d));
  const int cap = j.cap;
  const uint8_t far = static_cast<uint8_t>(dt::kBias + cap + 1);
  const uint8_t* tables = j.offset_tables;
  const std::ptrdiff_t ts = 16 * KMAX;
  int painted = 0;  // blocks that painted listed columns
  for (int x = 0; x < n; x += N)
  {
    const uint8_t* gx = g + x;
    if constexpr (PAINT)
    {
      if (paintedBlock(
              d, g, out, x, n, j, far, [&] { return offsetCost<KMAX>(d, tables, gx, 0); }, painted))
        continue;
    }
    else if (!anyNear(d, gx, cap, far))
      continue;
    int used = cap;  // offsets taken
    hn::Mask<decltype(d)> is_special;
    const auto floor = mergeFloor(d, out + x, n - x, j.rule, is_special);
    // Two accumulators: two shorter dependency chains of maxima.
    auto c0 = offsetCost<KMAX>(d, tables, gx, 0);
    auto c1 = hn::Zero(d);
    const int hint = KMAX > 1 ? j.gather_est[x / N] : 0;
    for (int i = 0, dx = 1; dx <= cap; ++i, dx += dt::kGroup)
    {
      const int count = std::min(dt::kGroup, cap + 1 - dx);
      const int tables_needed = KMAX == 1 ? 1 : group_tables[i];
      if (tables_needed == 0)  // no further offset costs anything
      {
        used = dx - 1;
        break;
      }
      switch (tables_needed)
      {
        case 1:
          offsetGroup<1>(d, tables, ts, gx, dx, count, c0, c1);
          break;
        case 2:
          offsetGroup<(KMAX >= 2 ? 2 : 1)>(d, tables, ts, gx, dx, count, c0, c1);
          break;
        case 3:
          offsetGroup<(KMAX >= 3 ? 3 : 1)>(d, tables, ts, gx, dx, count, c0, c1);
          break;
        default:
          offsetGroup<KMAX>(d, tables, ts, gx, dx, count, c0, c1);
          break;
      }
      // No further offset gives more than the cost of e^2 (entry 0 of its first table), e the first
      // offset after the group: once every lane has that much (or its floor does; or, for a special
      // cell, once that cost is below special_threshold), stop; checked from about where the block
      // stopped in the row before (stopHint). (With one table the reach is at most 14: checking costs
      // more than it saves.)
      const int e = dx + dt::kGroup;
      if (KMAX > 1 && stopHint(e, hint) && e <= cap && blockDone(d, c0, c1, floor, is_special, tables[ts * e], j.rule))
      {
        used = e - 1;
        break;
      }
    }
    if (j.paint != nullptr) j.gather_est[x / N] = static_cast<uint8_t>(used);
    mergeStore(d, hn::Max(c0, c1), out + x, std::min(N, n - x), j.rule);
  }
  return painted;
}

#if HWY_TARGET == HWY_AVX3_DL
/// The cost of distances m (< 128) by one permute of the offset's wide table t: Highway 1.0.3 has no
/// byte-lane TableLookupLanes, so VBMI's vpermb / vpermt2b are called directly (this target only).
template <int MODE, class D>
HWY_INLINE hn::Vec<D> wideCost(D d, const uint8_t* t, hn::Vec<D> m)
{
  if constexpr (MODE == dt::kWide64)
    return hn::Vec<D>{_mm512_permutexvar_epi8(m.raw, hn::Load(d, t).raw)};
  else
    return hn::Vec<D>{_mm512_permutex2var_epi8(hn::Load(d, t).raw, m.raw, hn::Load(d, t + 64).raw)};
}

/// Row pass in the cost domain by wide tables (reach <= kMaxWideReach, distances stored unbiased):
/// c = max over dx of table_dx[min(g[x - dx], g[x + dx])], merged into out; as rowPassCost8 otherwise.
template <int MODE, bool PAINT>
HWY_INLINE int rowPassWide(const uint8_t* HWY_RESTRICT g, uint8_t* HWY_RESTRICT out, int n, const dt::Job& j)
{
  const hn::ScalableTag<uint8_t> d;
  const int N = static_cast<int>(hn::Lanes(d));
  const int cap = j.cap;
  const uint8_t far = static_cast<uint8_t>(cap + 1);
  const uint8_t* tables = j.wide_tables;
  constexpr std::ptrdiff_t ts = 128;
  int painted = 0;  // blocks that painted listed columns
  for (int x = 0; x < n; x += N)
  {
    const uint8_t* gx = g + x;
    if constexpr (PAINT)
    {
      if (paintedBlock(
              d, g, out, x, n, j, far, [&] { return wideCost<MODE>(d, tables, hn::LoadU(d, gx)); }, painted))
        continue;
    }
    else if (!anyNear(d, gx, cap, far))
      continue;
    hn::Mask<decltype(d)> is_special;
    const auto floor = mergeFloor(d, out + x, n - x, j.rule, is_special);
    auto c0 = wideCost<MODE>(d, tables, hn::LoadU(d, gx));
    auto c1 = hn::Zero(d);
    const int hint = j.gather_est[x / N];
    auto at = [&](int dx)
    { return wideCost<MODE>(d, tables + ts * dx, hn::Min(hn::LoadU(d, gx - dx), hn::LoadU(d, gx + dx))); };
    int dx = 1;
    for (; dx + dt::kGroup - 1 <= cap; dx += dt::kGroup)
    {
      c1 = hn::Max(c1, at(dx));
      c0 = hn::Max(c0, at(dx + 1));
      c1 = hn::Max(c1, at(dx + 2));
      c0 = hn::Max(c0, at(dx + 3));
      // As rowPassCost8: no further offset gives more than the cost of e^2 at vertical distance 0.
      const int e = dx + dt::kGroup;
      if (stopHint(e, hint) && e <= cap && blockDone(d, c0, c1, floor, is_special, tables[ts * e], j.rule)) break;
    }
    if (dx + dt::kGroup - 1 > cap)  // the loop ran out (no stop): the offsets left
      for (; dx <= cap; ++dx)
        c1 = hn::Max(c1, at(dx));
    j.gather_est[x / N] = static_cast<uint8_t>(std::min(cap, dx + dt::kGroup - 1));
    mergeStore(d, hn::Max(c0, c1), out + x, std::min(N, n - x), j.rule);
  }
  return painted;
}
#endif

/// Row pass in squared distances (kMaxCostDomainReach < reach <= kMaxBandedReach): d2 = min over dx of
/// dx^2 + sq[x +- dx], then the cost table, merged into out.
HWY_INLINE void rowPassSq16(const uint8_t* HWY_RESTRICT g, uint8_t* HWY_RESTRICT out, int n, const dt::Job& j)
{
  const hn::ScalableTag<uint16_t> d16;
  const hn::Rebind<uint8_t, decltype(d16)> d8;  // as many byte lanes as 16-bit lanes
  const int N = static_cast<int>(hn::Lanes(d16));
  const int cap = j.cap;
  const uint8_t far = static_cast<uint8_t>(cap + 1);
  const int pad = j.pad;
  // Squared vertical distances of the whole padded row (far stays above any reachable d2).
  uint16_t* HWY_RESTRICT sq = j.sq + pad;
  for (int k = -pad; k < n + pad; k += N)
  {
    const auto v = hn::PromoteTo(d16, hn::LoadU(d8, g + k));
    hn::StoreU(hn::Mul(v, v), d16, sq + k);
  }
  const uint16_t far_sq = static_cast<uint16_t>(far * far);
  const uint8_t* table = j.table16;
  uint16_t* HWY_RESTRICT acc_buf = j.acc;
  // dx^2 in every lane: a load (a broadcast from a register would compete with the arithmetic).
  auto square = [&](int dx) { return hn::LoadDup128(d16, j.squares + 8 * dx); };
  uint8_t* HWY_RESTRICT cost_buf = j.costs;
  const auto special = hn::Set(d16, j.rule.special);
  for (int x = 0; x < n; x += N)
  {
    // Skip a block with no source within reach (a whole byte vector of blocks at a time would need
    // the same loads; the 16-bit vectors are read anyway).
    const uint16_t* sx = sq + x;
    {
      auto near = hn::LoadU(d16, sx - cap);
      for (int o = N - cap;; o += N)
      {
        const int oo = o < cap ? o : cap;
        near = hn::Min(near, hn::LoadU(d16, sx + oo));
        if (oo == cap) break;
      }
      if (hn::AllTrue(d16, hn::Eq(near, hn::Set(d16, far_sq)))) continue;
    }
    // The merge's floor, as in rowPassCost8 (the last, partial block takes none).
    const bool whole = x + N <= n;
    const auto old = hn::PromoteTo(d16, whole ? hn::LoadU(d8, out + x) : hn::Zero(d8));
    const auto is_special = whole ? hn::Eq(old, special) : hn::FirstN(d16, 0);
    const auto floor = hn::IfThenZeroElse(is_special, old);
    auto a0 = hn::LoadU(d16, sx);
    auto a1 = a0;
    int dx = 1;
    for (; dx + 1 <= cap; dx += 2)
    {
      const auto m0 = hn::Min(hn::LoadU(d16, sx - dx), hn::LoadU(d16, sx + dx));
      a0 = hn::Min(a0, hn::SaturatedAdd(m0, square(dx)));
      const int e = dx + 1;
      const auto m1 = hn::Min(hn::LoadU(d16, sx - e), hn::LoadU(d16, sx + e));
      a1 = hn::Min(a1, hn::SaturatedAdd(m1, square(e)));
      // Every further offset adds at least (e + 1)^2 > e^2, so costs at most top: once each lane has
      // its distance (at most e^2), or a floor of top, or (special) top is below special_threshold, stop.
      if ((dx & 7) == 7)
      {
        const auto a = hn::Min(a0, a1);
        const uint8_t top = table[(e + 1) * (e + 1)];
        auto done = hn::Or(hn::Eq(hn::Min(a, square(e)), a), hn::Eq(hn::Max(floor, hn::Set(d16, top)), floor));
        if (top < j.rule.special_threshold) done = hn::Or(done, is_special);
        if (hn::AllTrue(d16, done)) break;
      }
    }
    if (dx == cap)
    {
      const auto m0 = hn::Min(hn::LoadU(d16, sx - dx), hn::LoadU(d16, sx + dx));
      a0 = hn::Min(a0, hn::SaturatedAdd(m0, square(dx)));
    }
    const int len = std::min(N, n - x);
    uint8_t* o = out + x;
#if HWY_TARGET == HWY_SCALAR
    hn::StoreU(hn::Min(a0, a1), d16, acc_buf);
    for (int i = 0; i < N; ++i)
      cost_buf[i] = table[acc_buf[i]];
    const auto costs = hn::LoadU(d8, cost_buf);
#else
    // The costs by two gathers of 32-bit words at byte offsets d2 of the table (its low byte is the
    // cost; the table has 3 bytes of slack past its end).
    const hn::Half<decltype(d16)> dh;
    const hn::Rebind<uint32_t, decltype(dh)> d32;
    const hn::RebindToSigned<decltype(d32)> di32;
    const hn::Half<decltype(d8)> d8h;
    const auto a = hn::Min(a0, a1);
    const auto* words = reinterpret_cast<const uint32_t*>(table);
    const auto low_byte = hn::Set(d32, 0xFF);
    const auto lo = hn::GatherOffset(d32, words, hn::BitCast(di32, hn::PromoteTo(d32, hn::LowerHalf(dh, a))));
    const auto hi = hn::GatherOffset(d32, words, hn::BitCast(di32, hn::PromoteTo(d32, hn::UpperHalf(dh, a))));
    const auto costs = hn::Combine(d8, hn::DemoteTo(d8h, hn::BitCast(di32, hn::And(hi, low_byte))),
                                   hn::DemoteTo(d8h, hn::BitCast(di32, hn::And(lo, low_byte))));
    if (len < N) hn::StoreU(costs, d8, cost_buf);
#endif
    if (len == N)
      hn::StoreU(mergeRule(d8, hn::LoadU(d8, o), costs, j.rule), d8, o);
    else
      for (int i = 0; i < len; ++i)
      {
        const uint8_t old = o[i], c = cost_buf[i];
        const uint8_t for_special = c >= j.rule.special_threshold ? c : j.rule.special;
        o[i] = old == j.rule.special ? for_special : std::max(old, c);
      }
  }
}

/// The vertical pass in stripes of rows and the row pass per row (in decreasing y within a stripe, so
/// that each grid row is read, as a source row, before it is written).
/// K: tables per column offset in the cost domain, 0 for 16-bit squared distances.
template <int K>
void runJob(const dt::Job& j)
{
  const int cap = j.cap;
  const DistanceWindow& win = j.win;
  const int cx0 = j.cx0, cw = j.cx1 - j.cx0;
  const int ry1 = j.ry1;
  const int n = win.x1 - win.x0;
  const uint8_t lo = j.source.lo;
  const uint8_t span = static_cast<uint8_t>(j.source.hi - j.source.lo);
  // Distances are stored biased in the cost domain by 16-entry tables (see kBias).
  constexpr bool kTables16 = K > 0 && K <= 4;
  const uint8_t base = kTables16 ? dt::kBias : uint8_t{0};
  const uint8_t far = static_cast<uint8_t>(base + cap + 1);
  const int band_off = j.pad + (cx0 - win.x0);  // offset of column cx0 in a stripe row
  // The tables each group of offsets needs: those up to the last with a cost at vertical distance 0
  // (a larger distance costs no more).
  uint8_t group_tables[(dt::kMaxCostDomainReach + dt::kGroup - 1) / dt::kGroup + 1] = {};
  if (kTables16)
    for (int i = 0, dx = 1; dx <= cap; ++i, dx += dt::kGroup)
      for (int k = 0; k < K; ++k)
        if (j.offset_tables[16 * K * dx + 16 * k] > 0) group_tables[i] = static_cast<uint8_t>(k + 1);
  auto src = [&](int y) { return j.src_rows[y - j.ry0]; };
  bool painting = true;  // whether the last row that could paint did so (see below)
  int rows_done = 0;
  const int blocks = (n + static_cast<int>(hn::Lanes(hn::ScalableTag<uint8_t>())) - 1) /
                     static_cast<int>(hn::Lanes(hn::ScalableTag<uint8_t>()));

  // Columns outside the band stay far in every stripe row.
  const int used_rows = std::min(j.stripe, win.y1 - win.y0);
  std::memset(j.rows, far, static_cast<std::size_t>(used_rows) * static_cast<std::size_t>(j.row_stride));

  // The rows above the window: the downward distance only.
  std::memset(j.run, far, static_cast<std::size_t>(cw));
  for (int y = j.ry0; y < win.y0; ++y)
    verticalStep(src(y), j.run, j.run, cw, lo, span, base, far);

  for (int s0 = win.y0; s0 < win.y1; s0 += j.stripe)
  {
    const int s1 = std::min(win.y1, s0 + j.stripe);
    const uint8_t* above = j.run;
    for (int y = s0; y < s1; ++y)
    {
      uint8_t* dst = j.rows + static_cast<std::size_t>(y - s0) * j.row_stride + band_off;
      verticalStep(src(y), above, dst, cw, lo, span, base, far);
      above = dst;
    }
    std::memcpy(j.run, above, static_cast<std::size_t>(cw));
    // The upward distance of the row after the stripe: the nearest source among the next cap rows.
    std::memset(j.up, far, static_cast<std::size_t>(cw));
    const int top = std::min(ry1, s1 + cap);
    for (int y = s1; y < top; ++y)
      lookaheadStep(src(y), j.up, cw, lo, span, static_cast<uint8_t>(base + (y - s1)), far);
    const uint8_t* below = j.up;
    const uint8_t* costed = nullptr;  // sink mode: the band of the row whose costs out_row holds
    for (int y = s1 - 1; y >= s0; --y)
    {
      uint8_t* gr = j.rows + static_cast<std::size_t>(y - s0) * j.row_stride;
      uint8_t* dst = gr + band_off;
      upwardStep(below, dst, cw, far);
      below = dst;
      uint8_t* out;
      if (j.sink != nullptr)
      {
        // The costs of a row depend on its vertical distances only: a row whose band equals the one
        // before reuses its costs. Otherwise a zero start makes the merge rule leave exactly the cost.
        if (costed != nullptr && std::memcmp(costed, dst, static_cast<std::size_t>(cw)) == 0)
        {
          (*j.sink)(y, j.out_row);
          continue;
        }
        std::memset(j.out_row, 0, static_cast<std::size_t>(n));
        out = j.out_row;
        costed = dst;
      }
      else
        out = j.target + y * j.target_stride + win.x0;
      // The first row costed (rows go up within a stripe) runs the offsets in every block, which
      // records how many each block takes (gather_est, for paintChoice; a block records it again
      // whenever it runs them). The rows after it paint where that looks cheaper, each after listing
      // its columns (listPainted), as long as the row before painted listed columns in at least
      // 1 / kPaintRowShare of its blocks; every kPaintProbe rows one looks again.
      const bool paint = K > 0 && j.paint != nullptr && rows_done > 0 && (painting || rows_done % dt::kPaintProbe == 0);
      ++rows_done;
      if (paint) listPainted(gr + j.pad, n, j, base, far);
      int painted = 0;
      if constexpr (K == dt::kWide64 || K == dt::kWide128)
      {
#if HWY_TARGET == HWY_AVX3_DL
        // Two instances, so that the rows that do not paint run the offset loop without the painting
        // code beside it (which cost them about 10 % on willow, likely registers).
        painted = paint ? rowPassWide<K, true>(gr + j.pad, out, n, j) : rowPassWide<K, false>(gr + j.pad, out, n, j);
#endif
      }
      else if constexpr (kTables16)
      {
        constexpr int KK = kTables16 ? K : 1;
        painted = paint ? rowPassCost8<KK, true>(gr + j.pad, out, n, j, group_tables)
                        : rowPassCost8<KK, false>(gr + j.pad, out, n, j, group_tables);
      }
      else
        rowPassSq16(gr + j.pad, out, n, j);
      if (paint) painting = painted * dt::kPaintRowShare >= blocks;
      if (j.sink != nullptr) (*j.sink)(y, j.out_row);
    }
  }
}

void RunDistanceJob(const dt::Job& j)
{
#if HWY_TARGET == HWY_AVX3_DL
  // The tables exist for the reaches the permute is for (kMinWideReach .. kMaxWideReach).
  if (j.wide_tables != nullptr)
  {
    // The index of vpermb is a distance up to cap + 1 (its low 6 bits), of vpermt2b up to 127.
    if (j.cap + 1 < 64)
      runJob<dt::kWide64>(j);
    else
      runJob<dt::kWide128>(j);
    return;
  }
#endif
  switch (j.cap <= dt::kMaxCostDomainReach ? dt::tablesPerOffset(j.cap) : 0)
  {
    case 1:
      runJob<1>(j);
      break;
    case 2:
      runJob<2>(j);
      break;
    case 3:
      runJob<3>(j);
      break;
    case 4:
      runJob<4>(j);
      break;
    default:
      runJob<0>(j);
  }
}
}  // namespace HWY_NAMESPACE
}  // namespace costmap_layers
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace costmap_layers
{
HWY_EXPORT(RunDistanceJob);

void runDistanceJob(const dt::Job& job)
{
  HWY_DYNAMIC_DISPATCH(RunDistanceJob)(job);
}
}  // namespace costmap_layers
#endif  // HWY_ONCE
