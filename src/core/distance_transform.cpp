#include "costmap_layers/core/distance_transform.hpp"

// The hot loops are written for the vectoriser; GCC enables it at -O2 only for trivially
// profitable loops, so this file asks for the full vectoriser (Clang vectorises at -O2 anyway).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("tree-vectorize", "vect-cost-model=dynamic")
#endif

#include <algorithm>
#include <atomic>
#include <cstring>
#include <stdexcept>
#include <string>

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define COSTMAP_LAYERS_DT_AVX2_DISPATCH 1
#include <immintrin.h>
#endif
#if defined(__aarch64__) && defined(__ARM_NEON)
#define COSTMAP_LAYERS_DT_NEON 1
#include <arm_neon.h>
#endif
#if defined(__GNUC__) || defined(__clang__)
#define COSTMAP_LAYERS_DT_INLINE inline __attribute__((always_inline))
#define COSTMAP_LAYERS_DT_PREFETCH(p) __builtin_prefetch((p), 0, 2)
#else
#define COSTMAP_LAYERS_DT_INLINE inline
#define COSTMAP_LAYERS_DT_PREFETCH(p) ((void)(p))
#endif

namespace costmap_layers
{
namespace
{
/// Vertical distances saturate here in the exact transform (no overflow on + 1).
constexpr uint32_t kNoSourceInColumn = 0x7FFFFFFFu;

/// floor(num / den) for den > 0.
int64_t floorDiv(int64_t num, int64_t den)
{
  return num >= 0 ? num / den : -((-num + den - 1) / den);
}
}  // namespace

void squaredDistanceTransform(const uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source,
                              uint32_t* out, std::ptrdiff_t out_stride, uint32_t max_sq_dist,
                              DistanceTransformScratch& scratch)
{
  if (width <= 0 || height <= 0) return;
  const uint8_t lo = source.lo;
  const uint8_t span = static_cast<uint8_t>(source.hi - source.lo);

  // Pass 1, per column (done row by row so that it vectorises across columns): vertical distance to
  // the nearest source above, then below.
  for (int y = 0; y < height; ++y)
  {
    const uint8_t* src = grid + y * stride;
    uint32_t* g = out + y * out_stride;
    const uint32_t* prev = y > 0 ? out + (y - 1) * out_stride : nullptr;
    for (int x = 0; x < width; ++x)
    {
      const uint32_t above = prev != nullptr ? std::min(prev[x] + 1u, kNoSourceInColumn) : kNoSourceInColumn;
      g[x] = static_cast<uint8_t>(src[x] - lo) <= span ? 0u : above;
    }
  }
  for (int y = height - 2; y >= 0; --y)
  {
    uint32_t* g = out + y * out_stride;
    const uint32_t* next = out + (y + 1) * out_stride;
    for (int x = 0; x < width; ++x)
      g[x] = std::min(g[x], std::min(next[x] + 1u, kNoSourceInColumn));
  }

  // Pass 2, per row: lower envelope of the parabolas (x - u)^2 + g(u)^2 over the columns u that have
  // a source (Meijster, Roerdink and Hesselink), all in 64-bit integers.
  scratch.row_f.resize(static_cast<std::size_t>(width));
  scratch.env_s.resize(static_cast<std::size_t>(width));
  scratch.env_t.resize(static_cast<std::size_t>(width));
  int64_t* f = scratch.row_f.data();
  int32_t* s = scratch.env_s.data();
  int32_t* t = scratch.env_t.data();
  for (int y = 0; y < height; ++y)
  {
    uint32_t* row = out + y * out_stride;
    for (int x = 0; x < width; ++x)
    {
      const int64_t g = row[x];
      f[x] = row[x] == kNoSourceInColumn ? -1 : g * g;
    }
    int q = -1;
    for (int u = 0; u < width; ++u)
    {
      if (f[u] < 0) continue;
      while (q >= 0)
      {
        const int64_t a = static_cast<int64_t>(t[q] - s[q]) * (t[q] - s[q]) + f[s[q]];
        const int64_t b = static_cast<int64_t>(t[q] - u) * (t[q] - u) + f[u];
        if (a <= b) break;
        --q;
      }
      if (q < 0)
      {
        q = 0;
        s[0] = u;
        t[0] = 0;
        continue;
      }
      // Last column where the parabola of s[q] is no worse than that of u.
      const int64_t i = s[q];
      const int64_t sep = floorDiv(static_cast<int64_t>(u) * u - i * i + f[u] - f[i], 2 * (u - i));
      const int64_t w = sep + 1;
      if (w < width)
      {
        ++q;
        s[q] = u;
        t[q] = static_cast<int32_t>(w);
      }
    }
    for (int x = width - 1; x >= 0; --x)
    {
      if (q < 0)
      {
        row[x] = kFarSquaredDistance;
        continue;
      }
      const int64_t dx = x - s[q];
      const int64_t d2 = dx * dx + f[s[q]];
      row[x] = d2 > static_cast<int64_t>(max_sq_dist) ? kFarSquaredDistance : static_cast<uint32_t>(d2);
      if (x == t[q]) --q;
    }
  }
}

namespace
{
/// The banded kernel. T is the lane type of the squared distances; the caller sized the buffers:
/// run and up (grid band width, up times the window height), row (band width + 2 cap), acc (window
/// width).
template <class T>
COSTMAP_LAYERS_DT_INLINE void bandedKernel(const uint8_t* grid, int width, int height, std::ptrdiff_t stride,
                                           SourceRange source, int cap, const DistanceWindow& win,
                                           uint8_t* __restrict run, uint8_t* __restrict up, T* __restrict row,
                                           T* __restrict acc, const std::function<void(int, const T*)>& sink)
{
  const int cx0 = std::max(0, win.x0 - cap), cx1 = std::min(width, win.x1 + cap);
  const int ry0 = std::max(0, win.y0 - cap), ry1 = std::min(height, win.y1 + cap);
  const int cw = cx1 - cx0;
  const int n = win.x1 - win.x0;
  const uint8_t lo = source.lo;
  const uint8_t span = static_cast<uint8_t>(source.hi - source.lo);
  const uint8_t far_g = static_cast<uint8_t>(cap + 1);
  const T far_sq = static_cast<T>(cap * cap + 1);

  auto advance = [&](int y)
  {
    const uint8_t* __restrict src = grid + y * stride + cx0;
    for (int k = 0; k < cw; ++k)
    {
      uint8_t r = static_cast<uint8_t>(run[k] + 1);
      r = r < far_g ? r : far_g;
      run[k] = static_cast<uint8_t>(src[k] - lo) <= span ? uint8_t{0} : r;
    }
  };

  // Upward pass: distance to the nearest source in the same column at a larger or equal y, swept from
  // the end of the band back to the window's first row; only the window's rows are kept.
  std::memset(run, far_g, static_cast<std::size_t>(cw));
  for (int y = ry1 - 1; y >= win.y0; --y)
  {
    advance(y);
    if (y < win.y1) std::memcpy(up + static_cast<std::size_t>(y - win.y0) * cw, run, static_cast<std::size_t>(cw));
  }

  // Downward pass, fused with the row pass and the sink.
  for (int k = 0; k < cap; ++k)
  {
    row[k] = far_sq;
    row[cap + cw + k] = far_sq;
  }
  T* __restrict band = row + cap;
  const T* __restrict g = band + (win.x0 - cx0);
  std::memset(run, far_g, static_cast<std::size_t>(cw));
  for (int y = ry0; y < win.y1; ++y)
  {
    advance(y);
    if (y < win.y0) continue;
    const uint8_t* __restrict u = up + static_cast<std::size_t>(y - win.y0) * cw;
    for (int k = 0; k < cw; ++k)
    {
      const T v = static_cast<T>(run[k] < u[k] ? run[k] : u[k]);
      const T sq = static_cast<T>(v * v);
      band[k] = sq < far_sq ? sq : far_sq;
    }
    for (int k = 0; k < n; ++k)
      acc[k] = g[k];
    for (int dx = 1; dx <= cap; ++dx)
    {
      const T c = static_cast<T>(dx * dx);
      const T* __restrict left = g - dx;
      const T* __restrict right = g + dx;
      for (int k = 0; k < n; ++k)
      {
        const T m = static_cast<T>((left[k] < right[k] ? left[k] : right[k]) + c);
        acc[k] = acc[k] < m ? acc[k] : m;
      }
    }
    sink(y, acc);
  }
}

template <class T>
void bandedPortable(const uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source, int cap,
                    const DistanceWindow& win, uint8_t* run, uint8_t* up, T* row, T* acc,
                    const std::function<void(int, const T*)>& sink)
{
  bandedKernel<T>(grid, width, height, stride, source, cap, win, run, up, row, acc, sink);
}

#ifdef COSTMAP_LAYERS_DT_AVX2_DISPATCH
template <class T>
__attribute__((target("avx2"))) void bandedAvx2(const uint8_t* grid, int width, int height, std::ptrdiff_t stride,
                                                SourceRange source, int cap, const DistanceWindow& win, uint8_t* run,
                                                uint8_t* up, T* row, T* acc,
                                                const std::function<void(int, const T*)>& sink)
{
  bandedKernel<T>(grid, width, height, stride, source, cap, win, run, up, row, acc, sink);
}
#endif

// ---- Kernel choice -------------------------------------------------------------------------------

enum Kernel : int
{
  kPortable = 0,
  kSse41 = 1,
  kAvx2 = 2,
  kAvx512 = 3,
  kNeon = 4,
  kKernelCount = 5,
  kAuto = -1
};
const char* const kKernelNames[kKernelCount] = {"portable", "sse4.1", "avx2", "avx512bw", "neon"};

bool cpuRuns(int k)
{
  switch (k)
  {
    case kPortable:
      return true;
#ifdef COSTMAP_LAYERS_DT_AVX2_DISPATCH
    case kSse41:
      __builtin_cpu_init();
      return __builtin_cpu_supports("sse4.1") != 0;
    case kAvx2:
      __builtin_cpu_init();
      return __builtin_cpu_supports("avx2") != 0;
    case kAvx512:
      __builtin_cpu_init();
      return __builtin_cpu_supports("avx512f") != 0 && __builtin_cpu_supports("avx512bw") != 0;
#endif
#ifdef COSTMAP_LAYERS_DT_NEON
    case kNeon:
      return true;  // part of AArch64
#endif
    default:
      return false;
  }
}

int bestKernel()
{
  static const int best = []
  {
    int b = kPortable;
    for (int k = 0; k < kKernelCount; ++k)
      if (cpuRuns(k)) b = k;
    return b;
  }();
  return best;
}

std::atomic<int> g_forced_kernel{kAuto};

int currentKernel()
{
  const int forced = g_forced_kernel.load(std::memory_order_relaxed);
  return forced == kAuto ? bestKernel() : forced;
}

#ifdef COSTMAP_LAYERS_DT_AVX2_DISPATCH
/// The banded row engines have an AVX2 clone only.
bool useAvx2()
{
  const int k = currentKernel();
  return k == kAvx2 || k == kAvx512;
}
#endif

template <class T>
void runBanded(const uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source, int cap,
               const DistanceWindow& window, std::vector<uint8_t>& run, std::vector<uint8_t>& up, std::vector<T>& row,
               std::vector<T>& acc, const std::function<void(int, const T*)>& sink)
{
  DistanceWindow win;
  win.x0 = std::max(0, window.x0);
  win.y0 = std::max(0, window.y0);
  win.x1 = std::min(width, window.x1);
  win.y1 = std::min(height, window.y1);
  if (win.x0 >= win.x1 || win.y0 >= win.y1 || cap < 0) return;
  const int cw = std::min(width, win.x1 + cap) - std::max(0, win.x0 - cap);
  const std::size_t n = static_cast<std::size_t>(win.x1 - win.x0);
  auto grow = [](auto& v, std::size_t size)
  {
    if (v.size() < size) v.resize(size);
  };
  grow(run, static_cast<std::size_t>(cw));
  grow(up, static_cast<std::size_t>(cw) * static_cast<std::size_t>(win.y1 - win.y0));
  grow(row, static_cast<std::size_t>(cw + 2 * cap));
  grow(acc, n);
#ifdef COSTMAP_LAYERS_DT_AVX2_DISPATCH
  if (useAvx2())
  {
    bandedAvx2<T>(grid, width, height, stride, source, cap, win, run.data(), up.data(), row.data(), acc.data(), sink);
    return;
  }
#endif
  bandedPortable<T>(grid, width, height, stride, source, cap, win, run.data(), up.data(), row.data(), acc.data(), sink);
}

// ---- Cost merge: the banded 8-bit transform in the cost domain, written into the grid ------------

/// Widest vector (bytes) of any kernel: the padding on both sides of a stripe row.
constexpr int kMaxLanes = 64;

/// One row of the row pass. g[k] is the vertical distance (saturated at cap + 1) of window column k,
/// readable for k in [-cap - kMaxLanes, n + cap + kMaxLanes); out is the grid row at the window.
struct MergeRow
{
  const uint8_t* g;
  uint8_t* out;
  int n;
};

/// Bytes per column offset in the tables: a 16-entry table repeated for every 128-bit lane.
constexpr int kLutRow = 64;

/// What the row passes share: the tables lut[kLutRow * dx + v] = cost of dx^2 + (v % 16)^2 (0 past
/// cap or for v % 16 > cap), and cost_sq, the cost per squared distance (256 entries, 0 past cap^2).
struct MergeConsts
{
  const uint8_t* lut;
  const uint8_t* cost_sq;
  uint8_t* sq_row;  ///< portable row pass: n + 2 * (cap + kMaxLanes) bytes of scratch
  int cap;
  uint8_t far;
  uint8_t special;
  uint8_t threshold;
};

COSTMAP_LAYERS_DT_INLINE uint8_t mergeCell(uint8_t old, uint8_t c, uint8_t special, uint8_t threshold)
{
  const uint8_t for_special = c >= threshold ? c : special;
  const uint8_t for_known = old > c ? old : c;
  return old == special ? for_special : for_known;
}

/// The portable row pass: squared distances by a min-plus over the column offsets (the compiler
/// vectorises every loop), one table lookup per cell, then the merge rule; blocks of kBlock columns
/// with no vertical distance below cap + 1 within cap are skipped.
COSTMAP_LAYERS_DT_INLINE void mergeRowPortable(const MergeRow& r, const MergeConsts& k)
{
  constexpr int kBlock = 64;
  const int cap = k.cap;
  const uint8_t far = k.far;
  const uint8_t far_sq = static_cast<uint8_t>(cap * cap + 1);
  // Squared vertical distances (capped at cap^2 + 1) of every column a block reads.
  uint8_t* __restrict sq = k.sq_row + cap;
  const uint8_t* __restrict gg = r.g;
  for (int i = -cap; i < r.n + cap + kBlock; ++i)
  {
    const uint8_t s = static_cast<uint8_t>(gg[i] * gg[i]);
    sq[i] = s < far_sq ? s : far_sq;
  }
  for (int x = 0; x < r.n; x += kBlock)
  {
    const uint8_t* __restrict g = r.g + x;
    uint8_t near = far;
    for (int i = -cap; i < kBlock + cap; ++i)
      near = g[i] < near ? g[i] : near;
    if (near >= far) continue;
    const uint8_t* __restrict q = sq + x;
    uint8_t d[kBlock];
    uint8_t c[kBlock];
    for (int i = 0; i < kBlock; ++i)
      d[i] = q[i];
    for (int dx = 1; dx <= cap; ++dx)
    {
      const uint8_t dx2 = static_cast<uint8_t>(dx * dx);
      for (int i = 0; i < kBlock; ++i)
      {
        const uint8_t m = static_cast<uint8_t>((q[i - dx] < q[i + dx] ? q[i - dx] : q[i + dx]) + dx2);
        d[i] = d[i] < m ? d[i] : m;
      }
    }
    for (int i = 0; i < kBlock; ++i)
      c[i] = k.cost_sq[d[i]];
    const int len = std::min(kBlock, r.n - x);
    uint8_t* __restrict out = r.out + x;
    for (int i = 0; i < len; ++i)
      out[i] = mergeCell(out[i], c[i], k.special, k.threshold);
  }
}

#ifdef COSTMAP_LAYERS_DT_AVX2_DISPATCH
__attribute__((target("sse4.1"), always_inline)) inline __m128i load(const uint8_t* p)
{
  return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
}
__attribute__((target("avx2"), always_inline)) inline __m256i load256(const uint8_t* p)
{
  return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
}
__attribute__((target("avx512f,avx512bw"), always_inline)) inline __m512i load512(const uint8_t* p)
{
  return _mm512_loadu_si512(p);
}

__attribute__((target("sse4.1"))) void mergeRowSse41(const MergeRow& r, const MergeConsts& k)
{
  constexpr int V = 16;
  const int cap = k.cap;
  const __m128i far = _mm_set1_epi8(static_cast<char>(k.far));
  const __m128i special = _mm_set1_epi8(static_cast<char>(k.special));
  const __m128i threshold = _mm_set1_epi8(static_cast<char>(k.threshold));
  for (int x = 0; x < r.n; x += V)
  {
    const uint8_t* g = r.g + x;
    __m128i near = load(g - cap);
    for (int o = V - cap;; o += V)
    {
      const int oo = o < cap ? o : cap;
      near = _mm_min_epu8(near, load(g + oo));
      if (oo == cap) break;
    }
    if (_mm_movemask_epi8(_mm_cmpeq_epi8(near, far)) == 0xFFFF) continue;
    // Two accumulators: the maxima of odd and even offsets form two shorter dependency chains.
    __m128i c = _mm_shuffle_epi8(load(k.lut), load(g));
    __m128i c1 = _mm_setzero_si128();
    int dx = 1;
    for (; dx < cap; dx += 2)
    {
      c1 = _mm_max_epu8(c1, _mm_shuffle_epi8(load(k.lut + kLutRow * dx), _mm_min_epu8(load(g - dx), load(g + dx))));
      const int e = dx + 1;
      c = _mm_max_epu8(c, _mm_shuffle_epi8(load(k.lut + kLutRow * e), _mm_min_epu8(load(g - e), load(g + e))));
    }
    if (dx == cap)
      c1 = _mm_max_epu8(c1, _mm_shuffle_epi8(load(k.lut + kLutRow * dx), _mm_min_epu8(load(g - dx), load(g + dx))));
    c = _mm_max_epu8(c, c1);
    uint8_t tmp[V];
    const bool whole = x + V <= r.n;
    uint8_t* dst = whole ? r.out + x : tmp;
    if (!whole) std::memcpy(tmp, r.out + x, static_cast<std::size_t>(r.n - x));
    const __m128i old = load(dst);
    const __m128i for_special = _mm_blendv_epi8(special, c, _mm_cmpeq_epi8(_mm_max_epu8(c, threshold), c));
    const __m128i res = _mm_blendv_epi8(_mm_max_epu8(old, c), for_special, _mm_cmpeq_epi8(old, special));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(dst), res);
    if (!whole) std::memcpy(r.out + x, tmp, static_cast<std::size_t>(r.n - x));
  }
}

__attribute__((target("avx2"))) void mergeRowAvx2(const MergeRow& r, const MergeConsts& k)
{
  constexpr int V = 32;
  const int cap = k.cap;
  const __m256i far = _mm256_set1_epi8(static_cast<char>(k.far));
  const __m256i special = _mm256_set1_epi8(static_cast<char>(k.special));
  const __m256i threshold = _mm256_set1_epi8(static_cast<char>(k.threshold));
  __m256i lut[kMaxBandedCap8 + 1];
  for (int dx = 0; dx <= cap; ++dx)
    lut[dx] = load256(k.lut + kLutRow * dx);
  for (int x = 0; x < r.n; x += V)
  {
    const uint8_t* g = r.g + x;
    __m256i near = load256(g - cap);
    for (int o = V - cap;; o += V)
    {
      const int oo = o < cap ? o : cap;
      near = _mm256_min_epu8(near, load256(g + oo));
      if (oo == cap) break;
    }
    if (_mm256_movemask_epi8(_mm256_cmpeq_epi8(near, far)) == -1) continue;
    // Two accumulators: the maxima of odd and even offsets form two shorter dependency chains.
    __m256i c = _mm256_shuffle_epi8(lut[0], load256(g));
    __m256i c1 = _mm256_setzero_si256();
    int dx = 1;
    for (; dx < cap; dx += 2)
    {
      c1 = _mm256_max_epu8(c1, _mm256_shuffle_epi8(lut[dx], _mm256_min_epu8(load256(g - dx), load256(g + dx))));
      const int e = dx + 1;
      c = _mm256_max_epu8(c, _mm256_shuffle_epi8(lut[e], _mm256_min_epu8(load256(g - e), load256(g + e))));
    }
    if (dx == cap)
      c1 = _mm256_max_epu8(c1, _mm256_shuffle_epi8(lut[dx], _mm256_min_epu8(load256(g - dx), load256(g + dx))));
    c = _mm256_max_epu8(c, c1);
    uint8_t tmp[V];
    const bool whole = x + V <= r.n;
    uint8_t* dst = whole ? r.out + x : tmp;
    if (!whole) std::memcpy(tmp, r.out + x, static_cast<std::size_t>(r.n - x));
    const __m256i old = load256(dst);
    const __m256i for_special = _mm256_blendv_epi8(special, c, _mm256_cmpeq_epi8(_mm256_max_epu8(c, threshold), c));
    const __m256i res = _mm256_blendv_epi8(_mm256_max_epu8(old, c), for_special, _mm256_cmpeq_epi8(old, special));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst), res);
    if (!whole) std::memcpy(r.out + x, tmp, static_cast<std::size_t>(r.n - x));
  }
}

