// The one grid-to-grid sampler of the core: filters sample their masks with it, the static layer its
// map in a rolling window.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "costmap_layers/core/grid/costmap_2d.hpp"
#include "costmap_layers/core/data/grid_data.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/grid/transform2d.hpp"

namespace costmap_layers
{
/// Where a grid lies: cells, resolution [m/cell], origin [m, rad] of its cell (0, 0) corner.
struct GridPlacement
{
  uint32_t width = 0;
  uint32_t height = 0;
  double resolution = 1.0;
  double origin_x = 0.0;
  double origin_y = 0.0;
  double origin_yaw = 0.0;

  static GridPlacement of(const OccupancyGridData& g)
  {
    return {g.width, g.height, g.resolution, g.origin_x, g.origin_y, g.origin_yaw};
  }
};

/// The one rule from a point to a grid: (wx, wy) in the costmap's global frame, through to_grid (global
/// frame -> the grid's frame), to the grid's cell coordinates (gx, gy) [cells]: cell (i, j) spans
/// [i, i + 1) x [j, j + 1).
inline void toGridCells(const GridPlacement& g, const Transform2D& to_grid, double wx, double wy, double& gx,
                        double& gy)
{
  double fx, fy;
  to_grid.apply(wx, wy, fx, fy);
  fx -= g.origin_x;
  fy -= g.origin_y;
  const double c = std::cos(g.origin_yaw), s = std::sin(g.origin_yaw);
  gx = (c * fx + s * fy) / g.resolution;
  gy = (-s * fx + c * fy) / g.resolution;
}

/// The index of the grid cell under a point, or false when the point is off the grid (NaN too).
inline bool gridCellAt(const GridPlacement& g, const Transform2D& to_grid, double wx, double wy, std::size_t& index)
{
  double gx, gy;
  toGridCells(g, to_grid, wx, wy, gx, gy);
  if (!(gx >= 0.0) || !(gy >= 0.0) || gx >= g.width || gy >= g.height) return false;
  index = static_cast<std::size_t>(gy) * g.width + static_cast<std::size_t>(gx);
  return true;
}

/// The one grid-to-grid sampler: how master cells of one update window map to cells of another grid
/// (a filter's mask, or the static layer's map in a rolling window), each master cell taking the cell
/// under its centre: per master column a source column (or -1 outside) and per master row a source
/// row when the grids are axis-aligned, an offset when in addition the resolutions are equal,
/// otherwise a per-cell affine map. Built once per update, never per cell. ("mask" below is the source
/// grid.)
class GridSampler
{
public:
  /// @param to_mask  transform from the costmap's global frame into the mask's frame
  void build(const Costmap2D& master, const CellWindow& window, const GridPlacement& mask, const Transform2D& to_mask);
  void build(const Costmap2D& master, const CellWindow& window, const OccupancyGridData& mask,
             const Transform2D& to_mask)
  {
    build(master, window, GridPlacement::of(mask), to_mask);
  }

  /// Calls fn(master_cell, source_value) for every cell of the window that lies on the source grid
  /// (source: one value per source cell, row-major); cells off it are not visited.
  template <class T, class Fn>
  void forEach(Costmap2D& master, const T* source, uint32_t source_width, uint32_t source_height, Fn&& fn) const;
  template <class Fn>
  void forEach(Costmap2D& master, const OccupancyGridData& mask, Fn&& fn) const
  {
    forEach(master, mask.data.data(), mask.width, mask.height, fn);
  }

  /// Row-wise form for fast kernels. `source` holds one value per mask cell (mask-sized, row-major).
  /// For each window row that meets the mask, calls fn(master_cells, values, n): values[k] belongs to
  /// master_cells[k]. Mask cells are read in place when the mapping is an offset; otherwise they are
  /// gathered into scratch (reused when consecutive rows share a mask row), with `neutral` for cells
  /// that fall outside the mask.
  template <class T, class RowFn>
  void forEachRow(Costmap2D& master, const T* source, uint32_t source_width, uint32_t source_height, T neutral,
                  std::vector<T>& scratch, RowFn&& fn) const;

  /// True when rows and columns map independently (no rotation between costmap and mask).
  bool axisAligned() const { return axis_aligned_; }
  /// True when, in addition, one master cell is one mask cell (an offset).
  bool isOffset() const { return offset_; }
  /// Window columns per block of forEachRow's byte gather (16 or 8; one byte shuffle per block), or 0
  /// when byte masks are gathered cell by cell (offset, rotated, or no block fits the resolution ratio).
  int byteGatherBlock() const { return offset_ || !axis_aligned_ ? 0 : chunk_width_; }

private:
  /// Gathers the on-mask columns of one window row from a byte mask row through the shuffle plan (a
  /// Highway kernel in costmap_filter.cpp).
  void shuffleRow(const uint8_t* mask_row, uint8_t* out) const;

