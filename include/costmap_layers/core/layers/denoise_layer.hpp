// Nav2's DenoiseLayer: clears obstacle groups of fewer than minimal_group_size cells (the
// salt-and-pepper noise of a depth camera or a dusty lidar) from what the layers below it wrote, inside
// the update window. One connected-components pass over runs of obstacle cells (read 64 cells at a time
// from a bit mask), union-find on the runs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "costmap_layers/core/costmap/layer.hpp"

namespace costmap_layers
{
class ParamReader;

struct DenoiseConfig
{
  /// Groups of fewer cells are cleared; 0 and 1 clear nothing (Nav2: "1 or less leaves every cell") [cells]
  int minimal_group_size = 2;
  int group_connectivity_type = 8;  ///< 4: edge neighbours only; 8: corners too
};

DenoiseConfig parseDenoiseConfig(const ParamReader& params);

/// The pass itself, on any grid of bytes: reusable buffers, no allocation once they have grown.
class ObstacleGroupRemover
{
public:
  /// Which cells form the groups (Nav2's choice): lethal and inscribed ones, and unknown ones too when
  /// `unknown_is_obstacle` (Nav2 does so when the map's default value is not NO_INFORMATION).
  struct Rule
  {
    int minimal_group_size = 2;
    bool eight_connected = true;
    bool unknown_is_obstacle = false;
  };

  /// Sets every obstacle cell of a group smaller than rule.minimal_group_size to FREE_SPACE, within
  /// [min_i, max_i) x [min_j, max_j) of the grid `cells` (rows of `stride` cells); a group is judged by
  /// its cells inside the window. The window must lie inside the grid. Returns the cells cleared.
  std::size_t remove(uint8_t* cells, std::size_t stride, int min_i, int min_j, int max_i, int max_j, const Rule& rule);

private:
  /// minimal_group_size 2: single cells with no obstacle around, without union-find.
  std::size_t removeSingles(uint8_t* cells, std::size_t stride, int min_i, int min_j, int max_i, int max_j,
                            unsigned span, int reach);
  int32_t findRoot(int32_t r);
  void unite(int32_t a, int32_t b, int32_t cap);

  std::vector<int32_t> edges_;  ///< run r covers columns [edges_[2r], edges_[2r + 1])
  /// Per run: the parent run, or for a root minus the group's cell count (capped at the minimal size).
  std::vector<int32_t> parent_;
  std::vector<uint8_t> bits_;  ///< one row's obstacle cells as bits (scanRow())
  std::vector<std::size_t> row_first_;  ///< index of the first run of each window row, and one past the end
};

class DenoiseLayer : public Layer
{
public:
  /// Nav2's layer keeps no bounds of its own: it works on whatever window the layers below asked for.
  void updateBounds(double, double, double, double*, double*, double*, double*) override {}
  void updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j) override;
  /// Nav2: not current after a reset until the next update.
  void reset() override { current_ = false; }
  const DenoiseConfig& config() const { return config_; }

protected:
  void onInitialize() override;
  void onReconfigure(const ParamValue& params) override;
  std::vector<ParamSpec> tunableLayerParameters(const ParamValue& params) const override;

private:
  DenoiseConfig config_;
  ObstacleGroupRemover remover_;
};
}  // namespace costmap_layers