__attribute__((target("avx512f,avx512bw"))) void mergeRowAvx512(const MergeRow& r, const MergeConsts& k)
{
  constexpr int V = 64;
  const int cap = k.cap;
  const __m512i far = _mm512_set1_epi8(static_cast<char>(k.far));
  const __m512i special = _mm512_set1_epi8(static_cast<char>(k.special));
  const __m512i threshold = _mm512_set1_epi8(static_cast<char>(k.threshold));
  __m512i lut[kMaxBandedCap8 + 1];
  for (int dx = 0; dx <= cap; ++dx)
    lut[dx] = load512(k.lut + kLutRow * dx);
  for (int x = 0; x < r.n; x += V)
  {
    const uint8_t* g = r.g + x;
    __m512i near = load512(g - cap);
    for (int o = V - cap;; o += V)
    {
      const int oo = o < cap ? o : cap;
      near = _mm512_min_epu8(near, load512(g + oo));
      if (oo == cap) break;
    }
    if (_mm512_cmpneq_epu8_mask(near, far) == 0) continue;
    // Two accumulators: the maxima of odd and even offsets form two shorter dependency chains.
    __m512i c = _mm512_shuffle_epi8(lut[0], load512(g));
    __m512i c1 = _mm512_setzero_si512();
    int dx = 1;
    for (; dx < cap; dx += 2)
    {
      c1 = _mm512_max_epu8(c1, _mm512_shuffle_epi8(lut[dx], _mm512_min_epu8(load512(g - dx), load512(g + dx))));
      const int e = dx + 1;
      c = _mm512_max_epu8(c, _mm512_shuffle_epi8(lut[e], _mm512_min_epu8(load512(g - e), load512(g + e))));
    }
    if (dx == cap)
      c1 = _mm512_max_epu8(c1, _mm512_shuffle_epi8(lut[dx], _mm512_min_epu8(load512(g - dx), load512(g + dx))));
    c = _mm512_max_epu8(c, c1);
    const int left = r.n - x;
    const __mmask64 lanes = left >= V ? ~__mmask64{0} : ((__mmask64{1} << left) - 1);
    uint8_t* dst = r.out + x;
    const __m512i old = _mm512_maskz_loadu_epi8(lanes, dst);
    const __m512i for_special = _mm512_mask_blend_epi8(_mm512_cmpge_epu8_mask(c, threshold), special, c);
    const __m512i res =
        _mm512_mask_blend_epi8(_mm512_cmpeq_epi8_mask(old, special), _mm512_max_epu8(old, c), for_special);
    _mm512_mask_storeu_epi8(dst, lanes, res);
  }
}
#endif

