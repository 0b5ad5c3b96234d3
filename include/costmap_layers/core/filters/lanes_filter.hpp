// LanesFilter: keeps the robot on lanes. The mask marks lanes and other permitted areas with 0,
// forbidden space with 100 and "no opinion" with -1; values 1..99 are soft costs as in KeepoutFilter
// (round(v * 254 / 100)). Lane cells and -1 cells write nothing (other layers' costs stay).
//
// A forbidden cell's cost grows with d, the exact Euclidean distance [m] between its centre and the
// centre of the nearest lane cell (a 0 cell) of the mask, so that a robot drifting off a lane meets a
// rising slope and then a wall:
//   d >= lane_border_width  ->  254 (LETHAL)
//   d <  lane_border_width  ->  round(border_cost + (253 - border_cost) * s), at most 253, where with
//                               r the mask resolution [m] (the smallest d a forbidden cell can have),
//                               W = lane_border_width and k = decay [1/m]:
//       linear:       s = (d - r) / (W - r)
//       exponential:  s = (exp(k (d - r)) - 1) / (exp(k (W - r)) - 1)
//                     (convex: the cost stays near border_cost close to the lane and climbs steeply
//                     towards W; as k -> 0 it becomes linear)
// So the first cells outside a lane (d = r) cost exactly border_cost, diagonal-only neighbours
// (d = r * sqrt(2)) a little more, the cost never falls as d grows, and everything at or beyond W is
// lethal. Without any lane cell in the mask, every forbidden cell is lethal. With W <= r every
// forbidden cell is lethal.
//
// The costs are computed once per mask, on the mask grid (the core's distance engine from the lane
// cells, up to W), and sampled at master cell centres by the base's mapping.
// Merging follows mergeFilterCost (higher cost wins; an unknown master cell takes only costs >= 253).
//
// Parameters (in the filter's namespace):
//   mask_topic         "/map_filter"  (read by the base)
//   lane_border_width  0.5     [m], >= 0
//   border_cost        1       1..253
//   cost_profile       "linear" | "exponential"
//   decay              10.0    [1/m], > 0, exponential profile only
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "costmap_layers/core/kernels/distance_transform.hpp"
#include "costmap_layers/core/filters/cost_grid_filter.hpp"
#include "costmap_layers/core/rules/lane_rules.hpp"

namespace costmap_layers
{
class ParamReader;

/// Reads the parameters above; throws std::invalid_argument on a bad value.
LanesFilterConfig parseLanesFilterConfig(const ParamReader& params);

/// LanesFilter's last step over n mask cells, exposed for tests: a forbidden cell (100) takes
/// 254 - c[k] (c: 254 minus its distance cost, 0 beyond the band), any other value its soft cost
/// round(v * 254 / 100) (0 for 0, -1 and values outside -1..100). out may be c. With stream, out is
/// written around the caches (and ordered before the return). Runs on the SIMD target in force
/// (simd_targets.hpp).
/// @return the number of values outside -1..100
std::size_t lanesFinishCosts(const int8_t* mask, const uint8_t* c, uint8_t* out, std::size_t n, bool stream);

class LanesFilter : public CostGridFilter
{
public:
  const LanesFilterConfig& config() const { return config_; }
  /// How many times the per-mask costs were computed (once per new mask). For tests and diagnostics.
  std::size_t costComputations() const { return cost_computations_; }

protected:
  /// Changes lane_border_width, border_cost, cost_profile and decay at run time; the costs are
  /// recomputed at the next update.
  void onReconfigure(const ParamValue& params) override;
  std::vector<ParamSpec> tunableLayerParameters(const ParamValue& params) const override;
  void onInitializeFilter(const ParamReader& params) override;
  std::size_t computeCosts(const OccupancyGridData& mask, std::vector<uint8_t>& costs) override;

private:
  LanesFilterConfig config_;
  std::atomic<std::size_t> cost_computations_{0};
  DistanceTransformScratch scratch_;
};
}  // namespace costmap_layers
