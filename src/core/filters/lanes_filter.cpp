// LanesFilter (see lanes_filter.hpp). The last step over the mask cells is written once with Highway
// (foreach_target.h compiles it per target; HWY_DYNAMIC_DISPATCH picks one at run time).
#include "costmap_layers/core/filters/lanes_filter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/rules/cost_rules.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/core/filters/lanes_filter.cpp"
#include <hwy/cache_control.h>
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace costmap_layers
{
namespace HWY_NAMESPACE
{
namespace hn = hwy::HWY_NAMESPACE;

/// One cell the scalar way: a forbidden cell (100) takes 254 - c, any other value its soft cost.
HWY_INLINE uint8_t finishCell(uint8_t v, uint8_t c, std::size_t& invalid)
{
  invalid += static_cast<uint8_t>(v + 1u) > 101u ? 1u : 0u;
  return v == 100u ? static_cast<uint8_t>(LETHAL_OBSTACLE - c) : maskValueCost(static_cast<int8_t>(v));
}

/// A block of lane (0), forbidden (100) and unknown (-1) cells only, what lane masks are made of, costs
/// a compare and a subtraction; a block holding anything else also computes soft costs,
/// (254 v + 50) / 100 in 16-bit lanes (the division as a multiply-high by 5243 and a shift by 16 + 3,
/// exact for v in 1..99, the only values it is kept for), and counts the invalid values.
std::size_t FinishLaneCosts(const uint8_t* HWY_RESTRICT u, const uint8_t* c, uint8_t* out, std::size_t n, bool stream)
{
  const hn::ScalableTag<uint8_t> d;
  const hn::ScalableTag<uint16_t> d16;
  const hn::Rebind<uint8_t, decltype(d16)> d8h;
  const hn::Rebind<int16_t, decltype(d16)> di16;
  const std::size_t N = hn::Lanes(d), N16 = hn::Lanes(d16);
  const auto forbidden = hn::Set(d, 100), unknown = hn::Set(d, 255), lethal = hn::Set(d, LETHAL_OBSTACLE);
  const auto k1 = hn::Set(d, 1), k98 = hn::Set(d, 98), k101 = hn::Set(d, 101);
  const auto k254 = hn::Set(d16, 254), k50 = hn::Set(d16, 50), kdiv = hn::Set(d16, 5243);
  HWY_ALIGN uint8_t soft_costs[64];
  std::size_t invalid = 0;
  std::size_t k = 0;
  if (stream)  // the streaming stores want aligned addresses
    for (; k < n && reinterpret_cast<std::uintptr_t>(out + k) % (N * sizeof(uint8_t)) != 0; ++k)
      out[k] = finishCell(u[k], c[k], invalid);
  for (; k + N <= n; k += N)
  {
    const auto v = hn::LoadU(d, u + k);
    const auto is_forbidden = hn::Eq(v, forbidden);
    auto res = hn::IfThenElseZero(is_forbidden, hn::Sub(lethal, hn::LoadU(d, c + k)));
    const auto plain = hn::Or(hn::Or(hn::Eq(v, hn::Zero(d)), is_forbidden), hn::Eq(v, unknown));
    if (!hn::AllTrue(d, plain))
    {
      const auto vm1 = hn::Sub(v, k1);
      const auto soft = hn::Eq(hn::Min(vm1, k98), vm1);  // v in 1..99
      const auto vp1 = hn::Add(v, k1);
      const auto valid = hn::Eq(hn::Max(vp1, k101), k101);  // v in -1..100
      invalid += hn::CountTrue(d, hn::Not(valid));
      for (std::size_t h = 0; h < N; h += N16)
      {
        const auto w = hn::PromoteTo(d16, hn::LoadU(d8h, u + k + h));
        const auto q = hn::ShiftRight<3>(hn::MulHigh(hn::Add(hn::Mul(w, k254), k50), kdiv));
        hn::StoreU(hn::DemoteTo(d8h, hn::BitCast(di16, q)), d8h, soft_costs + h);
      }
      res = hn::Or(res, hn::IfThenElseZero(soft, hn::Load(d, soft_costs)));
    }
    if (stream)
      hn::Stream(res, d, out + k);
    else
      hn::StoreU(res, d, out + k);
  }
  for (; k < n; ++k)
    out[k] = finishCell(u[k], c[k], invalid);
  return invalid;
}
}  // namespace HWY_NAMESPACE
}  // namespace costmap_layers
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace costmap_layers
{
HWY_EXPORT(FinishLaneCosts);

namespace
{
constexpr int8_t kLane = 0;
constexpr int8_t kForbidden = 100;

/// Costs grids from this size on are written with streaming stores: they would only evict the mask and
/// the engine's rows from the caches, and the next update reads them once.
constexpr std::size_t kStreamCostsFrom = std::size_t{8} << 20;

std::size_t finishCosts(const int8_t* m, const uint8_t* c, uint8_t* out, std::size_t n, bool stream)
{
  return HWY_DYNAMIC_DISPATCH(FinishLaneCosts)(reinterpret_cast<const uint8_t*>(m), c, out, n, stream);
}
}  // namespace

std::size_t lanesFinishCosts(const int8_t* mask, const uint8_t* c, uint8_t* out, std::size_t n, bool stream)
{
  const std::size_t invalid = finishCosts(mask, c, out, n, stream);
  if (stream) hwy::FlushStream();
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
  // overflowing.
  const uint64_t diagonal_sq =
      static_cast<uint64_t>(w) * static_cast<uint64_t>(w) + static_cast<uint64_t>(h) * static_cast<uint64_t>(h);
  const uint64_t q = std::min(lanesLethalSquaredDistance(config_, mask.resolution), diagonal_sq + 1);
  const bool any_lane = std::memchr(bytes, static_cast<uint8_t>(kLane), n) != nullptr;
  const bool stream = n >= kStreamCostsFrom;

  if (!any_lane || q <= 1)
  {
    // No distance below the lethal one: every forbidden cell is lethal (254 - 0).
    std::memset(costs.data(), 0, n);
    return finishCosts(m, costs.data(), costs.data(), n, false);
  }

  // Every squared distance below q must come out exactly: a band of cap cells with cap^2 >= q - 1.
  uint64_t cap = static_cast<uint64_t>(std::sqrt(static_cast<double>(q - 1)));
  while (cap * cap < q - 1)
    ++cap;
  // The engine wants a cost that does not increase with the distance: 254 - the cost (the cost never
  // falls as d grows), 0 from the lethal distance on; the lane cells themselves (d = 0) are never
  // forbidden, so they take the first cells' value.
  const double r = mask.resolution;
  const LanesFilterConfig config = config_;
  const DistanceCosts distance_costs(
      static_cast<int64_t>(cap),
      [&](uint64_t d2) -> uint8_t
      {
        if (d2 >= q) return 0;
        const double dist = std::sqrt(static_cast<double>(std::max<uint64_t>(d2, 1))) * r;
        return static_cast<uint8_t>(LETHAL_OBSTACLE - lanesForbiddenCost(config, dist, r));
      });
  std::size_t invalid = 0;
  const SourceRange lanes{static_cast<uint8_t>(kLane), static_cast<uint8_t>(kLane)};
  distanceCostRows(bytes, w, h, w, lanes, distance_costs, DistanceWindow{0, 0, w, h}, scratch_,
                   [&](int y, const uint8_t* row)
                   {
                     const std::size_t o = static_cast<std::size_t>(y) * static_cast<std::size_t>(w);
                     invalid += finishCosts(m + o, row, costs.data() + o, static_cast<std::size_t>(w), stream);
                   });
  if (stream) hwy::FlushStream();
  return invalid;
}
}  // namespace costmap_layers
#endif  // HWY_ONCE