#ifdef COSTMAP_LAYERS_DT_NEON
void mergeRowNeon(const MergeRow& r, const MergeConsts& k)
{
  constexpr int V = 16;
  const int cap = k.cap;
  const uint8x16_t special = vdupq_n_u8(k.special);
  const uint8x16_t threshold = vdupq_n_u8(k.threshold);
  uint8x16_t lut[kMaxBandedCap8 + 1];
  for (int dx = 0; dx <= cap; ++dx)
    lut[dx] = vld1q_u8(k.lut + kLutRow * dx);
  for (int x = 0; x < r.n; x += V)
  {
    const uint8_t* g = r.g + x;
    uint8x16_t near = vld1q_u8(g - cap);
    for (int o = V - cap;; o += V)
    {
      const int oo = o < cap ? o : cap;
      near = vminq_u8(near, vld1q_u8(g + oo));
      if (oo == cap) break;
    }
    if (vminvq_u8(near) >= k.far) continue;
    // Two accumulators: the maxima of odd and even offsets form two shorter dependency chains.
    uint8x16_t c = vqtbl1q_u8(lut[0], vld1q_u8(g));
    uint8x16_t c1 = vdupq_n_u8(0);
    int dx = 1;
    for (; dx < cap; dx += 2)
    {
      c1 = vmaxq_u8(c1, vqtbl1q_u8(lut[dx], vminq_u8(vld1q_u8(g - dx), vld1q_u8(g + dx))));
      const int e = dx + 1;
      c = vmaxq_u8(c, vqtbl1q_u8(lut[e], vminq_u8(vld1q_u8(g - e), vld1q_u8(g + e))));
    }
    if (dx == cap) c1 = vmaxq_u8(c1, vqtbl1q_u8(lut[dx], vminq_u8(vld1q_u8(g - dx), vld1q_u8(g + dx))));
    c = vmaxq_u8(c, c1);
    uint8_t tmp[V];
    const bool whole = x + V <= r.n;
    uint8_t* dst = whole ? r.out + x : tmp;
    if (!whole) std::memcpy(tmp, r.out + x, static_cast<std::size_t>(r.n - x));
    const uint8x16_t old = vld1q_u8(dst);
    const uint8x16_t for_special = vbslq_u8(vcgeq_u8(c, threshold), c, special);
    const uint8x16_t res = vbslq_u8(vceqq_u8(old, special), for_special, vmaxq_u8(old, c));
    vst1q_u8(dst, res);
    if (!whole) std::memcpy(r.out + x, tmp, static_cast<std::size_t>(r.n - x));
  }
}
#endif

