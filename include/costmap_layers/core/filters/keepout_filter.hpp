// KeepoutFilter: a mask value costs maskValueCost(v) (rules/cost_rules.hpp), computed once per mask
// and merged into the master grid by mergeFilterCost (CostGridFilter, filters/cost_grid_filter.hpp).
//
// KeepoutFilter's escape mode (Nav2's override_lethal_cost / lethal_override_cost, done for the whole
// footprint): when the robot is found inside a lethal keepout zone (a localisation jump, a push), the
// zone's lethal cells are written as a ramp of passable costs instead, so that a planner can drive
// it out by the shortest way, and lethal again once it is out.
//  - The robot is "in the zone" (robotInLethalKeepout()) while a lethal keepout cell (mask value 100:
//    cost >= 253) has its centre under the padded footprint, holds the robot's position or a footprint
//    vertex, or lies within escapeClearance() of the robot's position: the inscribed radius plus
//    sqrt(2) costmap cells. That last part is what makes escape mode work with an InflationLayer
//    after the filter: once the zone is lethal again, the inflation writes 253 up to the inscribed
//    radius around it, and the robot's cell and its eight neighbours must lie beyond that band, or a
//    planner (navfn treats 253 as an obstacle) finds no way from the robot and the robot is stuck
//    just outside the zone.
//  - While in the zone, each lethal keepout cell costs escapeRampCost() (cost_rules.hpp) of its depth:
//    the exact Euclidean distance from its centre to the centre of the nearest mask cell that is not
//    lethal keepout (the mask's edge is no way out: masks end where maps end), rising from 1 at the edge to
//    lethal_override_cost at the padded footprint's circumscribed radius and beyond. So the costs fall toward the
//    nearest way out. Other mask values keep their costs. The ramp stays below 253, so an InflationLayer does not
//    inflate the zone while the robot escapes.
//  - Escape mode is decided once per cycle at the robot's pose; a change redraws the mask's extent.
//
// Parameters (Nav2's names):
//   override_lethal_cost  false   escape mode on or off
//   lethal_override_cost  252     [cost] top of the ramp, 1..252 (Nav2 clamps into 0..252 silently;
//                                 here a value outside 1..252 is a start-up error)
#pragma once

#include <memory>
#include <vector>

#include "costmap_layers/core/rules/cost_rules.hpp"
#include "costmap_layers/core/filters/cost_grid_filter.hpp"
#include "costmap_layers/core/kernels/distance_transform.hpp"
#include "costmap_layers/core/grid/footprint.hpp"

namespace costmap_layers
{

struct KeepoutFilterConfig
{
  bool override_lethal_cost = false;
  int lethal_override_cost = MAX_NON_OBSTACLE;
};

/// Reads the parameters above; throws std::invalid_argument naming the parameter and the value.
KeepoutFilterConfig parseKeepoutFilterConfig(const ParamReader& params);

/// [m] How near a lethal keepout cell may be to the robot's position before the robot counts as in the
/// zone: the inscribed radius plus sqrt(2) costmap cells (see the file comment).
double escapeClearance(double inscribed_radius, double costmap_resolution);

/// Whether the robot at (x, y, yaw) in the global frame overlaps lethal keepout (see the file comment).
/// @param to_mask    global frame -> mask frame
/// @param footprint  padded footprint in the robot frame [m]; empty: the robot is a point
/// @param clearance  [m] escapeClearance()
bool robotInLethalKeepout(const OccupancyGridData& mask, const Transform2D& to_mask, double x, double y, double yaw,
                          const Footprint& footprint, double clearance);

/// Replaces every lethal cost (>= 253) of `costs` (one per mask cell, row-major, width x height) by
/// escapeRampCost() of the cell's depth [m] (resolution: the mask's): the distance to the nearest
/// cell that is not lethal; top when there is none. `ramp` is scratch.
void writeEscapeRamp(std::vector<uint8_t>& costs, uint32_t width, uint32_t height, double resolution,
                     double ramp_length, uint8_t top, std::vector<uint8_t>& ramp, DistanceTransformScratch& scratch);

class KeepoutFilter : public CostGridFilter
{
public:
  const KeepoutFilterConfig& config() const { return config_; }
  /// Whether escape mode is on (decided at the last update). Update thread only.
  bool escaping() const { return escaping_; }

protected:
  void onInitializeFilter(const ParamReader& params) override;
  std::size_t computeCosts(const OccupancyGridData& mask, std::vector<uint8_t>& costs) override;
  /// Decides escape mode at the robot's pose (when override_lethal_cost is on).
  void processPose(const OccupancyGridData& mask, const Transform2D& to_mask, double robot_x, double robot_y,
                   double robot_yaw) override;
  /// The ramp's length follows the footprint.
  void onFootprintChanged() override;

private:
  KeepoutFilterConfig config_;
  bool escaping_ = false;  ///< update thread only
  std::vector<uint8_t> ramp_;
  DistanceTransformScratch scratch_;
};
}  // namespace costmap_layers
