#include "costmap_layers/core/layers/voxel_layer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/core/config/param_reader.hpp"

namespace costmap_layers
{
VoxelConfig parseVoxelConfig(const ParamReader& p)
{
  VoxelConfig c;
  c.origin_z = p.getDouble("origin_z", c.origin_z, -limits::kMaxCoordinate, limits::kMaxCoordinate);
  c.z_resolution = p.getDouble("z_resolution", c.z_resolution, 1e-6, limits::kMaxResolution);
  c.z_voxels = p.getInt("z_voxels", c.z_voxels, 1, static_cast<int>(VoxelGrid::kMaxLevels));
  c.unknown_threshold = p.getInt("unknown_threshold", c.unknown_threshold, 0, static_cast<int>(VoxelGrid::kMaxLevels));
  c.mark_threshold = p.getInt("mark_threshold", c.mark_threshold, 0, static_cast<int>(VoxelGrid::kMaxLevels));
  c.publish_voxel_map = p.getBool("publish_voxel_map", c.publish_voxel_map);
  return c;
}

void VoxelLayer::onInitialize()
{
  voxel_config_ = parseVoxelConfig(ParamReader(context_->params(), name_));
  ObstacleLayer::onInitialize();  // calls matchSize(), which sizes the voxels with the config above
}

void VoxelLayer::matchSize()
{
  ObstacleLayer::matchSize();
  voxels_.resize(costmap_.getSizeInCellsX(), costmap_.getSizeInCellsY(),
                 static_cast<unsigned int>(voxel_config_.z_voxels));
}

void VoxelLayer::reset()
{
  ObstacleLayer::reset();
  voxels_.reset();
}

void VoxelLayer::clearCells(unsigned int x0, unsigned int y0, unsigned int xn, unsigned int yn, uint8_t value)
{
  ObstacleLayer::clearCells(x0, y0, xn, yn, value);
  voxels_.resetColumns(x0, y0, xn, yn);
}

void VoxelLayer::onGridShifted(int cells_x, int cells_y)
{
  voxels_.shift(cells_x, cells_y);  // the columns move with the 2-D cells
}

void VoxelLayer::raytraceFreespace(const Observation& obs, double* min_x, double* min_y, double* max_x, double* max_y)
{
  const double res = costmap_.getResolution(), zres = voxel_config_.z_resolution;
  const double gx0 = costmap_.getOriginX(), gy0 = costmap_.getOriginY(), gz0 = voxel_config_.origin_z;
  const double gx1 = gx0 + costmap_.getSizeInMetersX(), gy1 = gy0 + costmap_.getSizeInMetersY();
  const double gz1 = gz0 + voxel_config_.z_voxels * zres;
  const double ox = obs.origin_x, oy = obs.origin_y, oz = obs.origin_z;
  if (!(ox >= gx0 && ox < gx1 && oy >= gy0 && oy < gy1 && oz >= gz0 && oz < gz1))
  {
    context_->report(Severity::Warn, "origin_outside",
                     name_ +
                         ": a sensor origin is outside the voxel grid (x, y in the costmap, z in [origin_z, "
                         "origin_z + z_voxels * z_resolution)), its rays clear nothing");
    return;
  }
  touch(ox, oy, min_x, min_y, max_x, max_y);

  uint32_t* cols = voxels_.data();
  uint8_t* grid = costmap_.data();
  const unsigned int mark_t = static_cast<unsigned int>(voxel_config_.mark_threshold);
  const unsigned int unknown_t = static_cast<unsigned int>(voxel_config_.unknown_threshold);
  auto clear = [cols, grid, mark_t, unknown_t](unsigned int index, unsigned int z)
  {
    uint32_t& col = cols[index];
    const uint32_t bits = ((1u << 16) | 1u) << z;
    if ((col & bits) == 0) return;  // already free: the column's counts did not change
    col &= ~bits;
    if (VoxelGrid::markedCount(col) <= mark_t)
      grid[index] = VoxelGrid::unknownCount(col) > unknown_t ? NO_INFORMATION : FREE_SPACE;
  };
  // Voxel units of the grid; the top and far edges are pulled in by a hair so that floor() stays inside.
  const double lim_x = voxels_.sizeX() * (1.0 - 1e-9), lim_y = voxels_.sizeY() * (1.0 - 1e-9),
               lim_z = voxels_.sizeZ() * (1.0 - 1e-9);
  double ex_min = ox, ey_min = oy, ex_max = ox, ey_max = oy;
  auto ray = [&](const Point3f& p)
  {
    const double a = p.x - ox, b = p.y - oy, c = p.z - oz;
    const double d = std::sqrt(a * a + b * b + c * c);
    if (!(d > 0.0)) return;
    double t = std::min(1.0, obs.raytrace_max_range / d);
    if (ox + t * a < gx0) t = (gx0 - ox) / a;
    if (ox + t * a > gx1) t = (gx1 - ox) / a;
    if (oy + t * b < gy0) t = (gy0 - oy) / b;
    if (oy + t * b > gy1) t = (gy1 - oy) / b;
    if (oz + t * c < gz0) t = (gz0 - oz) / c;
    if (oz + t * c > gz1) t = (gz1 - oz) / c;
    t = std::max(0.0, std::min(1.0, t));
    const double t0 = obs.raytrace_min_range / d;
    if (t0 >= t) return;
    auto vx = [&](double s) { return std::min(lim_x, std::max(0.0, (ox + s * a - gx0) / res)); };
    auto vy = [&](double s) { return std::min(lim_y, std::max(0.0, (oy + s * b - gy0) / res)); };
    auto vz = [&](double s) { return std::min(lim_z, std::max(0.0, (oz + s * c - gz0) / zres)); };
    voxels_.walkLine(clear, vx(t0), vy(t0), vz(t0), vx(t), vy(t), vz(t));
    const double ex = ox + t * a, ey = oy + t * b;
    ex_min = std::min(ex_min, ex);
    ey_min = std::min(ey_min, ey);
    ex_max = std::max(ex_max, ex);
    ey_max = std::max(ey_max, ey);
  };
  for (const Point3f& p : obs.points)
    ray(p);
  for (const Point3f& p : obs.clear_only)
    ray(p);
  touch(ex_min, ey_min, min_x, min_y, max_x, max_y);
  touch(ex_max, ey_max, min_x, min_y, max_x, max_y);
}

void VoxelLayer::markObservation(const Observation& obs, double* min_x, double* min_y, double* max_x, double* max_y)
{
  const double max2 = obs.obstacle_max_range * obs.obstacle_max_range;
  const double min2 = obs.obstacle_min_range * obs.obstacle_min_range;
  const double gz0 = voxel_config_.origin_z, zres = voxel_config_.z_resolution;
  const double levels = voxel_config_.z_voxels;
  const unsigned int mark_t = static_cast<unsigned int>(voxel_config_.mark_threshold);
  uint8_t* grid = costmap_.data();
  for (const Point3f& p : obs.points)
  {
    if (!config_.marksHeight(p.z)) continue;
    const double dx = p.x - obs.origin_x, dy = p.y - obs.origin_y, dz = p.z - obs.origin_z;
    const double d2 = dx * dx + dy * dy + dz * dz;
    if (d2 > max2 || d2 < min2) continue;
    unsigned int mx, my;
    if (!costmap_.worldToMap(p.x, p.y, mx, my)) continue;
    const double fz = (p.z - gz0) / zres;
    if (!(fz >= 0.0 && fz < levels)) continue;
    if (voxels_.markVoxel(mx, my, static_cast<unsigned int>(fz), mark_t))
    {
      grid[costmap_.getIndex(mx, my)] = LETHAL_OBSTACLE;
      touch(p.x, p.y, min_x, min_y, max_x, max_y);
    }
  }
}
}  // namespace costmap_layers
