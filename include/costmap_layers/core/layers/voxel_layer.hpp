// costmap_2d's VoxelLayer: the ObstacleLayer (same sources, buffers, parameters and merge) with a 3-D
// grid of bit-packed columns (VoxelGrid) behind the 2-D one. Hits mark voxels; a cell becomes lethal
// when its column has more than mark_threshold marked voxels. Rays clear voxels in 3-D; each cleared
// voxel re-evaluates its column: with at most mark_threshold marked voxels the cell becomes FREE_SPACE,
// or NO_INFORMATION when more than unknown_threshold of its z_voxels voxels are still unknown.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "costmap_layers/core/grid/voxel_grid.hpp"
#include "costmap_layers/core/layers/obstacle_layer.hpp"

namespace costmap_layers
{
struct VoxelConfig
{
  double origin_z = 0.0;           ///< [m] bottom of the lowest voxel (global z)
  double z_resolution = 0.2;       ///< [m] voxel height (> 0)
  int z_voxels = 10;               ///< levels per column, 1..16
  int unknown_threshold = 15;      ///< 0..16: more unknown voxels than this make a cleared cell unknown
  int mark_threshold = 0;          ///< 0..16: more marked voxels than this make the cell lethal
  /// Offer the voxels on ~<name>/voxel_grid (costmap_layers/VoxelMap), voxel_markers (a cube list) and
  /// voxel_cloud (PointCloud2 of the marked voxels' centres), each built only while someone subscribes.
  bool publish_voxel_map = false;
};

/// Reads origin_z, z_resolution, z_voxels, unknown_threshold, mark_threshold and publish_voxel_map.
/// Throws std::invalid_argument naming the parameter.
VoxelConfig parseVoxelConfig(const ParamReader& params);

class VoxelLayer : public ObstacleLayer
{
public:
  static constexpr const char* kVoxelGridTopic = "voxel_grid";
  static constexpr const char* kVoxelMarkersTopic = "voxel_markers";
  static constexpr const char* kVoxelCloudTopic = "voxel_cloud";

  /// The ObstacleLayer's, then the voxel outputs someone reads (publish_voxel_map).
  void updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y, double* max_x,
                    double* max_y) override;
  void matchSize() override;
  void reset() override;
  /// The cells and their columns: a cleared cell keeps no marked voxel that would make it lethal again
  /// when another voxel of its column is marked and cleared.
  void clearCells(unsigned int x0, unsigned int y0, unsigned int xn, unsigned int yn, uint8_t value) override;

  const VoxelConfig& voxelConfig() const { return voxel_config_; }
  const VoxelGrid& voxels() const { return voxels_; }

protected:
  void onInitialize() override;
  void onGridShifted(int cells_x, int cells_y) override;
  void raytraceFreespace(const Observation& observation, double* min_x, double* min_y, double* max_x,
                         double* max_y) override;
  void markObservation(const Observation& observation, double* min_x, double* min_y, double* max_x,
                       double* max_y) override;

private:
  /// Emits a snapshot of the voxels on each voxel output the host says someone reads.
  void publishVoxels();

  /// The walks one raytraceFreespace call has cleared, by end voxel: every walk of an observation starts
  /// in the sensor's voxel, so two readings ending in the same voxel walk the same voxels, and the second
  /// needs no walk when its steps lie within those already cleared (clearing is idempotent and the
  /// column's cell depends only on the column's bits at the end). An organised depth cloud holds many
  /// readings per voxel. Open addressing over a table reused from call to call (no allocation once it
  /// has grown to twice the largest observation, at most kMaxSlots: 1.5 MB), emptied by an epoch count.
  class ClearedWalks
  {
  public:
    /// A new observation of at most `walks` walks.
    void begin(std::size_t walks);
    /// True when the steps lo..hi of the walk to voxel `key` were cleared already in this observation;
    /// otherwise notes them (merged with the steps noted for that voxel when they touch) and is false.
    bool covered(uint64_t key, uint32_t lo, uint32_t hi);

  private:
    static constexpr std::size_t kMaxSlots = std::size_t{1} << 16;
    struct Slot
    {
      uint64_t key = 0;
      uint32_t lo = 0, hi = 0;
      uint32_t epoch = 0;  ///< the slot is empty unless this is the current epoch
    };
    std::vector<Slot> slots_;
    std::size_t mask_ = 0;
    std::size_t used_ = 0;  ///< slots of the current epoch
    uint32_t epoch_ = 0;
  };

  VoxelConfig voxel_config_;
  VoxelGrid voxels_;
  ClearedWalks cleared_walks_;
};
}  // namespace costmap_layers
