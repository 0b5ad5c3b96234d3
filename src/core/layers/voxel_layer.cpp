#include "costmap_layers/core/layers/voxel_layer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/layers/ray_geometry.hpp"
#include "costmap_layers/core/rules/limits.hpp"

namespace costmap_layers
{
void VoxelLayer::ClearedWalks::begin(std::size_t walks)
{
  std::size_t size = 64;
  while (size < 2 * walks && size < kMaxSlots)
    size *= 2;
  if (slots_.size() < size)
  {
    slots_.assign(size, Slot{});
    epoch_ = 0;
  }
  mask_ = slots_.size() - 1;
  used_ = 0;
  if (++epoch_ == 0)  // wrapped: every slot of an old epoch would look current again
  {
    for (Slot& s : slots_)
      s.epoch = 0;
    epoch_ = 1;
  }
}

bool VoxelLayer::ClearedWalks::covered(uint64_t key, uint32_t lo, uint32_t hi)
{
  // Fibonacci hashing, linear probing; the table is kept at most half full, so a free slot exists.
  std::size_t i = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 32) & mask_;
  while (true)
  {
    Slot& s = slots_[i];
    if (s.epoch != epoch_)
    {
      // Half full (a cloud of more than kMaxSlots / 2 end voxels): the walks not noted are walked.
      if (2 * used_ >= slots_.size()) return false;
      s = Slot{key, lo, hi, epoch_};
      ++used_;
      return false;
    }
    if (s.key == key)
    {
      if (lo >= s.lo && hi <= s.hi) return true;
      if (lo <= s.hi + 1 && hi + 1 >= s.lo)  // they touch: both runs are cleared, so their union is
      {
        s.lo = std::min(s.lo, lo);
        s.hi = std::max(s.hi, hi);
      }
      else if (hi - lo > s.hi - s.lo)
      {
        s.lo = lo;
        s.hi = hi;
      }
      return false;
    }
    i = (i + 1) & mask_;
  }
}

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
  if (!voxel_config_.publish_voxel_map) return;
  // costmap_2d publishes voxel_grid in the layer's namespace; RViz reads the cube list or the cloud.
  for (const auto& [kind, topic] : {std::pair{OutputKind::VoxelGrid, kVoxelGridTopic},
                                    std::pair{OutputKind::VoxelMarkers, kVoxelMarkersTopic},
                                    std::pair{OutputKind::VoxelCloud, kVoxelCloudTopic}})
  {
    OutputPort port;
    port.kind = kind;
    port.topic = topic;
    port.layer_namespace = true;
    port.on_demand = true;
    addOutput(port);
  }
}

void VoxelLayer::updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y,
                              double* max_x, double* max_y)
{
  ObstacleLayer::updateBounds(robot_x, robot_y, robot_yaw, min_x, min_y, max_x, max_y);
  if (voxel_config_.publish_voxel_map) publishVoxels();
}

