// The per-cell passes are plain byte loops meant for the vectoriser, which GCC runs at -O2 only for
// trivially profitable loops: ask for it here, as the distance transform does.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("tree-vectorize", "vect-cost-model=dynamic")
#endif
#include "costmap_layers/core/lanes_filter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#if defined(__SSE2__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#endif

#include "costmap_layers/core/cost_values.hpp"
#include "costmap_layers/core/param_reader.hpp"

namespace costmap_layers
{
namespace
{
constexpr int8_t kLane = 0;
constexpr int8_t kForbidden = 100;
/// Above this band radius [cells] the banded 16-bit transform (O(radius) per cell) gives way to the
/// full transform (O(1) per cell, larger constant).
constexpr int kMaxBandedLanesCap = 48;
/// The largest lookup table by squared distance built for the full transform; beyond, costs are
/// computed per cell.
constexpr uint64_t kMaxLutEntries = uint64_t{1} << 22;

/// Counts values outside -1..100 (invalid in an OccupancyGrid), in blocks with 32-bit counters so that
/// it vectorises.
std::size_t countInvalid(const int8_t* m, std::size_t n)
{
  constexpr std::size_t kBlock = 1 << 16;
  std::size_t invalid = 0;
  for (std::size_t o = 0; o < n; o += kBlock)
  {
    const std::size_t e = std::min(n, o + kBlock);
    uint32_t count = 0;
    for (std::size_t k = o; k < e; ++k)
      count += static_cast<uint8_t>(static_cast<uint8_t>(m[k]) + 1u) > 101u ? 1u : 0u;
    invalid += count;
  }
  return invalid;
}

/// Writes one mask row's costs: forbidden cells from the distance table, others their soft cost.
template <class D>
void writeRow(const int8_t* mask_row, const D* sq_dist, const uint8_t* lut, std::size_t lut_last, uint8_t* out,
              std::size_t n)
{
  for (std::size_t x = 0; x < n; ++x)
  {
    const int8_t v = mask_row[x];
    out[x] = v == kForbidden ? lut[std::min<std::size_t>(sq_dist[x], lut_last)] : maskValueCost(v);
  }
}

/// The final costs of n mask cells: a forbidden cell takes 254 - c[k] (c: 254 minus its distance cost,
/// 0 beyond the band), any other cell its soft cost. out may be c.
/// @return the number of values outside -1..100.
std::size_t finishCostsScalar(const uint8_t* u, const uint8_t* c, uint8_t* out, std::size_t n)
{
  std::size_t invalid = 0;
  for (std::size_t k = 0; k < n; ++k)
  {
    const uint8_t v = u[k];
    invalid += static_cast<uint8_t>(v + 1u) > 101u ? 1u : 0u;
    out[k] = v == static_cast<uint8_t>(kForbidden) ? static_cast<uint8_t>(LETHAL_OBSTACLE - c[k])
                                                   : maskValueCost(static_cast<int8_t>(v));
  }
  return invalid;
}

// The vector forms: a block of lane (0), forbidden (100) and unknown (-1) cells only, what lane masks
// are made of, costs a compare and a subtraction; a block holding anything else also computes soft
// costs, (254 v + 50) / 100 in 16-bit lanes (the division as a multiply-high by 5243 and a shift by
// 16 + 3, exact for v in 1..99, the only values it is kept for), and counts the invalid values.
#if defined(__SSE2__) && (defined(__GNUC__) || defined(__clang__))
#define COSTMAP_LAYERS_LANES_SIMD 1
template <bool kStream>
std::size_t finishCostsSse2(const uint8_t* u, const uint8_t* c, uint8_t* out, std::size_t n)
{
  const __m128i zero = _mm_setzero_si128();
  const __m128i forbidden = _mm_set1_epi8(static_cast<char>(kForbidden));
  const __m128i unknown = _mm_set1_epi8(-1);
  const __m128i lethal = _mm_set1_epi8(static_cast<char>(LETHAL_OBSTACLE));
  std::size_t invalid = 0;
  std::size_t k = 0;
  if (kStream)  // the streaming stores want aligned addresses
  {
    k = std::min(n, static_cast<std::size_t>(-reinterpret_cast<std::uintptr_t>(out) % 16));
    invalid = finishCostsScalar(u, c, out, k);
  }
  for (; k + 16 <= n; k += 16)
  {
    const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(u + k));
    const __m128i d = _mm_loadu_si128(reinterpret_cast<const __m128i*>(c + k));
    const __m128i is_forbidden = _mm_cmpeq_epi8(v, forbidden);
    __m128i res = _mm_and_si128(is_forbidden, _mm_sub_epi8(lethal, d));
    const __m128i plain = _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi8(v, zero), is_forbidden), _mm_cmpeq_epi8(v, unknown));
    if (_mm_movemask_epi8(plain) != 0xFFFF)
    {
      // soft: v - 1 < 99; valid: v + 1 <= 101 (unsigned bytes)
      const __m128i vm1 = _mm_sub_epi8(v, _mm_set1_epi8(1));
      const __m128i soft = _mm_cmpeq_epi8(_mm_min_epu8(vm1, _mm_set1_epi8(98)), vm1);
      const __m128i vp1 = _mm_add_epi8(v, _mm_set1_epi8(1));
      const __m128i valid = _mm_cmpeq_epi8(_mm_max_epu8(vp1, _mm_set1_epi8(101)), _mm_set1_epi8(101));
      invalid += static_cast<std::size_t>(__builtin_popcount(~_mm_movemask_epi8(valid) & 0xFFFF));
      const __m128i k254 = _mm_set1_epi16(254), k50 = _mm_set1_epi16(50), kdiv = _mm_set1_epi16(5243);
      __m128i lo = _mm_add_epi16(_mm_mullo_epi16(_mm_unpacklo_epi8(v, zero), k254), k50);
      __m128i hi = _mm_add_epi16(_mm_mullo_epi16(_mm_unpackhi_epi8(v, zero), k254), k50);
      lo = _mm_srli_epi16(_mm_mulhi_epu16(lo, kdiv), 3);
      hi = _mm_srli_epi16(_mm_mulhi_epu16(hi, kdiv), 3);
      res = _mm_or_si128(res, _mm_and_si128(soft, _mm_packus_epi16(lo, hi)));
    }
    if (kStream)
      _mm_stream_si128(reinterpret_cast<__m128i*>(out + k), res);
    else
      _mm_storeu_si128(reinterpret_cast<__m128i*>(out + k), res);
  }
  return invalid + finishCostsScalar(u + k, c + k, out + k, n - k);
}

