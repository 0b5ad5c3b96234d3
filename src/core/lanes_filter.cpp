// The per-cell passes are plain byte loops meant for the vectoriser, which GCC runs at -O2 only for
// trivially profitable loops: ask for it here, as the distance transform does.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("tree-vectorize", "vect-cost-model=dynamic")
#endif
#include "costmap_layers/core/lanes_filter.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

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

/// The keepout cost of a mask value, round(v * 254 / 100) for v in 1..100, else 0, in 16-bit integer
/// arithmetic so that loops over it vectorise: for v >= 1, round-half-up of 2.54 v is (254 v + 50) / 100
/// (at most 64820, within 16 bits).
inline uint8_t softCost(int8_t v)
{
  const auto u = static_cast<uint8_t>(v);
  const auto c = static_cast<uint8_t>(static_cast<uint16_t>(u * 254u + 50u) / 100u);
  return static_cast<uint8_t>(u - 1u) < 100u ? c : uint8_t{0};
}

/// Counts values outside -1..100 (invalid in an OccupancyGrid) and, when lanes is not null, writes 1 for
/// lane cells and 0 for others into it. Counted in blocks with 32-bit counters so that it vectorises.
std::size_t scanMask(const int8_t* m, std::size_t n, uint8_t* lanes)
{
  constexpr std::size_t kBlock = 1 << 16;
  std::size_t invalid = 0;
  for (std::size_t o = 0; o < n; o += kBlock)
  {
    const std::size_t e = std::min(n, o + kBlock);
    uint32_t count = 0;
    if (lanes)
      for (std::size_t k = o; k < e; ++k)
      {
        const auto u = static_cast<uint8_t>(m[k]);
        lanes[k] = u == static_cast<uint8_t>(kLane) ? 1 : 0;
        count += static_cast<uint8_t>(u + 1u) > 101u ? 1u : 0u;
      }
    else
      for (std::size_t k = o; k < e; ++k) count += static_cast<uint8_t>(static_cast<uint8_t>(m[k]) + 1u) > 101u ? 1u : 0u;
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
    out[x] = v == kForbidden ? lut[std::min<std::size_t>(sq_dist[x], lut_last)] : softCost(v);
  }
}

/// Final pass of the cost-merge engine: out holds 254 - cost for forbidden cells (0 beyond the band).
void finishCosts(const int8_t* m, uint8_t* out, std::size_t n)
{
  for (std::size_t k = 0; k < n; ++k)
  {
    const int8_t v = m[k];
    const auto forbidden = static_cast<uint8_t>(LETHAL_OBSTACLE - out[k]);
    out[k] = v == kForbidden ? forbidden : softCost(v);
  }
}
}  // namespace

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
  while (q > 0 && lethal(q - 1)) --q;
  while (!lethal(q)) ++q;
  return q;
}

void LanesFilter::onInitializeFilter(const ParamReader& params) { config_ = parseLanesFilterConfig(params); }

std::size_t LanesFilter::computeCosts(const OccupancyGridData& mask, std::vector<uint8_t>& costs)
{
  ++cost_computations_;
  const int w = static_cast<int>(mask.width), h = static_cast<int>(mask.height);
  const std::size_t n = mask.data.size();
  costs.resize(n);
  const int8_t* m = mask.data.data();
  const auto* bytes = reinterpret_cast<const uint8_t*>(m);
  const uint64_t q = lanesLethalSquaredDistance(config_, mask.resolution);
  const bool any_lane = std::memchr(bytes, static_cast<uint8_t>(kLane), n) != nullptr;

  if (!any_lane || q <= 1)
  {
    // No distance below the lethal one: every forbidden cell is lethal (254 - 0).
    std::memset(costs.data(), 0, n);
    finishCosts(m, costs.data(), n);
    return scanMask(m, n, nullptr);
  }

  // Every squared distance below q must come out exactly: a band of radius cap with cap^2 >= q - 1.
  uint64_t cap = static_cast<uint64_t>(std::sqrt(static_cast<double>(q - 1)));
  while (cap * cap < q - 1) ++cap;
  while (cap > 0 && (cap - 1) * (cap - 1) >= q - 1) --cap;

  auto buildLut = [&](std::vector<uint8_t>& lut, std::size_t entries) {
    lut.resize(entries);
    for (std::size_t d2 = 0; d2 < entries; ++d2)
      lut[d2] = d2 >= q ? LETHAL_OBSTACLE
                        : lanesForbiddenCost(config_, std::sqrt(static_cast<double>(d2)) * mask.resolution,
                                             mask.resolution);
  };
  const DistanceWindow all{0, 0, w, h};
  std::vector<uint8_t> lut;
  if (cap <= static_cast<uint64_t>(kMaxBandedCap8))
  {
    // The banded cost-domain engine wants a non-increasing table, merged with max into the grid: give
    // it 254 - cost (non-increasing since the cost never falls with distance; 0 beyond the band, where
    // everything is lethal) over a grid marking lane cells 1 and others 0, then turn it back.
    buildLut(lut, static_cast<std::size_t>(cap * cap) + 1);
    for (auto& c : lut) c = static_cast<uint8_t>(LETHAL_OBSTACLE - c);
    lut[0] = lut.size() > 1 ? lut[1] : 0;  // the lane cells themselves: never used
    const std::size_t invalid = scanMask(m, n, costs.data());
    cappedCostMerge8(costs.data(), w, h, w, SourceRange{1, 1}, static_cast<int>(cap), all, lut.data(),
                     CostMergeRule{255, 255}, scratch_);
    finishCosts(m, costs.data(), n);
    return invalid;
  }
  const std::size_t invalid = scanMask(m, n, nullptr);
  const SourceRange lanes{static_cast<uint8_t>(kLane), static_cast<uint8_t>(kLane)};
  if (cap <= static_cast<uint64_t>(kMaxBandedLanesCap))
  {
    buildLut(lut, 65536);
    cappedSquaredDistanceRows16(bytes, w, h, w, lanes, static_cast<int>(cap), all, scratch_,
                                [&](int y, const uint16_t* d2) {
                                  const std::size_t o = static_cast<std::size_t>(y) * w;
                                  writeRow(m + o, d2, lut.data(), 65535, costs.data() + o,
                                                      static_cast<std::size_t>(w));
                                });
    return invalid;
  }

  // Wide borders: the full transform, capped just below the lethal distance.
  sq_dist_.resize(n);
  const uint32_t max_sq = static_cast<uint32_t>(std::min<uint64_t>(q - 1, kFarSquaredDistance - 1));
  squaredDistanceTransform(bytes, w, h, w, lanes, sq_dist_.data(), w, max_sq, scratch_);
  if (q <= kMaxLutEntries)
  {
    buildLut(lut, static_cast<std::size_t>(q) + 1);  // the last entry (q) is lethal: farther cells map to it
    for (int y = 0; y < h; ++y)
    {
      const std::size_t o = static_cast<std::size_t>(y) * w;
      writeRow(m + o, sq_dist_.data() + o, lut.data(), static_cast<std::size_t>(q), costs.data() + o,
                          static_cast<std::size_t>(w));
    }
    return invalid;
  }
  for (std::size_t k = 0; k < n; ++k)
  {
    if (m[k] != kForbidden)
      costs[k] = softCost(m[k]);
    else if (sq_dist_[k] == kFarSquaredDistance)
      costs[k] = LETHAL_OBSTACLE;
    else
      costs[k] = lanesForbiddenCost(config_, std::sqrt(static_cast<double>(sq_dist_[k])) * mask.resolution,
                                    mask.resolution);
  }
  return invalid;
}
}  // namespace costmap_layers