/// Everything one merge needs; buffers sized by the caller.
struct MergeJob
{
  const uint8_t* grid;  // sources are read here
  uint8_t* target;      // merged in place (same cells as grid), or nullptr to stream rows to sink
  std::ptrdiff_t target_stride;
  uint8_t* out_row;  // sink mode: one window row, cleared before each row pass
  const CostRowSink* sink;
  int width, height;
  std::ptrdiff_t stride;
  SourceRange source;
  DistanceWindow win;  // clipped, non-empty
  MergeConsts consts;
  uint8_t* rows;  // stripe rows of row_stride bytes each; window column 0 at offset pad
  int row_stride;
  int pad;
  int stripe;    // rows per stripe
  uint8_t* run;  // the vertical distances of the row before the stripe, band width
  uint8_t* up;   // the upward running distance past the stripe, band width
};

/// The vertical pass, in stripes of rows, and the row pass per row (in decreasing y within a stripe:
/// each grid row is read, as a source row, before it is written). Vertical distances saturate at
/// cap + 1. RowPass is inlined into the caller's instruction set.
template <class RowPass>
COSTMAP_LAYERS_DT_INLINE void mergeDriver(const MergeJob& j, RowPass row_pass)
{
  const int cap = j.consts.cap;
  const DistanceWindow& win = j.win;
  const int cx0 = std::max(0, win.x0 - cap), cx1 = std::min(j.width, win.x1 + cap);
  const int ry0 = std::max(0, win.y0 - cap), ry1 = std::min(j.height, win.y1 + cap);
  const int cw = cx1 - cx0;
  const int n = win.x1 - win.x0;
  const uint8_t lo = j.source.lo;
  const uint8_t span = static_cast<uint8_t>(j.source.hi - j.source.lo);
  const uint8_t far = j.consts.far;
  const int band_off = j.pad + (cx0 - win.x0);  // offset of column cx0 in a stripe row

  // Columns outside the band stay far in every stripe row.
  const int used_rows = std::min(j.stripe, win.y1 - win.y0);
  std::memset(j.rows, far, static_cast<std::size_t>(used_rows) * static_cast<std::size_t>(j.row_stride));

  // The rows above the window: the downward distance only.
  uint8_t* __restrict run = j.run;
  std::memset(run, far, static_cast<std::size_t>(cw));
  for (int y = ry0; y < win.y0; ++y)
  {
    const uint8_t* __restrict src = j.grid + y * j.stride + cx0;
    for (int k = 0; k < cw; ++k)
    {
      uint8_t r = static_cast<uint8_t>(run[k] + 1);
      r = r < far ? r : far;
      run[k] = static_cast<uint8_t>(src[k] - lo) <= span ? uint8_t{0} : r;
    }
  }

  for (int s0 = win.y0; s0 < win.y1; s0 += j.stripe)
  {
    const int s1 = std::min(win.y1, s0 + j.stripe);
    // Downward through the stripe, reading the grid forward (as the hardware prefetchers expect).
    const uint8_t* above = run;
    for (int y = s0; y < s1; ++y)
    {
      const uint8_t* __restrict src = j.grid + y * j.stride + cx0;
      uint8_t* __restrict dst = j.rows + static_cast<std::size_t>(y - s0) * j.row_stride + band_off;
      const uint8_t* __restrict a = above;
      for (int k = 0; k < cw; ++k)
      {
        uint8_t r = static_cast<uint8_t>(a[k] + 1);
        r = r < far ? r : far;
        dst[k] = static_cast<uint8_t>(src[k] - lo) <= span ? uint8_t{0} : r;
      }
      above = dst;
    }
    std::memcpy(run, above, static_cast<std::size_t>(cw));
    // The upward distance of the row after the stripe: the nearest source among the next cap rows,
    // also read forward.
    uint8_t* __restrict up = j.up;
    std::memset(up, far, static_cast<std::size_t>(cw));
    const int top = std::min(ry1, s1 + cap);
    for (int y = s1; y < top; ++y)
    {
      const uint8_t* __restrict src = j.grid + y * j.stride + cx0;
      const uint8_t d = static_cast<uint8_t>(y - s1);
      for (int k = 0; k < cw; ++k)
      {
        const uint8_t v = static_cast<uint8_t>(src[k] - lo) <= span ? d : far;
        up[k] = up[k] < v ? up[k] : v;
      }
    }
    // Upward through the stripe, then the row pass, one row at a time while it is in cache. The
    // vertical distance of a row is min(its downward distance, the next row's vertical distance + 1).
    const uint8_t* below = up;
    const uint8_t* costed = nullptr;  // sink mode: the band of the row whose costs out_row holds
    for (int y = s1 - 1; y >= s0; --y)
    {
      uint8_t* __restrict gr = j.rows + static_cast<std::size_t>(y - s0) * j.row_stride;
      uint8_t* __restrict dst = gr + band_off;
      const uint8_t* __restrict b = below;
      for (int k = 0; k < cw; ++k)
      {
        uint8_t r = static_cast<uint8_t>(b[k] + 1);
        r = r < far ? r : far;
        dst[k] = dst[k] < r ? dst[k] : r;
      }
      below = dst;
      // Overlap the next stripe's memory reads with this stripe's work: one row per row, into the
      // level-2 cache (the grid is read there next, and the lookahead above has read cap rows of it).
      const int ahead = s1 + cap + (s1 - 1 - y);
      if (ahead < ry1)
      {
        const uint8_t* next = j.grid + ahead * j.stride + cx0;
        for (int k = 0; k < cw; k += 64)
          COSTMAP_LAYERS_DT_PREFETCH(next + k);
      }
      if (j.sink != nullptr)
      {
        // The costs of a row depend on its vertical distances only: a row whose band equals the one
        // before (long straight lanes, open space) reuses its costs. Otherwise a zero start makes the
        // merge rule (old 0 is never special) leave exactly the cost.
        if (costed == nullptr || std::memcmp(costed, dst, static_cast<std::size_t>(cw)) != 0)
        {
          std::memset(j.out_row, 0, static_cast<std::size_t>(n));
          row_pass(MergeRow{gr + j.pad, j.out_row, n}, j.consts);
          costed = dst;
        }
        (*j.sink)(y, j.out_row);
      }
      else
        row_pass(MergeRow{gr + j.pad, j.target + y * j.target_stride + win.x0, n}, j.consts);
    }
  }
}