template <bool kStream>
__attribute__((target("avx2"))) std::size_t finishCostsAvx2(const uint8_t* u, const uint8_t* c, uint8_t* out,
                                                            std::size_t n)
{
  const __m256i zero = _mm256_setzero_si256();
  const __m256i forbidden = _mm256_set1_epi8(static_cast<char>(kForbidden));
  const __m256i unknown = _mm256_set1_epi8(-1);
  const __m256i lethal = _mm256_set1_epi8(static_cast<char>(LETHAL_OBSTACLE));
  std::size_t invalid = 0;
  std::size_t k = 0;
  if (kStream)  // the streaming stores want aligned addresses
  {
    k = std::min(n, static_cast<std::size_t>(-reinterpret_cast<std::uintptr_t>(out) % 32));
    invalid = finishCostsScalar(u, c, out, k);
  }
  for (; k + 32 <= n; k += 32)
  {
    const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(u + k));
    const __m256i d = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(c + k));
    const __m256i is_forbidden = _mm256_cmpeq_epi8(v, forbidden);
    __m256i res = _mm256_and_si256(is_forbidden, _mm256_sub_epi8(lethal, d));
    const __m256i plain =
        _mm256_or_si256(_mm256_or_si256(_mm256_cmpeq_epi8(v, zero), is_forbidden), _mm256_cmpeq_epi8(v, unknown));
    if (_mm256_movemask_epi8(plain) != -1)
    {
      const __m256i vm1 = _mm256_sub_epi8(v, _mm256_set1_epi8(1));
      const __m256i soft = _mm256_cmpeq_epi8(_mm256_min_epu8(vm1, _mm256_set1_epi8(98)), vm1);
      const __m256i vp1 = _mm256_add_epi8(v, _mm256_set1_epi8(1));
      const __m256i valid = _mm256_cmpeq_epi8(_mm256_max_epu8(vp1, _mm256_set1_epi8(101)), _mm256_set1_epi8(101));
      invalid += static_cast<std::size_t>(__builtin_popcount(~static_cast<unsigned>(_mm256_movemask_epi8(valid))));
      const __m256i k254 = _mm256_set1_epi16(254), k50 = _mm256_set1_epi16(50), kdiv = _mm256_set1_epi16(5243);
      __m256i lo = _mm256_add_epi16(_mm256_mullo_epi16(_mm256_unpacklo_epi8(v, zero), k254), k50);
      __m256i hi = _mm256_add_epi16(_mm256_mullo_epi16(_mm256_unpackhi_epi8(v, zero), k254), k50);
      lo = _mm256_srli_epi16(_mm256_mulhi_epu16(lo, kdiv), 3);
      hi = _mm256_srli_epi16(_mm256_mulhi_epu16(hi, kdiv), 3);
      res = _mm256_or_si256(res, _mm256_and_si256(soft, _mm256_packus_epi16(lo, hi)));
    }
    if (kStream)
      _mm256_stream_si256(reinterpret_cast<__m256i*>(out + k), res);
    else
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + k), res);
  }
  return invalid + finishCostsScalar(u + k, c + k, out + k, n - k);
}
#endif

