#include "costmap_layers/core/data/voxel_grid_data.hpp"

namespace costmap_layers
{
std::size_t voxelCentres(const VoxelGridData& grid, VoxelStatus which, std::vector<VoxelPoint>& points,
                         std::size_t max_points)
{
  points.clear();
  const unsigned int levels = grid.size_z > VoxelGrid::kMaxLevels ? VoxelGrid::kMaxLevels : grid.size_z;
  const uint32_t in_use = levels >= 32 ? ~uint32_t{0} : (uint32_t{1} << levels) - 1u;
  const std::size_t columns = std::size_t{grid.size_x} * grid.size_y;
  const std::size_t n = columns < grid.data.size() ? columns : grid.data.size();
  std::size_t total = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const uint32_t col = grid.data[i];
    const uint32_t high = col >> 16, low = col & 0xFFFFu;
    uint32_t bits = 0;
    if (which == VoxelStatus::Marked)
      bits = high & low;
    else if (which == VoxelStatus::Unknown)
      bits = low & ~high;
    else
      bits = ~(high | low);
    bits &= in_use;
    if (bits == 0) continue;
    const unsigned int cx = static_cast<unsigned int>(i % grid.size_x);
    const unsigned int cy = static_cast<unsigned int>(i / grid.size_x);
    const float x = static_cast<float>(grid.origin_x + (cx + 0.5) * grid.resolution);
    const float y = static_cast<float>(grid.origin_y + (cy + 0.5) * grid.resolution);
    for (unsigned int z = 0; z < levels; ++z)
    {
      if (!(bits & (uint32_t{1} << z))) continue;
      ++total;
      if (points.size() < max_points)
        points.push_back({x, y, static_cast<float>(grid.origin_z + (z + 0.5) * grid.z_resolution), z});
    }
  }
  return total;
}
}  // namespace costmap_layers
