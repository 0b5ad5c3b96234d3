// What a VoxelLayer publishes of its voxels: a copy of its columns with the grid's geometry (the fields
// of costmap_2d's and Nav2's VoxelGrid message, published as costmap_layers/VoxelMap), and the centres
// of the voxels in one state, for RViz (a cube list, a cloud).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "costmap_layers/core/grid/voxel_grid.hpp"

namespace costmap_layers
{
struct VoxelGridData
{
  unsigned int size_x = 0, size_y = 0;    ///< columns
  unsigned int size_z = 0;                ///< levels per column, 1..16
  double origin_x = 0.0, origin_y = 0.0;  ///< [m] corner of column (0, 0) in the global frame
  double origin_z = 0.0;                  ///< [m] bottom of level 0
  double resolution = 0.0;                ///< [m] column width
  double z_resolution = 0.0;              ///< [m] level height
  /// size_x * size_y columns, row by row, bits as VoxelGrid keeps them (voxel_grid.hpp): for level z,
  /// bits 16+z and z set = marked, bit z alone = unknown, neither = free.
  std::vector<uint32_t> data;
};

/// The most voxel centres a message carries: 2^20 points, 12 MB as floats (a 6 x 6 m local window at
/// 5 cm with 10 levels has 144,000 voxels; a whole 4000 x 4000 map of them would be 256 million).
constexpr std::size_t kMaxVoxelPoints = std::size_t{1} << 20;

struct VoxelPoint
{
  float x = 0.f, y = 0.f, z = 0.f;  ///< [m] the voxel's centre in the grid's frame
  unsigned int level = 0;           ///< its z level
};

/// The centres of the voxels in state `which` (levels below size_z only), row by row and level by level
/// within a column, at most `max_points` of them. @return how many there are in all: more than
/// points.size() when the list was cut.
std::size_t voxelCentres(const VoxelGridData& grid, VoxelStatus which, std::vector<VoxelPoint>& points,
                         std::size_t max_points = kMaxVoxelPoints);
}  // namespace costmap_layers
