#include "costmap_layers/core/grid/grid_sampler.hpp"

#include <algorithm>
#include <cmath>

// The byte gather of GridSampler::forEachRow, written once with Highway (foreach_target.h compiles it
// per target; HWY_DYNAMIC_DISPATCH picks one at run time).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/core/grid/grid_sampler.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace costmap_layers
{
namespace HWY_NAMESPACE
{
namespace hn = hwy::HWY_NAMESPACE;

/// For each chunk k: width window columns from pos[k] on take mask_row[src[k] + shuffle[16 k + i]]
/// (one 16-byte load and one byte shuffle; indices 0x80 past the width).
void GatherMaskBytes(const uint8_t* HWY_RESTRICT mask_row, const int32_t* HWY_RESTRICT chunks, std::size_t count,
                     const uint8_t* HWY_RESTRICT shuffle, int width, uint8_t* HWY_RESTRICT out)
{
#if HWY_TARGET == HWY_SCALAR
  for (std::size_t k = 0; k < count; ++k)
    for (int i = 0; i < width; ++i)
      out[chunks[2 * k] + i] = mask_row[chunks[2 * k + 1] + shuffle[16 * k + static_cast<std::size_t>(i)]];
#else
  const hn::FixedTag<uint8_t, 16> d;
  const hn::FixedTag<uint8_t, 8> d8;
  for (std::size_t k = 0; k < count; ++k)
  {
    const auto v = hn::LoadU(d, mask_row + chunks[2 * k + 1]);
    const auto gathered = hn::TableLookupBytesOr0(v, hn::LoadU(d, shuffle + 16 * k));
    if (width == 16)
      hn::StoreU(gathered, d, out + chunks[2 * k]);
    else
      hn::StoreU(hn::LowerHalf(d8, gathered), d8, out + chunks[2 * k]);
  }
#endif
}
}  // namespace HWY_NAMESPACE
}  // namespace costmap_layers
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace costmap_layers
{
HWY_EXPORT(GatherMaskBytes);

void GridSampler::shuffleRow(const uint8_t* mask_row, uint8_t* out) const
{
  HWY_DYNAMIC_DISPATCH(GatherMaskBytes)
  (mask_row, chunks_.data(), chunks_.size() / 2, chunk_shuffle_.data(), chunk_width_, out);
}

void GridSampler::build(const Costmap2D& master, const CellWindow& window, const GridPlacement& mask,
                        const Transform2D& to_mask)
{
  window_ = window;
  // Master cell (i, j) centre in the global frame, then in the mask frame, then in mask cells.
  const double res = master.getResolution();
  const double ox = master.getOriginX() + 0.5 * res, oy = master.getOriginY() + 0.5 * res;
  // Three points through the one point-to-grid rule; the rest is affine.
  auto toGrid = [&](double wx, double wy, double& gx, double& gy) { toGridCells(mask, to_mask, wx, wy, gx, gy); };
  toGrid(ox, oy, p0x_, p0y_);
  double ux, uy, vx, vy;
  toGrid(ox + res, oy, ux, uy);
  toGrid(ox, oy + res, vx, vy);
  dux_ = ux - p0x_;
  duy_ = uy - p0y_;
  dvx_ = vx - p0x_;
  dvy_ = vy - p0y_;

  constexpr double eps = 1e-9;
  axis_aligned_ = std::fabs(duy_) < eps && std::fabs(dvx_) < eps;
  // The whole-cell offset must fit an int with room for the window added to it; a mask that far off
  // (a tiny resolution far from the origin) goes through the per-column path, which compares in double.
  constexpr double max_offset = 1e9;
  offset_ = axis_aligned_ && std::fabs(dux_ - 1.0) < eps && std::fabs(dvy_ - 1.0) < eps &&
            std::fabs(p0x_) < max_offset && std::fabs(p0y_) < max_offset;
  if (offset_)
  {
    offset_x_ = static_cast<int>(std::floor(p0x_ + 1e-9));
    offset_y_ = static_cast<int>(std::floor(p0y_ + 1e-9));
    return;
  }
  if (!axis_aligned_) return;
  const int mask_w = static_cast<int>(mask.width), mask_h = static_cast<int>(mask.height);
  cols_.resize(static_cast<std::size_t>(std::max(0, window.xn - window.x0)));
  rows_.resize(static_cast<std::size_t>(std::max(0, window.yn - window.y0)));
  for (int i = window.x0; i < window.xn; ++i)
  {
    const double g = std::floor(p0x_ + i * dux_);
    cols_[static_cast<std::size_t>(i - window.x0)] = (g >= 0 && g < mask_w) ? static_cast<int32_t>(g) : -1;
  }
  for (int j = window.y0; j < window.yn; ++j)
  {
    const double g = std::floor(p0y_ + j * dvy_);
    rows_[static_cast<std::size_t>(j - window.y0)] = (g >= 0 && g < mask_h) ? static_cast<int32_t>(g) : -1;
  }

  // The on-mask columns: one run, since the column map is linear (checked, not assumed).
  const int n = static_cast<int>(cols_.size());
  cols_lo_ = 0;
  while (cols_lo_ < n && cols_[static_cast<std::size_t>(cols_lo_)] < 0)
    ++cols_lo_;
  cols_hi_ = n;
  while (cols_hi_ > cols_lo_ && cols_[static_cast<std::size_t>(cols_hi_ - 1)] < 0)
    --cols_hi_;
  cols_contiguous_ = std::all_of(cols_.begin() + cols_lo_, cols_.begin() + cols_hi_, [](int32_t c) { return c >= 0; });

  // The byte-gather plan: blocks of 16 (else 8) window columns whose mask columns all fall within 16
  // consecutive mask bytes, so that one load and one byte shuffle fill a block. The last block overlaps
  // the one before when the run is not a multiple of the width. Mask columns nearer than 16 to the end
  // of the row are read from mask_w - 16 on, so that no load passes the end of the row.
  chunk_width_ = 0;
  chunks_.clear();
  chunk_shuffle_.clear();
  if (!cols_contiguous_ || mask_w < 16) return;
  for (const int width : {16, 8})
  {
    if (cols_hi_ - cols_lo_ < width) continue;
    bool fits = true;
    for (int pos = cols_lo_; pos < cols_hi_; pos += width)
    {
      const int p = std::min(pos, cols_hi_ - width);
      const auto first = cols_.begin() + p;
      const auto [lo_it, hi_it] = std::minmax_element(first, first + width);
      if (*hi_it - *lo_it > 15)
      {
        fits = false;
        break;
      }
      const int32_t src = std::min(*lo_it, mask_w - 16);
      chunks_.push_back(p);
      chunks_.push_back(src);
      for (int k = 0; k < 16; ++k)
        chunk_shuffle_.push_back(k < width ? static_cast<uint8_t>(first[k] - src) : uint8_t{0x80});
    }
    if (fits)
    {
      chunk_width_ = width;
      return;
    }
    chunks_.clear();
    chunk_shuffle_.clear();
  }
}
}  // namespace costmap_layers
#endif  // HWY_ONCE
