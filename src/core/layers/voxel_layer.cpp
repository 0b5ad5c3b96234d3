#include "costmap_layers/core/layers/voxel_layer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "costmap_layers/core/layers/ray_geometry.hpp"
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
  TouchedBox<double> ends(ox, oy);
  auto ray = [&](const Point3f& p)
  {
    const double a = p.x - ox, b = p.y - oy, c = p.z - oz;
    const double d = std::sqrt(a * a + b * b + c * c);
    if (!(d > 0.0)) return;
    double t = std::min(1.0, obs.raytrace_max_range / d);
    t = clipRayToBox<3>({ox, oy, oz}, {a, b, c}, {gx0, gy0, gz0}, {gx1, gy1, gz1}, t);
    const double t0 = obs.raytrace_min_range / d;
    if (t0 >= t) return;
    auto vx = [&](double s) { return std::min(lim_x, std::max(0.0, (ox + s * a - gx0) / res)); };
    auto vy = [&](double s) { return std::min(lim_y, std::max(0.0, (oy + s * b - gy0) / res)); };
    auto vz = [&](double s) { return std::min(lim_z, std::max(0.0, (oz + s * c - gz0) / zres)); };
    voxels_.walkLine(clear, vx(t0), vy(t0), vz(t0), vx(t), vy(t), vz(t));
    ends.add(ox + t * a, oy + t * b);
  };
  for (const Point3f& p : obs.points)
    ray(p);
  for (const Point3f& p : obs.clear_only)
    ray(p);
  touch(ends.min_x, ends.min_y, min_x, min_y, max_x, max_y);
  touch(ends.max_x, ends.max_y, min_x, min_y, max_x, max_y);
}

void VoxelLayer::markObservation(const Observation& obs, double* min_x, double* min_y, double* max_x, double* max_y)
{
  const double gz0 = voxel_config_.origin_z, zres = voxel_config_.z_resolution;
  const double levels = voxel_config_.z_voxels;
  const unsigned int mark_t = static_cast<unsigned int>(voxel_config_.mark_threshold);
  uint8_t* grid = costmap_.data();
  TouchedBox<double> marked;
  for (const Point3f& p : obs.points)
  {
    unsigned int mx, my;
    if (!marksPoint(obs, p, mx, my)) continue;
    const double fz = (p.z - gz0) / zres;
    if (!(fz >= 0.0 && fz < levels)) continue;
    if (voxels_.markVoxel(mx, my, static_cast<unsigned int>(fz), mark_t))
    {
      grid[costmap_.getIndex(mx, my)] = LETHAL_OBSTACLE;
      marked.add(p.x, p.y);
    }
  }
  if (!marked.empty())
  {
    touch(marked.min_x, marked.min_y, min_x, min_y, max_x, max_y);
    touch(marked.max_x, marked.max_y, min_x, min_y, max_x, max_y);
  }
}
}  // namespace costmap_layers
