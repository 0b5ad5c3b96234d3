// costmap_2d's InflationLayer, exact: every cell within the inflation radius of a lethal cell (and,
// with inflate_around_unknown, of an unknown cell) gets the cost of its true Euclidean distance to the
// nearest such cell. Distances and costs come from the core's distance engine (distance_transform.hpp)
// over the update window; only distances with a cost above 0 are computed: up to
// min(inflation_radius, inscribed radius + ln(252) / cost_scaling_factor), beyond which the cost rounds
// down to 0.
#pragma once

#include <cstdint>
#include <vector>

#include "costmap_layers/core/rules/cost_rules.hpp"
#include "costmap_layers/core/kernels/distance_transform.hpp"
#include "costmap_layers/core/costmap/layer.hpp"

namespace costmap_layers
{
class ParamReader;

struct InflationConfig
{
  double inflation_radius = 0.55;       ///< [m]
  double cost_scaling_factor = 10.0;    ///< [1/m]
  bool inflate_unknown = false;         ///< an unknown cell takes any cost > 0, not only >= 253
  bool inflate_around_unknown = false;  ///< unknown cells are sources like lethal ones
  int num_threads = 1;                  ///< threads of one update (the window cut into bands of rows)
  /// [m] Nav2's: >= 0 replaces the footprint's inscribed radius in the cost function (warned: a
  /// safety risk); -1, the default, means the footprint's.
  double custom_inscribed_radius = -1.0;
};

/// Reads inflation_radius (>= 0), cost_scaling_factor (>= 0), inflate_unknown, inflate_around_unknown,
/// num_threads (1..64; 0 or -1: half the cores, at least one, as Nav2's -1) and custom_inscribed_radius
/// (-1 or [0, limit]). Throws std::invalid_argument naming the parameter.
InflationConfig parseInflationConfig(const ParamReader& params);
/// num_threads (1..64; 0 or -1: half the cores, at least one), for every layer that inflates.
int parseInflationThreads(const ParamReader& params, int def);

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
  /// The distance [cells] beyond which every cost is 0: at most cellInflationRadius(), and less when
  /// the cost rounds down to 0 earlier (inscribed radius + ln(252) / cost_scaling_factor).
  int64_t costReach() const { return costs_.reach(); }
  double inscribedRadius() const { return inscribed_radius_; }
  /// The cost written at squared cell distance d2 (0 when d2 exceeds the radius).
  uint8_t costAtSquaredDistance(uint64_t d2) const { return costs_.at(d2); }

protected:
  void onInitialize() override;
  /// onInitialize() with a configuration already parsed (a layer built on this one reads its own).
  void initializeWith(const InflationConfig& config);
  /// The cells distances are measured from (lethal; unknown too with inflate_around_unknown), and how a
  /// cost is written into a cell (unknown cells take only costs from the threshold inflate_unknown sets):
  /// for a layer that merges further distance costs the same way.
  SourceRange sourceRange() const;
  CostMergeRule mergeRule() const;
  /// What a cost table was built for: radius [cells], factor, resolution, inscribed radius.
  struct TableKey
  {
    int cells = -1;
    double factor = 0, resolution = 0, inscribed = 0;
    bool operator==(const TableKey& o) const
    {
      return cells == o.cells && factor == o.factor && resolution == o.resolution && inscribed == o.inscribed;
    }
  };

private:
  /// Rebuilds the cost table when the radius, factor, resolution or inscribed radius changed.
  void rebuildTable();
  /// The footprint's inscribed radius, or custom_inscribed_radius when set (then warned).
  void updateInscribedRadius();

  InflationConfig config_;
  double resolution_ = 0.0;
  double inscribed_radius_ = 0.0;
  int cell_inflation_radius_ = 0;
  bool need_reinflation_ = true;
  TableKey table_key_;
  DistanceCosts costs_;
  DistanceTransformScratch scratch_;
};
}  // namespace costmap_layers