void mergePortable(const MergeJob& j)
{
  mergeDriver(j, mergeRowPortable);
}

#ifdef COSTMAP_LAYERS_DT_AVX2_DISPATCH
__attribute__((target("sse4.1"))) void mergeSse41(const MergeJob& j)
{
  mergeDriver(j, mergeRowSse41);
}
__attribute__((target("avx2"))) void mergeAvx2(const MergeJob& j)
{
  mergeDriver(j, mergeRowAvx2);
}
__attribute__((target("avx512f,avx512bw"))) void mergeAvx512(const MergeJob& j)
{
  mergeDriver(j, mergeRowAvx512);
}
#endif
#ifdef COSTMAP_LAYERS_DT_NEON
void mergeNeon(const MergeJob& j)
{
  mergeDriver(j, mergeRowNeon);
}
#endif
}  // namespace

void cappedSquaredDistanceRows8(const uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source,
                                int cap, const DistanceWindow& window, DistanceTransformScratch& scratch,
                                const DistanceRowSink8& sink)
{
  if (cap > kMaxBandedCap8) throw std::invalid_argument("cappedSquaredDistanceRows8: cap above kMaxBandedCap8");
  runBanded<uint8_t>(grid, width, height, stride, source, cap, window, scratch.run, scratch.up, scratch.row8,
                     scratch.acc8, sink);
}