void VoxelLayer::publishVoxels()
{
  // One copy per cycle, shared by every output someone reads; none when nobody does.
  std::shared_ptr<const VoxelGridData> snapshot;
  for (const auto& [kind, topic] : {std::pair{OutputKind::VoxelGrid, kVoxelGridTopic},
                                    std::pair{OutputKind::VoxelMarkers, kVoxelMarkersTopic},
                                    std::pair{OutputKind::VoxelCloud, kVoxelCloudTopic}})
  {
    if (!outputWanted(topic)) continue;
    if (!snapshot)
    {
      auto grid = std::make_shared<VoxelGridData>();
      grid->size_x = voxels_.sizeX();
      grid->size_y = voxels_.sizeY();
      grid->size_z = voxels_.sizeZ();
      grid->origin_x = costmap_.getOriginX();
      grid->origin_y = costmap_.getOriginY();
      grid->origin_z = voxel_config_.origin_z;
      grid->resolution = costmap_.getResolution();
      grid->z_resolution = voxel_config_.z_resolution;
      grid->data.assign(voxels_.data(), voxels_.data() + std::size_t{voxels_.sizeX()} * voxels_.sizeY());
      snapshot = std::move(grid);
    }
    OutputEvent event;
    event.kind = kind;
    event.topic = topic;
    event.voxels = snapshot;
    emit(event);
  }
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
  // Voxel units of the grid; the top and far edges are pulled in by a hair so that the voxel of a point
  // on them is the last one inside.
  const double lim_x = voxels_.sizeX() * (1.0 - 1e-9), lim_y = voxels_.sizeY() * (1.0 - 1e-9),
               lim_z = voxels_.sizeZ() * (1.0 - 1e-9);
  auto vx = [&](double x) { return std::min(lim_x, std::max(0.0, (x - gx0) / res)); };
  auto vy = [&](double y) { return std::min(lim_y, std::max(0.0, (y - gy0) / res)); };
  auto vz = [&](double z) { return std::min(lim_z, std::max(0.0, (z - gz0) / zres)); };
  const double sx = vx(ox), sy = vy(oy), sz = vz(oz);
  const auto ix0 = static_cast<unsigned int>(sx), iy0 = static_cast<unsigned int>(sy),
             iz0 = static_cast<unsigned int>(sz);
  // costmap_2d's reach (voxel_grid's raytraceLine with cellDistance): the ranges in whole cells of the
  // costmap, rounded up, counted along the line in voxel units, where a z voxel counts as one cell
  // whatever z_resolution is. The same rule as the obstacle layer's: step k of the walk lies k * step
  // along the line, and min_cells <= k * step <= max_cells is cleared, the end voxel included. NaN
  // clears nothing.
  const double min_cells = costmap_.cellDistance(obs.raytrace_min_range);
  const double max_cells =
      std::isnan(obs.raytrace_max_range) ? -1.0 : static_cast<double>(costmap_.cellDistance(obs.raytrace_max_range));
  const unsigned int size_x = costmap_.getSizeInCellsX();
  TouchedBox<unsigned int> visited_cells(ix0, iy0);
  auto ray = [&](const Point3f& p)
  {
    const double a = p.x - ox, b = p.y - oy, c = p.z - oz;
    if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(c)) return;
    // As costmap_2d: the line runs towards the reading, cut at the grid's box only, so a reading beyond
    // the range keeps its direction; the range then stops the walk along it.
    const double t = clipRayToBox<3>({ox, oy, oz}, {a, b, c}, {gx0, gy0, gz0}, {gx1, gy1, gz1}, 1.0);
    const double ex = vx(ox + t * a), ey = vy(oy + t * b), ez = vz(oz + t * c);
    const auto ix1 = static_cast<unsigned int>(ex), iy1 = static_cast<unsigned int>(ey),
               iz1 = static_cast<unsigned int>(ez);
    const unsigned int steps = VoxelGrid::lineSteps(ix0, iy0, iz0, ix1, iy1, iz1);
    // voxel_grid measures the line between the exact points (in voxel units) and steps between whole
    // voxels, so a step is length / steps along it (0 for a reading in the sensor's voxel).
    const double length = std::sqrt((ex - sx) * (ex - sx) + (ey - sy) * (ey - sy) + (ez - sz) * (ez - sz));
    const double step = steps == 0 ? 0.0 : length / steps;
    // The steps cleared: min_cells <= k * step <= max_cells, k up to the walk's last; a reading in the
    // sensor's voxel (step 0) clears that voxel when the range allows 0.
    int64_t lo = 0, hi = -1;
    if (step == 0.0)
      hi = 0.0 >= min_cells && 0.0 <= max_cells ? 0 : -1;
    else
    {
      lo = firstStepAtLeast(step, min_cells);
      hi = std::min<int64_t>(steps, lastStepAtMost(step, max_cells));
    }
    if (hi < lo) return;
    const uint64_t end_voxel = (static_cast<uint64_t>(iy1) * size_x + ix1) * VoxelGrid::kMaxLevels + iz1;
    if (cleared_walks_.covered(end_voxel, static_cast<uint32_t>(lo), static_cast<uint32_t>(hi))) return;
    bool cleared = false;
    unsigned int last = 0;
    voxels_.traceLine(
        [&](unsigned int index, unsigned int z, unsigned int k)
        {
          if (k < static_cast<uint64_t>(lo)) return;
          clear(index, z);
          last = index;
          cleared = true;
        },
        ix0, iy0, iz0, ix1, iy1, iz1, static_cast<unsigned int>(hi));
    // The walk stays in the box of its first and last voxels: the origin's column and the last cleared
    // one hold every column it changed. (A walk found covered ends within the box of one that was
    // walked: each coordinate of a walk moves one way only.)
    if (cleared) visited_cells.add(last % size_x, last / size_x);
  };
  cleared_walks_.begin(obs.points.size() + obs.clear_only.size());
  for (const Point3f& p : obs.points)
    ray(p);
  for (const Point3f& p : obs.clear_only)
    ray(p);
  double wx, wy;
  costmap_.mapToWorld(visited_cells.min_x, visited_cells.min_y, wx, wy);
  touch(wx, wy, min_x, min_y, max_x, max_y);
  costmap_.mapToWorld(visited_cells.max_x, visited_cells.max_y, wx, wy);
  touch(wx, wy, min_x, min_y, max_x, max_y);
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
