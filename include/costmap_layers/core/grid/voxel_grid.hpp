// voxel_grid's bit-packed columns: one uint32 per 2-D cell, up to 16 voxels high. For level z, bit
// (16 + z) is "marked" and bit z is "known-or-marked":
//   marked = both bits set, unknown = only bit z set, free = neither.
// So markedCount = popcount(col >> 16) and unknownCount = popcount((col >> 16) ^ (col & 0xFFFF)).
// Unlike voxel_grid, only the z levels in use start unknown (costmap_2d starts all 16 and adds
// 16 - z_voxels to unknown_threshold instead, which gives the same answers).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace costmap_layers
{
enum class VoxelStatus
{
  Free,
  Unknown,
  Marked
};

class VoxelGrid
{
public:
  static constexpr unsigned int kMaxLevels = 16;

  /// Reallocates to size_x * size_y columns of size_z levels (1..16, else std::invalid_argument),
  /// every voxel unknown.
  void resize(unsigned int size_x, unsigned int size_y, unsigned int size_z);
  /// Every voxel unknown.
  void reset();
  /// Every voxel of the columns [x0, xn) x [y0, yn) unknown (the window cut to the grid).
  void resetColumns(unsigned int x0, unsigned int y0, unsigned int xn, unsigned int yn);
  /// Keeps the columns the window shifted by (dx, dy) cells shares with the old one (column (x, y) of
  /// the new grid is column (x + dx, y + dy) of the old); the others become unknown.
  void shift(int dx, int dy);

  unsigned int sizeX() const { return size_x_; }
  unsigned int sizeY() const { return size_y_; }
  unsigned int sizeZ() const { return size_z_; }
  uint32_t column(unsigned int x, unsigned int y) const { return data_[y * size_x_ + x]; }
  uint32_t* data() { return data_.data(); }
  const uint32_t* data() const { return data_.data(); }
  /// The column value of an all-unknown column.
  uint32_t unknownColumn() const { return unknown_column_; }

  static unsigned int markedCount(uint32_t col) { return popcount(col >> 16); }
  static unsigned int unknownCount(uint32_t col) { return popcount((col >> 16) ^ (col & 0xFFFFu)); }

  /// Out-of-grid voxels read as Unknown.
  VoxelStatus getVoxel(unsigned int x, unsigned int y, unsigned int z) const;
  /// Marked when more than mark_threshold voxels are marked, else Unknown when more than
  /// unknown_threshold are unknown, else Free (voxel_grid's getVoxelColumn).
  VoxelStatus getColumn(unsigned int x, unsigned int y, unsigned int unknown_threshold,
                        unsigned int mark_threshold) const;
  /// Marks a voxel (ignored outside the grid). @return true when the column then has more than
  /// mark_threshold marked voxels.
  bool markVoxel(unsigned int x, unsigned int y, unsigned int z, unsigned int mark_threshold);
  void clearVoxel(unsigned int x, unsigned int y, unsigned int z);

  /// Walks the voxels of the segment between two points given in voxel units (x / resolution, ...),
  /// both inside the grid, from the first to the voxel holding the end point, that one included (as
  /// costmap_2d's voxel_grid raytraceLine, whose last call comes after its loop). Calls
  /// at(column_index, z) once per voxel; nothing is allocated. Steps of at most one voxel per axis.
  template <class ActionType>
  void walkLine(ActionType&& at, double x0, double y0, double z0, double x1, double y1, double z1) const;

private:
  /// Bit count without relying on a popcnt instruction (the build targets baseline x86-64, where
  /// __builtin_popcount is a library call).
  static unsigned int popcount(uint32_t v)
  {
    v = v - ((v >> 1) & 0x55555555u);
    v = (v & 0x33333333u) + ((v >> 2) & 0x33333333u);
    v = (v + (v >> 4)) & 0x0F0F0F0Fu;
    return (v * 0x01010101u) >> 24;
  }

  unsigned int size_x_ = 0, size_y_ = 0, size_z_ = 0;
  uint32_t unknown_column_ = 0;
  std::vector<uint32_t> data_;
};

template <class ActionType>
void VoxelGrid::walkLine(ActionType&& at, double x0, double y0, double z0, double x1, double y1, double z1) const
{
  // Both ends are inside the grid (non-negative voxel units below 2^20), so 32.32 fixed point walks
  // the segment exactly enough and truncation is floor.
  const double dx = x1 - x0, dy = y1 - y0, dz = z1 - z0;
  const double longest = std::max(std::fabs(dx), std::max(std::fabs(dy), std::fabs(dz)));
  if (!(longest > 0.0) || !(longest < 1e6)) return;  // also NaN
  if (!(x0 >= 0.0 && y0 >= 0.0 && z0 >= 0.0 && x0 < size_x_ && y0 < size_y_ && z0 < size_z_)) return;
  const unsigned int steps = static_cast<unsigned int>(std::ceil(longest));
  constexpr double kOne = 4294967296.0;  // 2^32
  int64_t fx = static_cast<int64_t>(x0 * kOne), fy = static_cast<int64_t>(y0 * kOne),
          fz = static_cast<int64_t>(z0 * kOne);
  const int64_t sx = static_cast<int64_t>(dx / steps * kOne), sy = static_cast<int64_t>(dy / steps * kOne),
                sz = static_cast<int64_t>(dz / steps * kOne);
  const int64_t ex = static_cast<int64_t>(std::floor(x1)), ey = static_cast<int64_t>(std::floor(y1)),
                ez = static_cast<int64_t>(std::floor(z1));
  auto inside = [this](int64_t ix, int64_t iy, int64_t iz)
  {
    return ix >= 0 && iy >= 0 && iz >= 0 && ix < static_cast<int64_t>(size_x_) && iy < static_cast<int64_t>(size_y_) &&
           iz < static_cast<int64_t>(size_z_);
  };
  int64_t px = -1, py = -1, pz = -1;
  for (unsigned int i = 0; i < steps; ++i, fx += sx, fy += sy, fz += sz)
  {
    // Arithmetic shift: a hair below zero becomes -1 and ends the walk below.
    const int64_t ix = fx >> 32, iy = fy >> 32, iz = fz >> 32;
    if (ix == px && iy == py && iz == pz) continue;  // still in the voxel just visited
    if (!inside(ix, iy, iz)) return;
    at(static_cast<unsigned int>(iy) * size_x_ + static_cast<unsigned int>(ix), static_cast<unsigned int>(iz));
    if (ix == ex && iy == ey && iz == ez) return;
    px = ix, py = iy, pz = iz;
  }
  // The last position walked lies one step before the end point: its voxel, when not reached yet.
  if (inside(ex, ey, ez))
    at(static_cast<unsigned int>(ey) * size_x_ + static_cast<unsigned int>(ex), static_cast<unsigned int>(ez));
}
}  // namespace costmap_layers
