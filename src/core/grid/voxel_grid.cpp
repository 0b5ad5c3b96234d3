#include "costmap_layers/core/grid/voxel_grid.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace costmap_layers
{
void VoxelGrid::resize(unsigned int size_x, unsigned int size_y, unsigned int size_z)
{
  if (size_z == 0 || size_z > kMaxLevels)
    throw std::invalid_argument("VoxelGrid: z size must be in [1, 16] (got " + std::to_string(size_z) + ")");
  size_x_ = size_x;
  size_y_ = size_y;
  size_z_ = size_z;
  unknown_column_ = (1u << size_z) - 1u;
  data_.assign(static_cast<std::size_t>(size_x) * size_y, unknown_column_);
}

void VoxelGrid::reset()
{
  std::fill(data_.begin(), data_.end(), unknown_column_);
}

void VoxelGrid::resetColumns(unsigned int x0, unsigned int y0, unsigned int xn, unsigned int yn)
{
  xn = std::min(xn, size_x_);
  yn = std::min(yn, size_y_);
  if (x0 >= xn || y0 >= yn) return;
  for (unsigned int y = y0; y < yn; ++y)
  {
    const auto row = data_.begin() + static_cast<std::ptrdiff_t>(y) * size_x_;
    std::fill(row + x0, row + xn, unknown_column_);
  }
}

void VoxelGrid::shift(int dx, int dy)
{
  if (dx == 0 && dy == 0) return;
  const int sx = static_cast<int>(size_x_), sy = static_cast<int>(size_y_);
  std::vector<uint32_t> next(data_.size(), unknown_column_);
  // New column (x, y) comes from old (x + dx, y + dy) when that is inside the old grid.
  const int x_begin = std::max(0, -dx), x_end = std::min(sx, sx - dx);
  const int y_begin = std::max(0, -dy), y_end = std::min(sy, sy - dy);
  if (x_begin < x_end)
  {
    for (int y = y_begin; y < y_end; ++y)
    {
      const uint32_t* from = data_.data() + static_cast<std::size_t>(y + dy) * size_x_ + (x_begin + dx);
      std::copy(from, from + (x_end - x_begin), next.data() + static_cast<std::size_t>(y) * size_x_ + x_begin);
    }
  }
  data_.swap(next);
}

VoxelStatus VoxelGrid::getVoxel(unsigned int x, unsigned int y, unsigned int z) const
{
  if (x >= size_x_ || y >= size_y_ || z >= size_z_) return VoxelStatus::Unknown;
  const uint32_t col = data_[y * size_x_ + x];
  const bool marked = (col >> (16 + z)) & 1u;
  const bool known_bit = (col >> z) & 1u;
  if (marked) return VoxelStatus::Marked;
  return known_bit ? VoxelStatus::Unknown : VoxelStatus::Free;
}

VoxelStatus VoxelGrid::getColumn(unsigned int x, unsigned int y, unsigned int unknown_threshold,
                                 unsigned int mark_threshold) const
{
  if (x >= size_x_ || y >= size_y_) return VoxelStatus::Unknown;
  const uint32_t col = data_[y * size_x_ + x];
  if (markedCount(col) > mark_threshold) return VoxelStatus::Marked;
  if (unknownCount(col) > unknown_threshold) return VoxelStatus::Unknown;
  return VoxelStatus::Free;
}

bool VoxelGrid::markVoxel(unsigned int x, unsigned int y, unsigned int z, unsigned int mark_threshold)
{
  if (x >= size_x_ || y >= size_y_ || z >= size_z_) return false;
  uint32_t& col = data_[y * size_x_ + x];
  col |= (1u << (16 + z)) | (1u << z);
  return markedCount(col) > mark_threshold;
}

void VoxelGrid::clearVoxel(unsigned int x, unsigned int y, unsigned int z)
{
  if (x >= size_x_ || y >= size_y_ || z >= size_z_) return;
  data_[y * size_x_ + x] &= ~((1u << (16 + z)) | (1u << z));
}
}  // namespace costmap_layers