void cappedSquaredDistanceRows16(const uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source,
                                 int cap, const DistanceWindow& window, DistanceTransformScratch& scratch,
                                 const DistanceRowSink16& sink)
{
  if (cap > kMaxBandedCap16) throw std::invalid_argument("cappedSquaredDistanceRows16: cap above kMaxBandedCap16");
  runBanded<uint16_t>(grid, width, height, stride, source, cap, window, scratch.run, scratch.up, scratch.row16,
                      scratch.acc16, sink);
}

namespace
{
/// The engine behind cappedCostMerge8 (target != nullptr: merged into target, which is grid) and
/// cappedCostRows8 (sink != nullptr).
void runCostMerge(const char* what, const uint8_t* grid, uint8_t* target, int width, int height, std::ptrdiff_t stride,
                  SourceRange source, int cap, const DistanceWindow& window, const uint8_t* cost_by_sq_dist,
                  CostMergeRule rule, DistanceTransformScratch& scratch, const CostRowSink* sink)
{
  if (cap < 0 || cap > kMaxBandedCap8)
    throw std::invalid_argument(std::string(what) + ": cap outside [0, kMaxBandedCap8]");
  if (rule.special_threshold == 0) throw std::invalid_argument(std::string(what) + ": special_threshold must be >= 1");
  const int cap_sq = cap * cap;
  for (int d2 = 1; d2 <= cap_sq; ++d2)
    if (cost_by_sq_dist[d2] > cost_by_sq_dist[d2 - 1])
      throw std::invalid_argument(std::string(what) + ": the cost table increases");
  DistanceWindow win;
  win.x0 = std::max(0, window.x0);
  win.y0 = std::max(0, window.y0);
  win.x1 = std::min(width, window.x1);
  win.y1 = std::min(height, window.y1);
  if (win.x0 >= win.x1 || win.y0 >= win.y1) return;

  // The tables: 16 entries per column offset, then 256 squared distances.
  const std::size_t lut_size = static_cast<std::size_t>(kLutRow * (cap + 1) + 256);
  if (scratch.merge_lut.size() < lut_size) scratch.merge_lut.resize(lut_size);
  uint8_t* lut = scratch.merge_lut.data();
  for (int dx = 0; dx <= cap; ++dx)
    for (int i = 0; i < kLutRow; ++i)
    {
      const int v = i % 16;
      const int d2 = dx * dx + v * v;
      lut[kLutRow * dx + i] = v <= cap && d2 <= cap_sq ? cost_by_sq_dist[d2] : uint8_t{0};
    }
  uint8_t* cost_sq = lut + kLutRow * (cap + 1);
  for (int d2 = 0; d2 < 256; ++d2)
    cost_sq[d2] = d2 <= cap_sq ? cost_by_sq_dist[d2] : uint8_t{0};

  const int n = win.x1 - win.x0;
  const int cw = std::min(width, win.x1 + cap) - std::max(0, win.x0 - cap);
  const int pad = cap + kMaxLanes;
  // Rows start on a cache line and window column 0 too: the row pass's aligned offsets then split
  // fewer loads across lines.
  const int row_stride = (n + 2 * pad + kMaxLanes - 1) / kMaxLanes * kMaxLanes;
  // A stripe of about 256 KiB: it stays in the level-2 cache between the two vertical sweeps.
  const int stripe = std::max(16, std::min(win.y1 - win.y0, (256 << 10) / row_stride));
  const std::size_t rows_size = static_cast<std::size_t>(stripe) * static_cast<std::size_t>(row_stride);
  if (scratch.merge_g.size() < rows_size + kMaxLanes) scratch.merge_g.resize(rows_size + kMaxLanes);
  if (scratch.run.size() < static_cast<std::size_t>(2 * cw + row_stride))
    scratch.run.resize(static_cast<std::size_t>(2 * cw + row_stride));

  if (sink != nullptr && scratch.merge_out.size() < static_cast<std::size_t>(n))
    scratch.merge_out.resize(static_cast<std::size_t>(n));

  MergeJob job;
  job.grid = grid;
  job.target = target;
  job.target_stride = stride;
  job.out_row = sink != nullptr ? scratch.merge_out.data() : nullptr;
  job.sink = sink;
  job.width = width;
  job.height = height;
  job.stride = stride;
  job.source = source;
  job.win = win;
  job.consts = MergeConsts{lut,
                           cost_sq,
                           scratch.run.data() + 2 * cw,
                           cap,
                           static_cast<uint8_t>(cap + 1),
                           rule.special,
                           rule.special_threshold};
  const std::size_t misalign = reinterpret_cast<std::uintptr_t>(scratch.merge_g.data() + pad) % kMaxLanes;
  job.rows = scratch.merge_g.data() + (misalign == 0 ? 0 : kMaxLanes - misalign);
  job.row_stride = row_stride;
  job.pad = pad;
  job.stripe = stripe;
  job.run = scratch.run.data();
  job.up = scratch.run.data() + cw;
  switch (currentKernel())
  {
#ifdef COSTMAP_LAYERS_DT_AVX2_DISPATCH
    case kSse41:
      mergeSse41(job);
      return;
    case kAvx2:
      mergeAvx2(job);
      return;
    case kAvx512:
      mergeAvx512(job);
      return;
#endif
#ifdef COSTMAP_LAYERS_DT_NEON
    case kNeon:
      mergeNeon(job);
      return;
#endif
    default:
      mergePortable(job);
  }
}
}  // namespace

