#include "costmap_layers/core/costmap/costmap_layer.hpp"

#include <algorithm>
#include <cstring>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"

namespace costmap_layers
{
void CostmapLayer::matchSize()
{
  const Costmap2D& master = layered_costmap_->getCostmap();
  costmap_.resizeMap(master.getSizeInCellsX(), master.getSizeInCellsY(), master.getResolution(), master.getOriginX(),
                     master.getOriginY());
}

std::pair<int, int> CostmapLayer::followRollingMaster()
{
  if (!layered_costmap_->isRolling()) return {0, 0};
  const Costmap2D& master = layered_costmap_->getCostmap();
  return costmap_.followOrigin(master.getOriginX(), master.getOriginY());
}

void CostmapLayer::touch(double x, double y, double* min_x, double* min_y, double* max_x, double* max_y)
{
  *min_x = std::min(x, *min_x);
  *min_y = std::min(y, *min_y);
  *max_x = std::max(x, *max_x);
  *max_y = std::max(y, *max_y);
}

void CostmapLayer::addExtraBounds(double mx0, double my0, double mx1, double my1)
{
  if (!has_extra_bounds_)
  {
    extra_min_x_ = mx0;
    extra_min_y_ = my0;
    extra_max_x_ = mx1;
    extra_max_y_ = my1;
    has_extra_bounds_ = true;
    return;
  }
  extra_min_x_ = std::min(mx0, extra_min_x_);
  extra_min_y_ = std::min(my0, extra_min_y_);
  extra_max_x_ = std::max(mx1, extra_max_x_);
  extra_max_y_ = std::max(my1, extra_max_y_);
}

void CostmapLayer::useExtraBounds(double* min_x, double* min_y, double* max_x, double* max_y)
{
  if (!has_extra_bounds_) return;
  *min_x = std::min(extra_min_x_, *min_x);
  *min_y = std::min(extra_min_y_, *min_y);
  *max_x = std::max(extra_max_x_, *max_x);
  *max_y = std::max(extra_max_y_, *max_y);
  has_extra_bounds_ = false;
}

namespace
{
/// Runs merge(master_row, own_row, n) over each row of the window shared by both grids.
template <class RowMerge>
void mergeRows(const Costmap2D& own, Costmap2D& master, int min_i, int min_j, int max_i, int max_j, RowMerge merge)
{
  const int sx = static_cast<int>(std::min(own.getSizeInCellsX(), master.getSizeInCellsX()));
  const int sy = static_cast<int>(std::min(own.getSizeInCellsY(), master.getSizeInCellsY()));
  min_i = std::max(min_i, 0);
  min_j = std::max(min_j, 0);
  max_i = std::min(max_i, sx);
  max_j = std::min(max_j, sy);
  if (min_i >= max_i || min_j >= max_j) return;
  const std::size_t n = static_cast<std::size_t>(max_i - min_i);
  for (int j = min_j; j < max_j; ++j)
  {
    const uint8_t* src = own.data() + own.getIndex(static_cast<unsigned>(min_i), static_cast<unsigned>(j));
    uint8_t* dst = master.data() + master.getIndex(static_cast<unsigned>(min_i), static_cast<unsigned>(j));
    merge(dst, src, n);
  }
}
}  // namespace

void CostmapLayer::updateWithMax(Costmap2D& master, int min_i, int min_j, int max_i, int max_j) const
{
  mergeRows(costmap_, master, min_i, min_j, max_i, max_j,
            [](uint8_t* m, const uint8_t* o, std::size_t n)
            {
              for (std::size_t k = 0; k < n; ++k)
              {
                const uint8_t own = o[k], old = m[k];
                const bool take = own != NO_INFORMATION && (old == NO_INFORMATION || old < own);
                m[k] = take ? own : old;
              }
            });
}

void CostmapLayer::updateWithTrueOverwrite(Costmap2D& master, int min_i, int min_j, int max_i, int max_j) const
{
  mergeRows(costmap_, master, min_i, min_j, max_i, max_j,
            [](uint8_t* m, const uint8_t* o, std::size_t n) { std::memcpy(m, o, n); });
}

void CostmapLayer::updateWithOverwrite(Costmap2D& master, int min_i, int min_j, int max_i, int max_j) const
{
  mergeRows(costmap_, master, min_i, min_j, max_i, max_j,
            [](uint8_t* m, const uint8_t* o, std::size_t n)
            {
              for (std::size_t k = 0; k < n; ++k)
                m[k] = o[k] != NO_INFORMATION ? o[k] : m[k];
            });
}

void CostmapLayer::updateWithAddition(Costmap2D& master, int min_i, int min_j, int max_i, int max_j) const
{
  mergeRows(costmap_, master, min_i, min_j, max_i, max_j,
            [](uint8_t* m, const uint8_t* o, std::size_t n)
            {
              for (std::size_t k = 0; k < n; ++k)
              {
                const unsigned own = o[k], old = m[k];
                const unsigned sum = std::min(old + own, static_cast<unsigned>(MAX_NON_OBSTACLE));
                const unsigned merged = old == NO_INFORMATION ? own : sum;
                m[k] = static_cast<uint8_t>(own == NO_INFORMATION ? old : merged);
              }
            });
}

void CostmapLayer::updateWithMaxWithoutUnknownOverwrite(Costmap2D& master, int min_i, int min_j, int max_i,
                                                        int max_j) const
{
  mergeRows(costmap_, master, min_i, min_j, max_i, max_j,
            [](uint8_t* m, const uint8_t* o, std::size_t n)
            {
              for (std::size_t k = 0; k < n; ++k)
              {
                const uint8_t own = o[k], old = m[k];
                const bool take = own != NO_INFORMATION && old != NO_INFORMATION && old < own;
                m[k] = take ? own : old;
              }
            });
}
}  // namespace costmap_layers
