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

  /// voxel_grid's line (its raytraceLine, a Bresenham walk over whole voxels): from voxel (x0, y0, z0)
  /// to voxel (x1, y1, z1), both inside the grid (else nothing is visited). The axis with the largest
  /// change in voxels drives the walk (x on a tie with y or z, y on a tie with z), one voxel per step,
  /// the others follow through error terms starting at half the step count, as there; step 0 is the
  /// first voxel and step `lineSteps` the last one, which is visited too. Calls at(column_index, z, k)
  /// for the steps k = 0 .. min(last_step, lineSteps) in order; nothing is allocated.
  template <class ActionType>
  void traceLine(ActionType&& at, unsigned int x0, unsigned int y0, unsigned int z0, unsigned int x1, unsigned int y1,
                 unsigned int z1, unsigned int last_step) const;
  /// The number of steps of traceLine's walk between two voxels: the largest change along an axis.
  static unsigned int lineSteps(unsigned int x0, unsigned int y0, unsigned int z0, unsigned int x1, unsigned int y1,
                                unsigned int z1)
  {
    auto change = [](unsigned int a, unsigned int b) { return a > b ? a - b : b - a; };
    return std::max(change(x0, x1), std::max(change(y0, y1), change(z0, z1)));
  }

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
void VoxelGrid::traceLine(ActionType&& at, unsigned int x0, unsigned int y0, unsigned int z0, unsigned int x1,
                          unsigned int y1, unsigned int z1, unsigned int last_step) const
{
  if (x0 >= size_x_ || y0 >= size_y_ || z0 >= size_z_ || x1 >= size_x_ || y1 >= size_y_ || z1 >= size_z_) return;
  // Both ends are inside the grid, so every voxel of the walk is (it stays in the box of its ends).
  const int64_t delta[3] = {static_cast<int64_t>(x1) - x0, static_cast<int64_t>(y1) - y0,
                            static_cast<int64_t>(z1) - z0};
  const int64_t change[3] = {delta[0] < 0 ? -delta[0] : delta[0], delta[1] < 0 ? -delta[1] : delta[1],
                             delta[2] < 0 ? -delta[2] : delta[2]};
  const int64_t steps = std::max(change[0], std::max(change[1], change[2]));
  const int64_t end = std::min<int64_t>(steps, last_step);
  // Every axis follows its error term, the driving one too: its change is `steps`, so its term moves it
  // on every step and comes back to where it started: the walk described at the declaration, with no
  // branch on which axis drives. The column index is carried along instead of recomputed.
  const int64_t step_x = delta[0] > 0 ? 1 : -1, step_y = (delta[1] > 0 ? 1 : -1) * static_cast<int64_t>(size_x_),
                step_z = delta[2] > 0 ? 1 : -1;
  int64_t index = static_cast<int64_t>(y0) * size_x_ + x0, z = z0;
  int64_t error_x = steps / 2, error_y = steps / 2, error_z = steps / 2;
  for (int64_t k = 0;; ++k)
  {
    at(static_cast<unsigned int>(index), static_cast<unsigned int>(z), static_cast<unsigned int>(k));
    if (k == end) return;
    // An axis moves when its error term reaches `steps`; the moves are masks, not branches: whether a
    // following axis moves on a step is as good as random to the branch predictor, and one mispredicted
    // jump cost more than the whole step.
    error_x += change[0];
    const int64_t move_x = -static_cast<int64_t>(error_x >= steps);  // all ones when x moves
    error_x -= steps & move_x;
    index += step_x & move_x;
    error_y += change[1];
    const int64_t move_y = -static_cast<int64_t>(error_y >= steps);
    error_y -= steps & move_y;
    index += step_y & move_y;
    error_z += change[2];
    const int64_t move_z = -static_cast<int64_t>(error_z >= steps);
    error_z -= steps & move_z;
    z += step_z & move_z;
  }
}
}  // namespace costmap_layers