  CellWindow window_;
  bool axis_aligned_ = true;
  bool offset_ = false;
  int offset_x_ = 0, offset_y_ = 0;  ///< mask cell = master cell + offset, when isOffset()
  std::vector<int32_t> cols_;        ///< mask column per window column, -1 outside
  std::vector<int32_t> rows_;        ///< mask row per window row, -1 outside
  // Axis-aligned, not an offset: the window columns on the mask are [cols_lo_, cols_hi_) (one run, as
  // the map is linear) when cols_contiguous_; the byte gather then runs through a shuffle plan built
  // once per update (chunk_width_ 16 or 8 columns per chunk, 0 when no plan fits the mapping).
  int cols_lo_ = 0, cols_hi_ = 0;
  bool cols_contiguous_ = false;
  int chunk_width_ = 0;
  /// The blocks of the byte gather, two numbers each: chunk_width_ window columns starting at window
  /// column pos take bytes src + shuffle[0..chunk_width_) of the mask row (shuffle indices 0..15, so
  /// one 16-byte load per block).
  std::vector<int32_t> chunks_;
  std::vector<uint8_t> chunk_shuffle_;  ///< 16 indices per chunk (0x80 past chunk_width_)
  // General case: mask-grid coordinates [cells] of master cell (i, j) = p0 + i * du + j * dv.
  double p0x_ = 0, p0y_ = 0, dux_ = 0, duy_ = 0, dvx_ = 0, dvy_ = 0;
};

template <class T, class RowFn>
void GridSampler::forEachRow(Costmap2D& master, const T* source, uint32_t source_width, uint32_t source_height,
                             T neutral, std::vector<T>& scratch, RowFn&& fn) const
{
  if (window_.empty()) return;
  const int mask_w = static_cast<int>(source_width);
  const int mask_h = static_cast<int>(source_height);
  const std::size_t n = static_cast<std::size_t>(window_.xn - window_.x0);
  if (!offset_) scratch.resize(n);
  // Axis-aligned gather: the columns off the mask hold `neutral` in every row, written once here.
  bool use_shuffle = false;
  if (!offset_ && axis_aligned_ && cols_contiguous_)
  {
    std::fill(scratch.begin(), scratch.begin() + cols_lo_, neutral);
    std::fill(scratch.begin() + cols_hi_, scratch.end(), neutral);
    if constexpr (std::is_integral_v<T> && sizeof(T) == 1) use_shuffle = chunk_width_ > 0;
  }
  int cached_row = -1;
  for (int j = window_.y0; j < window_.yn; ++j)
  {
    uint8_t* row = master.data() + static_cast<std::size_t>(j) * master.getSizeInCellsX();
    if (offset_)
    {
      const int my = j + offset_y_;
      if (my < 0 || my >= mask_h) continue;
      const int i0 = std::max(window_.x0, -offset_x_);
      const int i1 = std::min(window_.xn, mask_w - offset_x_);
      if (i0 >= i1) continue;
      fn(row + i0, source + static_cast<std::size_t>(my) * mask_w + offset_x_ + i0, static_cast<std::size_t>(i1 - i0));
    }
    else if (axis_aligned_)
    {
      const int my = rows_[static_cast<std::size_t>(j - window_.y0)];
      if (my < 0) continue;
      if (my != cached_row)
      {
        const T* mrow = source + static_cast<std::size_t>(my) * mask_w;
        if (use_shuffle)
        {
          if constexpr (std::is_integral_v<T> && sizeof(T) == 1)
            shuffleRow(reinterpret_cast<const uint8_t*>(mrow), reinterpret_cast<uint8_t*>(scratch.data()));
        }
        else if (cols_contiguous_)
        {
          const int32_t* cols = cols_.data();
          T* out = scratch.data();
          for (int k = cols_lo_; k < cols_hi_; ++k)
            out[k] = mrow[cols[k]];
        }
        else
          for (std::size_t k = 0; k < n; ++k)
            scratch[k] = cols_[k] >= 0 ? mrow[cols_[k]] : neutral;
        cached_row = my;
      }
      fn(row + window_.x0, scratch.data(), n);
    }
    else
    {
      double px = p0x_ + window_.x0 * dux_ + j * dvx_;
      double py = p0y_ + window_.x0 * duy_ + j * dvy_;
      for (std::size_t k = 0; k < n; ++k, px += dux_, py += duy_)
      {
        const bool inside = px >= 0.0 && py >= 0.0 && px < mask_w && py < mask_h;
        scratch[k] = inside ? source[static_cast<std::size_t>(py) * mask_w + static_cast<std::size_t>(px)] : neutral;
      }
      fn(row + window_.x0, scratch.data(), n);
    }
  }
}

template <class T, class Fn>
void GridSampler::forEach(Costmap2D& master, const T* source, uint32_t source_width, uint32_t source_height,
                          Fn&& fn) const
{
  if (window_.empty()) return;
  const int mask_w = static_cast<int>(source_width);
  const int mask_h = static_cast<int>(source_height);
  const T* mdata = source;
  for (int j = window_.y0; j < window_.yn; ++j)
  {
    uint8_t* row = master.data() + static_cast<std::size_t>(j) * master.getSizeInCellsX();
    if (offset_)
    {
      const int my = j + offset_y_;
      if (my < 0 || my >= mask_h) continue;
      const int i0 = std::max(window_.x0, -offset_x_);
      const int i1 = std::min(window_.xn, mask_w - offset_x_);
      const T* mrow = mdata + static_cast<std::size_t>(my) * mask_w + offset_x_;
      for (int i = i0; i < i1; ++i)
        fn(row[i], mrow[i]);
    }
    else if (axis_aligned_)
    {
      const int my = rows_[static_cast<std::size_t>(j - window_.y0)];
      if (my < 0) continue;
      const T* mrow = mdata + static_cast<std::size_t>(my) * mask_w;
      const int32_t* cols = cols_.data() - window_.x0;
      for (int i = window_.x0; i < window_.xn; ++i)
      {
        const int mx = cols[i];
        if (mx >= 0) fn(row[i], mrow[mx]);
      }
    }
    else
    {
      double px = p0x_ + window_.x0 * dux_ + j * dvx_;
      double py = p0y_ + window_.x0 * duy_ + j * dvy_;
      for (int i = window_.x0; i < window_.xn; ++i, px += dux_, py += duy_)
      {
        if (!(px >= 0.0 && py >= 0.0 && px < mask_w && py < mask_h)) continue;  // NaN too
        fn(row[i], mdata[static_cast<std::size_t>(py) * mask_w + static_cast<std::size_t>(px)]);
      }
    }
  }
}
}  // namespace costmap_layers