/// @param stream  write around the caches (for a grid much larger than them, written once): the caller
///                then calls finishStreaming() before the costs are read
std::size_t finishCosts(const int8_t* m, const uint8_t* c, uint8_t* out, std::size_t n, bool stream)
{
  const auto* u = reinterpret_cast<const uint8_t*>(m);
#ifdef COSTMAP_LAYERS_LANES_SIMD
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (stream) return avx2 ? finishCostsAvx2<true>(u, c, out, n) : finishCostsSse2<true>(u, c, out, n);
  return avx2 ? finishCostsAvx2<false>(u, c, out, n) : finishCostsSse2<false>(u, c, out, n);
#else
  (void)stream;
  return finishCostsScalar(u, c, out, n);
#endif
}

/// Orders the streaming stores of finishCosts() before what follows.
void finishStreaming()
{
#ifdef COSTMAP_LAYERS_LANES_SIMD
  _mm_sfence();
#endif
}

/// Costs grids from this size on are written with streaming stores: they would only evict the mask and
/// the engine's rows from the caches, and the next update reads them once.
constexpr std::size_t kStreamCostsFrom = std::size_t{8} << 20;
}  // namespace

std::size_t lanesFinishCosts(const int8_t* mask, const uint8_t* c, uint8_t* out, std::size_t n, bool stream,
                             const char* kernel)
{
  const std::string k = kernel != nullptr ? kernel : "";
  std::size_t invalid = 0;
  if (k.empty())
    invalid = finishCosts(mask, c, out, n, stream);
  else if (k == "portable")
    return finishCostsScalar(reinterpret_cast<const uint8_t*>(mask), c, out, n);
#ifdef COSTMAP_LAYERS_LANES_SIMD
  else if (k == "sse2")
    invalid = stream ? finishCostsSse2<true>(reinterpret_cast<const uint8_t*>(mask), c, out, n)
                     : finishCostsSse2<false>(reinterpret_cast<const uint8_t*>(mask), c, out, n);
  else if (k == "avx2" && __builtin_cpu_supports("avx2"))
    invalid = stream ? finishCostsAvx2<true>(reinterpret_cast<const uint8_t*>(mask), c, out, n)
                     : finishCostsAvx2<false>(reinterpret_cast<const uint8_t*>(mask), c, out, n);
#endif
  else
    return std::numeric_limits<std::size_t>::max();
  if (stream) finishStreaming();
  return invalid;
}

LanesFilterConfig parseLanesFilterConfig(const ParamReader& params)
{
  LanesFilterConfig c;
  c.lane_border_width = params.getDouble("lane_border_width", c.lane_border_width, 0.0, 1e4);
  c.border_cost = params.getInt("border_cost", c.border_cost, 1, INSCRIBED_INFLATED_OBSTACLE);
  const std::string profile = params.getChoice("cost_profile", "linear", {"linear", "exponential"});
  c.cost_profile = profile == "exponential" ? LaneCostProfile::Exponential : LaneCostProfile::Linear;
  c.decay = params.getDouble("decay", c.decay, 1e-9, 1e6);
  return c;
}

