// The layer of Nav2's "Writing a New Costmap2D Plugin" tutorial, on this package's base class:
// repeating cost ramps written straight into the master grid.
#pragma once

#include <cstdint>
#include <vector>

#include "costmap_layers/core/costmap/layer.hpp"
#include "costmap_layers/core/rules/gradient_rule.hpp"

namespace costmap_layers
{
class ParamReader;

struct GradientConfig
{
  int gradient_size = 20;    ///< cells per ramp, minus one: k runs 0 .. gradient_size + 1 [cells]
  int gradient_factor = 10;  ///< cost decrement per cell
};

GradientConfig parseGradientConfig(const ParamReader& params);

class GradientLayer : public Layer
{
public:
  void updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y, double* max_x,
                    double* max_y) override;
  void updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j) override;
  void onFootprintChanged() override { need_recalculation_ = true; }
  void reset() override { need_recalculation_ = true; }
  const GradientConfig& config() const { return config_; }

protected:
  void onInitialize() override;
  void onReconfigure(const ParamValue& params) override;
  std::vector<ParamSpec> tunableLayerParameters(const ParamValue& params) const override;

private:
  GradientConfig config_;
  bool need_recalculation_ = true;
  double last_min_x_ = 0, last_min_y_ = 0, last_max_x_ = 0, last_max_y_ = 0;
  std::vector<uint8_t> row_;  ///< one row of the pattern, reused across updates
};
}  // namespace costmap_layers
