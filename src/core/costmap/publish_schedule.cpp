#include "costmap_layers/core/costmap/publish_schedule.hpp"

#include <algorithm>
#include <cmath>

namespace costmap_layers
{
CellWindow clipWindow(const CellWindow& w, unsigned int sx, unsigned int sy)
{
  // In 64 bits: an int window and an unsigned size cannot overflow there.
  const int64_t x0 = std::max<int64_t>(w.x0, 0), y0 = std::max<int64_t>(w.y0, 0);
  const int64_t xn = std::min<int64_t>(w.xn, sx), yn = std::min<int64_t>(w.yn, sy);
  if (xn <= x0 || yn <= y0) return CellWindow{};
  return CellWindow{static_cast<int>(x0), static_cast<int>(y0), static_cast<int>(xn), static_cast<int>(yn)};
}

GridGeometry GridGeometry::of(const Costmap2D& grid)
{
  return GridGeometry{grid.getSizeInCellsX(), grid.getSizeInCellsY(), grid.getOriginX(), grid.getOriginY(),
                      grid.getResolution()};
}

bool GridGeometry::operator==(const GridGeometry& o) const
{
  return size_x == o.size_x && size_y == o.size_y && origin_x == o.origin_x && origin_y == o.origin_y &&
         resolution == o.resolution;
}

PublishSchedule::PublishSchedule(double publish_frequency, bool always_full)
    : period_s_(publish_frequency > 0.0 && std::isfinite(publish_frequency) ? 1.0 / publish_frequency : 0.0),
      always_full_(always_full)
{
}

void PublishSchedule::noteCycle(const Costmap2D& grid, const CellWindow& changed)
{
  const GridGeometry now = GridGeometry::of(grid);
  if (!have_geometry_ || now != geometry_)
  {
    pending_ = CellWindow{};
    full_needed_ = true;
  }
  geometry_ = now;
  have_geometry_ = true;
  const CellWindow w = clipWindow(changed, now.size_x, now.size_y);
  if (w.empty()) return;
  if (pending_.empty())
    pending_ = w;
  else
    pending_ = CellWindow{std::min(pending_.x0, w.x0), std::min(pending_.y0, w.y0), std::max(pending_.xn, w.xn),
                          std::max(pending_.yn, w.yn)};
}

bool PublishSchedule::due(double now_s)
{
  if (period_s_ <= 0.0 || !std::isfinite(now_s)) return false;
  if (!started_)
  {
    started_ = true;
    next_s_ = now_s + period_s_;
    return true;
  }
  if (now_s < next_s_ - period_s_)
  {
    // The clock went back by more than a period: restart the schedule from now.
    next_s_ = now_s + period_s_;
    return true;
  }
  if (now_s < next_s_) return false;
  next_s_ += period_s_;
  if (next_s_ <= now_s) next_s_ = now_s + period_s_;  // more than a period late: no burst
  return true;
}

PublishDecision PublishSchedule::take(const Costmap2D& grid, bool new_subscriber)
{
  PublishDecision d;
  const GridGeometry now = GridGeometry::of(grid);
  d.full = full_needed_ || always_full_ || new_subscriber || now != published_;
  if (d.full)
  {
    published_ = now;
    full_needed_ = false;
  }
  else
  {
    d.window = clipWindow(pending_, now.size_x, now.size_y);
  }
  pending_ = CellWindow{};
  return d;
}
}  // namespace costmap_layers
