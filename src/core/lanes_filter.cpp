#include "costmap_layers/core/lanes_filter.hpp"

#include <algorithm>
#include <array>
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

/// Per mask byte: the cost of everything but forbidden cells (0 for lanes, -1 and invalid values,
/// the soft cost for 1..99; 254 for 100, overridden by the distance cost), and whether it is invalid.
struct ValueTables
{
  std::array<uint8_t, 256> cost{};
  std::array<uint8_t, 256> invalid{};
  ValueTables()
  {
    for (int b = 0; b < 256; ++b)
    {
      const auto v = static_cast<int8_t>(b);
      cost[static_cast<std::size_t>(b)] = keepoutCost(v);
      invalid[static_cast<std::size_t>(b)] = (v < -1 || v > 100) ? 1 : 0;
    }
  }
};

const ValueTables& valueTables()
{
  static const ValueTables tables;
  return tables;
}

/// Writes one mask row's costs: forbidden cells from the distance table, others from the value table.
/// @return the number of invalid values in the row
template <class D>
std::size_t writeRow(const int8_t* mask_row, const D* sq_dist, const uint8_t* lut, std::size_t lut_last,
                     uint8_t* out, std::size_t n)
{
  const ValueTables& t = valueTables();
  std::size_t invalid = 0;
  for (std::size_t x = 0; x < n; ++x)
  {
    const auto b = static_cast<uint8_t>(mask_row[x]);
    invalid += t.invalid[b];
    const std::size_t d2 = std::min<std::size_t>(sq_dist[x], lut_last);
    out[x] = mask_row[x] == kForbidden ? lut[d2] : t.cost[b];
  }
  return invalid;
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

  std::size_t invalid = 0;
  if (!any_lane || q <= 1)
  {
    // No distance below the lethal one: forbidden cells are all lethal (the value table says 254).
    const uint8_t lethal = LETHAL_OBSTACLE;
    for (int y = 0; y < h; ++y)
    {
      const std::size_t o = static_cast<std::size_t>(y) * w;
      invalid += writeRow(m + o, bytes + o, &lethal, 0, costs.data() + o, static_cast<std::size_t>(w));
    }
    return invalid;
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
  const SourceRange lanes{static_cast<uint8_t>(kLane), static_cast<uint8_t>(kLane)};
  const DistanceWindow all{0, 0, w, h};
  std::vector<uint8_t> lut;
  if (cap <= static_cast<uint64_t>(kMaxBandedCap8))
  {
    buildLut(lut, 256);
    cappedSquaredDistanceRows8(bytes, w, h, w, lanes, static_cast<int>(cap), all, scratch_,
                               [&](int y, const uint8_t* d2) {
                                 const std::size_t o = static_cast<std::size_t>(y) * w;
                                 invalid += writeRow(m + o, d2, lut.data(), 255, costs.data() + o,
                                                     static_cast<std::size_t>(w));
                               });
    return invalid;
  }
  if (cap <= static_cast<uint64_t>(kMaxBandedLanesCap))
  {
    buildLut(lut, 65536);
    cappedSquaredDistanceRows16(bytes, w, h, w, lanes, static_cast<int>(cap), all, scratch_,
                                [&](int y, const uint16_t* d2) {
                                  const std::size_t o = static_cast<std::size_t>(y) * w;
                                  invalid += writeRow(m + o, d2, lut.data(), 65535, costs.data() + o,
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
      invalid += writeRow(m + o, sq_dist_.data() + o, lut.data(), static_cast<std::size_t>(q), costs.data() + o,
                          static_cast<std::size_t>(w));
    }
    return invalid;
  }
  const ValueTables& t = valueTables();
  for (std::size_t k = 0; k < n; ++k)
  {
    const auto b = bytes[k];
    invalid += t.invalid[b];
    if (m[k] != kForbidden)
      costs[k] = t.cost[b];
    else if (sq_dist_[k] == kFarSquaredDistance)
      costs[k] = LETHAL_OBSTACLE;
    else
      costs[k] = lanesForbiddenCost(config_, std::sqrt(static_cast<double>(sq_dist_[k])) * mask.resolution,
                                    mask.resolution);
  }
  return invalid;
}
}  // namespace costmap_layers