uint8_t lanesForbiddenCost(const LanesFilterConfig& c, double d, double r)
{
  const double w = c.lane_border_width;
  if (!(d < w)) return LETHAL_OBSTACLE;  // also +infinity and NaN
  const double span = w - r;
  double s = 0.0;
  if (span > 0.0 && d > r)
  {
    if (c.cost_profile == LaneCostProfile::Linear)
      s = (d - r) / span;
    else
      // (e^{k(d-r)} - 1) / (e^{k(W-r)} - 1), written so that it neither overflows nor loses precision.
      s = std::exp(c.decay * (d - w)) * std::expm1(-c.decay * (d - r)) / std::expm1(-c.decay * span);
  }
  s = std::clamp(s, 0.0, 1.0);
  const double cost = c.border_cost + (INSCRIBED_INFLATED_OBSTACLE - c.border_cost) * s;
  return static_cast<uint8_t>(std::min<long>(std::lround(cost), INSCRIBED_INFLATED_OBSTACLE));
}

uint64_t lanesLethalSquaredDistance(const LanesFilterConfig& c, double r)
{
  auto lethal = [&](uint64_t q) { return std::sqrt(static_cast<double>(q)) * r >= c.lane_border_width; };
  const double ratio = c.lane_border_width / r;
  // Beyond any grid's reach (the validator caps masks at 4e8 cells): never lethal by distance.
  if (!(ratio < 1e9)) return std::numeric_limits<uint64_t>::max();
  uint64_t q = static_cast<uint64_t>(std::floor(ratio * ratio));
  while (q > 0 && lethal(q - 1))
    --q;
  while (!lethal(q))
    ++q;
  return q;
}

void LanesFilter::onInitializeFilter(const ParamReader& params)
{
  config_ = parseLanesFilterConfig(params);
}

void LanesFilter::onReconfigure(const ParamValue& params)
{
  config_ = parseLanesFilterConfig(ParamReader(params, name_));  // throws before anything changes
  invalidateCosts();
}

std::vector<ParamSpec> LanesFilter::tunableLayerParameters(const ParamValue& params) const
{
  return recordParameters(params, name_, [](const ParamReader& r) { parseLanesFilterConfig(r); });
}

