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

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define COSTMAP_LAYERS_DT_AVX2_DISPATCH 1
#define COSTMAP_LAYERS_DT_INLINE inline __attribute__((always_inline))
#else
#define COSTMAP_LAYERS_DT_INLINE inline
#endif

namespace costmap_layers
{
namespace
{
/// Vertical distances saturate here in the exact transform (no overflow on + 1).
constexpr uint32_t kNoSourceInColumn = 0x7FFFFFFFu;

/// floor(num / den) for den > 0.
int64_t floorDiv(int64_t num, int64_t den) { return num >= 0 ? num / den : -((-num + den - 1) / den); }
}  // namespace

void squaredDistanceTransform(const uint8_t* grid, int width, int height, std::ptrdiff_t stride,
                              SourceRange source, uint32_t* out, std::ptrdiff_t out_stride, uint32_t max_sq_dist,
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
    for (int x = 0; x < width; ++x) g[x] = std::min(g[x], std::min(next[x] + 1u, kNoSourceInColumn));
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

  auto advance = [&](int y) {
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
    for (int k = 0; k < n; ++k) acc[k] = g[k];
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

bool cpuHasAvx2()
{
  static const bool has = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
  }();
  return has;
}
#endif

std::atomic<bool> g_allow_simd{true};

bool useAvx2()
{
#ifdef COSTMAP_LAYERS_DT_AVX2_DISPATCH
  return g_allow_simd.load(std::memory_order_relaxed) && cpuHasAvx2();
#else
  return false;
#endif
}

template <class T>
void runBanded(const uint8_t* grid, int width, int height, std::ptrdiff_t stride, SourceRange source, int cap,
               const DistanceWindow& window, std::vector<uint8_t>& run, std::vector<uint8_t>& up,
               std::vector<T>& row, std::vector<T>& acc, const std::function<void(int, const T*)>& sink)
{
  DistanceWindow win;
  win.x0 = std::max(0, window.x0);
  win.y0 = std::max(0, window.y0);
  win.x1 = std::min(width, window.x1);
  win.y1 = std::min(height, window.y1);
  if (win.x0 >= win.x1 || win.y0 >= win.y1 || cap < 0) return;
  const int cw = std::min(width, win.x1 + cap) - std::max(0, win.x0 - cap);
  const std::size_t n = static_cast<std::size_t>(win.x1 - win.x0);
  auto grow = [](auto& v, std::size_t size) {
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
  bandedPortable<T>(grid, width, height, stride, source, cap, win, run.data(), up.data(), row.data(), acc.data(),
                    sink);
}
}  // namespace

void cappedSquaredDistanceRows8(const uint8_t* grid, int width, int height, std::ptrdiff_t stride,
                                SourceRange source, int cap, const DistanceWindow& window,
                                DistanceTransformScratch& scratch, const DistanceRowSink8& sink)
{
  if (cap > kMaxBandedCap8) throw std::invalid_argument("cappedSquaredDistanceRows8: cap above kMaxBandedCap8");
  runBanded<uint8_t>(grid, width, height, stride, source, cap, window, scratch.run, scratch.up, scratch.row8,
                     scratch.acc8, sink);
}

void cappedSquaredDistanceRows16(const uint8_t* grid, int width, int height, std::ptrdiff_t stride,
                                 SourceRange source, int cap, const DistanceWindow& window,
                                 DistanceTransformScratch& scratch, const DistanceRowSink16& sink)
{
  if (cap > kMaxBandedCap16) throw std::invalid_argument("cappedSquaredDistanceRows16: cap above kMaxBandedCap16");
  runBanded<uint16_t>(grid, width, height, stride, source, cap, window, scratch.run, scratch.up, scratch.row16,
                      scratch.acc16, sink);
}

void setDistanceTransformSimd(bool allow) { g_allow_simd.store(allow, std::memory_order_relaxed); }

const char* distanceTransformKernel() { return useAvx2() ? "avx2" : "portable"; }
}  // namespace costmap_layers
