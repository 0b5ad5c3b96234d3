// costmap_2d's InflationLayer, exact: every cell within the inflation radius of a lethal cell (and,
// with inflate_around_unknown, of an unknown cell) gets the cost of its true Euclidean distance to the
// nearest such cell. Distances come from an exact distance transform over the update window padded
// by the radius; costs from a table indexed by the squared cell distance.
#pragma once

#include <cstdint>
#include <vector>

#include "costmap_layers/core/cost_rules.hpp"
#include "costmap_layers/core/distance_transform.hpp"
#include "costmap_layers/core/layer.hpp"

namespace costmap_layers
{
class ParamReader;

struct InflationConfig
{
  double inflation_radius = 0.55;       ///< [m]
  double cost_scaling_factor = 10.0;    ///< [1/m]
  bool inflate_unknown = false;         ///< an unknown cell takes any cost > 0, not only >= 253
  bool inflate_around_unknown = false;  ///< unknown cells are sources like lethal ones
};

/// Reads inflation_radius (>= 0), cost_scaling_factor (>= 0), inflate_unknown and
/// inflate_around_unknown. Throws std::invalid_argument naming the parameter.
InflationConfig parseInflationConfig(const ParamReader& params);

class InflationLayer : public Layer
{
public:
  void updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y, double* max_x,
                    double* max_y) override;
  void updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j) override;
  void matchSize() override;
  void onFootprintChanged() override;
  void reset() override;
  bool isClearable() override { return false; }

  const InflationConfig& config() const { return config_; }
  /// Replaces the parameters (as a reconfigure would); the next update covers the whole map.
  void setConfig(const InflationConfig& config);

protected:
  void onReconfigure(const ParamValue& params) override;
  std::vector<ParamSpec> tunableLayerParameters(const ParamValue& params) const override;

public:
  /// ceil(inflation_radius / resolution): cells farther than this are not written.
  int cellInflationRadius() const { return cell_inflation_radius_; }
  double inscribedRadius() const { return inscribed_radius_; }
  /// The cost written at squared cell distance d2 (0 when d2 exceeds the radius).
  uint8_t costAtSquaredDistance(uint32_t d2) const;

protected:
  void onInitialize() override;

private:
  void rebuildTable();
  /// Writes the costs of one window row, given its squared distances (T lanes), into master_row.
  template <class T>
  void writeRow(uint8_t* master_row, const T* sq_dist, int n);

  InflationConfig config_;
  double resolution_ = 0.0;
  double inscribed_radius_ = 0.0;
  int cell_inflation_radius_ = 0;
  bool need_reinflation_ = true;
  /// Cost per squared cell distance, zero past the radius; sized for every value the engine reports.
  std::vector<uint8_t> cost_table_;
  uint32_t table_limit_ = 0;  ///< squared distances above this are past the radius
  /// Whether cost_table_ never increases with the distance (it does not for sane parameters): the
  /// cost-domain engine relies on it.
  bool table_non_increasing_ = false;
  std::vector<uint8_t> row_costs_;
  std::vector<uint32_t> exact_;  ///< padded window for radii beyond the banded engines
  DistanceTransformScratch scratch_;
};
}  // namespace costmap_layers