std::size_t LanesFilter::computeCosts(const OccupancyGridData& mask, std::vector<uint8_t>& costs)
{
  ++cost_computations_;
  const int w = static_cast<int>(mask.width), h = static_cast<int>(mask.height);
  const std::size_t n = mask.data.size();
  costs.resize(n);
  const int8_t* m = mask.data.data();
  const auto* bytes = reinterpret_cast<const uint8_t*>(m);
  // No two cells of the mask are farther apart than its diagonal: a lethal distance beyond that (a wide
  // border on a fine mask, up to "never") changes nothing, and clamping it keeps cap * cap below from
  // overflowing (which looped forever).
  const uint64_t diagonal_sq =
      static_cast<uint64_t>(w) * static_cast<uint64_t>(w) + static_cast<uint64_t>(h) * static_cast<uint64_t>(h);
  const uint64_t q = std::min(lanesLethalSquaredDistance(config_, mask.resolution), diagonal_sq + 1);
  const bool any_lane = std::memchr(bytes, static_cast<uint8_t>(kLane), n) != nullptr;

  if (!any_lane || q <= 1)
  {
    // No distance below the lethal one: every forbidden cell is lethal (254 - 0).
    std::memset(costs.data(), 0, n);
    return finishCosts(m, costs.data(), costs.data(), n, false);
  }

  // Every squared distance below q must come out exactly: a band of radius cap with cap^2 >= q - 1.
  uint64_t cap = static_cast<uint64_t>(std::sqrt(static_cast<double>(q - 1)));
  while (cap * cap < q - 1)
    ++cap;
  while (cap > 0 && (cap - 1) * (cap - 1) >= q - 1)
    --cap;

  auto buildLut = [&](std::vector<uint8_t>& lut, std::size_t entries)
  {
    lut.resize(entries);
    for (std::size_t d2 = 0; d2 < entries; ++d2)
      lut[d2] =
          d2 >= q ? LETHAL_OBSTACLE
                  : lanesForbiddenCost(config_, std::sqrt(static_cast<double>(d2)) * mask.resolution, mask.resolution);
  };
  const DistanceWindow all{0, 0, w, h};
  std::vector<uint8_t> lut;
  if (cap <= static_cast<uint64_t>(kMaxBandedCap8))
  {
    // The banded cost-domain engine wants a non-increasing table: give it 254 - cost (non-increasing
    // since the cost never falls with distance; 0 beyond the band, where everything is lethal), with the
    // lane cells of the mask as sources, and turn each row back while it is in cache.
    buildLut(lut, static_cast<std::size_t>(cap * cap) + 1);
    for (auto& c : lut)
      c = static_cast<uint8_t>(LETHAL_OBSTACLE - c);
    lut[0] = lut.size() > 1 ? lut[1] : 0;  // the lane cells themselves: never used
    std::size_t invalid = 0;
    const SourceRange lanes{static_cast<uint8_t>(kLane), static_cast<uint8_t>(kLane)};
    const bool stream = n >= kStreamCostsFrom;
    cappedCostRows8(bytes, w, h, w, lanes, static_cast<int>(cap), all, lut.data(), scratch_,
                    [&](int y, const uint8_t* row)
                    {
                      const std::size_t o = static_cast<std::size_t>(y) * static_cast<std::size_t>(w);
                      invalid += finishCosts(m + o, row, costs.data() + o, static_cast<std::size_t>(w), stream);
                    });
    if (stream) finishStreaming();
    return invalid;
  }
  const std::size_t invalid = countInvalid(m, n);
  const SourceRange lanes{static_cast<uint8_t>(kLane), static_cast<uint8_t>(kLane)};
  if (cap <= static_cast<uint64_t>(kMaxBandedLanesCap))
  {
    buildLut(lut, 65536);
    cappedSquaredDistanceRows16(bytes, w, h, w, lanes, static_cast<int>(cap), all, scratch_,
                                [&](int y, const uint16_t* d2)
                                {
                                  const std::size_t o = static_cast<std::size_t>(y) * w;
                                  writeRow(m + o, d2, lut.data(), 65535, costs.data() + o, static_cast<std::size_t>(w));
                                });
    return invalid;
  }

  // Wide borders: the full transform, capped just below the lethal distance.
  sq_dist_.resize(n);
  const uint32_t max_sq = static_cast<uint32_t>(std::min<uint64_t>(q - 1, kFarSquaredDistance - 1));
  squaredDistanceTransform(bytes, w, h, w, lanes, sq_dist_.data(), w, max_sq, scratch_);
  // The table only needs the distances that occur (a tiny mask with a huge border in cells must not
  // build millions of entries): up to the largest one below q, then one lethal entry for the rest.
  uint64_t seen = 0;
  for (std::size_t k = 0; k < n; ++k)
    if (sq_dist_[k] < q) seen = std::max<uint64_t>(seen, sq_dist_[k]);
  if (seen < kMaxLutEntries)
  {
    buildLut(lut, static_cast<std::size_t>(seen) + 1);
    lut.push_back(LETHAL_OBSTACLE);  // index seen + 1: every cell at or beyond the lethal distance
    for (int y = 0; y < h; ++y)
    {
      const std::size_t o = static_cast<std::size_t>(y) * w;
      writeRow(m + o, sq_dist_.data() + o, lut.data(), static_cast<std::size_t>(seen) + 1, costs.data() + o,
               static_cast<std::size_t>(w));
    }
    return invalid;
  }
  for (std::size_t k = 0; k < n; ++k)
  {
    if (m[k] != kForbidden)
      costs[k] = maskValueCost(m[k]);
    else if (sq_dist_[k] == kFarSquaredDistance)
      costs[k] = LETHAL_OBSTACLE;
    else
      costs[k] =
          lanesForbiddenCost(config_, std::sqrt(static_cast<double>(sq_dist_[k])) * mask.resolution, mask.resolution);
  }
  return invalid;
}
}  // namespace costmap_layers