void cappedCostMerge8(uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source, int cap,
                      const DistanceWindow& window, const uint8_t* cost_by_sq_dist, CostMergeRule rule,
                      DistanceTransformScratch& scratch)
{
  runCostMerge("cappedCostMerge8", grid, grid, width, height, stride, source, cap, window, cost_by_sq_dist, rule,
               scratch, nullptr);
}

void cappedCostRows8(const uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source, int cap,
                     const DistanceWindow& window, const uint8_t* cost_by_sq_dist, DistanceTransformScratch& scratch,
                     const CostRowSink& sink)
{
  runCostMerge("cappedCostRows8", grid, nullptr, width, height, stride, source, cap, window, cost_by_sq_dist,
               CostMergeRule{255, 255}, scratch, &sink);
}

void setDistanceTransformSimd(bool allow)
{
  g_forced_kernel.store(allow ? int{kAuto} : int{kPortable}, std::memory_order_relaxed);
}

std::vector<const char*> distanceTransformKernels()
{
  std::vector<const char*> names;
  for (int k = 0; k < kKernelCount; ++k)
    if (cpuRuns(k)) names.push_back(kKernelNames[k]);
  return names;
}

bool setDistanceTransformKernel(const char* name)
{
  if (name == nullptr || *name == '\0')
  {
    g_forced_kernel.store(kAuto, std::memory_order_relaxed);
    return true;
  }
  for (int k = 0; k < kKernelCount; ++k)
    if (std::strcmp(name, kKernelNames[k]) == 0 && cpuRuns(k))
    {
      g_forced_kernel.store(k, std::memory_order_relaxed);
      return true;
    }
  return false;
}

const char* distanceTransformKernel()
{
  return kKernelNames[currentKernel()];
}
}  // namespace costmap_layers
