// Nav2's PluginContainerLayer: a layer with its own plugin list (`plugins`, each plugin's parameters
// under <container>/<plugin>), whose plugins write into the container's grid instead of the master;
// that grid is merged into the master as one layer with `combination_method`. A group of sensors can
// so be inflated apart from the static map, say. The plugins are made by the host's factories, by
// the same rules as the costmap's own list (costmap_builder.hpp), and exposed to the host through
// heldLayers() so that it wires their ports, reconfiguration and diagnostics like its own plugins'.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "costmap_layers/core/costmap/costmap_builder.hpp"
#include "costmap_layers/core/costmap/costmap_layer.hpp"

namespace costmap_layers
{
class ParamReader;

/// How the container's grid goes into the master (Nav2's values).
enum class ContainerCombination
{
  Overwrite = 0,                  ///< the container's known cells replace the master's
  Max = 1,                        ///< the larger cost; unknown master cells take the container's
  MaxWithoutUnknownOverwrite = 2  ///< the larger cost; unknown master cells stay unknown
};

struct PluginContainerConfig
{
  ContainerCombination combination_method = ContainerCombination::Max;  ///< Nav2's default, 1
};

/// Reads `combination_method` (0, 1 or 2; Nav2 warns about any other value and takes 1, refused here).
PluginContainerConfig parsePluginContainerConfig(const ParamReader& params);

class PluginContainerLayer : public CostmapLayer
{
public:
  /// Containers inside containers: at most this many levels of plugin lists below the costmap's.
  static constexpr int kMaxNesting = 4;

  /// The host's factories, given before initialize() (makeLayer() does so); `level` is the nesting of
  /// this container's plugin list: 1 for a container in the costmap's list.
  void setMaker(LayerMaker maker, int level);

  void updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y, double* max_x,
                    double* max_y) override;
  void updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j) override;
  void matchSize() override;
  void onFootprintChanged() override;
  /// Resets every plugin and the own grid; not current until the next update (as Nav2).
  void reset() override;
  void activate() override;
  void deactivate() override;
  /// True when any of its plugins is clearable (as Nav2).
  bool isClearable() override;
  /// Clears the own grid and the cells of every clearable plugin that keeps a grid.
  void clearCells(unsigned int x0, unsigned int y0, unsigned int xn, unsigned int yn, uint8_t value) override;
  std::vector<std::shared_ptr<Layer>> heldLayers() const override { return plugins_; }
  const PluginContainerConfig& config() const { return config_; }

protected:
  void onInitialize() override;
  void onReconfigure(const ParamValue& params) override;
  std::vector<ParamSpec> tunableLayerParameters(const ParamValue& params) const override;

private:
  LayerMaker maker_;
  int level_ = 0;  ///< 0: no host gave factories
  PluginContainerConfig config_;
  std::vector<std::shared_ptr<Layer>> plugins_;
};
}  // namespace costmap_layers
