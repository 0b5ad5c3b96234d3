#include "costmap_layers/core/grid/costmap_2d.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace costmap_layers
{
Costmap2D::Costmap2D(unsigned int size_x, unsigned int size_y, double resolution, double origin_x, double origin_y,
                     uint8_t default_value)
    : default_value_(default_value)
{
  resizeMap(size_x, size_y, resolution, origin_x, origin_y);
}

Costmap2D::Costmap2D(const Costmap2D& other)
    : size_x_(other.size_x_),
      size_y_(other.size_y_),
      resolution_(other.resolution_),
      origin_x_(other.origin_x_),
      origin_y_(other.origin_y_),
      default_value_(other.default_value_),
      owned_(other.cells_, other.cells_ + other.count_),
      cells_(owned_.data()),
      count_(other.count_)
{
}

void Costmap2D::copyGeometry(const Costmap2D& other)
{
  size_x_ = other.size_x_;
  size_y_ = other.size_y_;
  resolution_ = other.resolution_;
  origin_x_ = other.origin_x_;
  origin_y_ = other.origin_y_;
  default_value_ = other.default_value_;
}

Costmap2D& Costmap2D::operator=(const Costmap2D& other)
{
  if (this == &other) return *this;
  copyGeometry(other);
  owned_.assign(other.cells_, other.cells_ + other.count_);
  cells_ = owned_.data();
  count_ = other.count_;
  view_ = false;
  return *this;
}

Costmap2D::Costmap2D(Costmap2D&& other) noexcept
{
  *this = std::move(other);
}

Costmap2D& Costmap2D::operator=(Costmap2D&& other) noexcept
{
  if (this == &other) return *this;
  copyGeometry(other);
  view_ = other.view_;
  count_ = other.count_;
  owned_ = std::move(other.owned_);
  cells_ = view_ ? other.cells_ : owned_.data();
  other.owned_.clear();
  other.cells_ = nullptr;
  other.count_ = 0;
  other.size_x_ = other.size_y_ = 0;
  other.view_ = false;
  return *this;
}

void Costmap2D::viewMemory(uint8_t* cells, unsigned int size_x, unsigned int size_y, double resolution, double origin_x,
                           double origin_y)
{
  size_x_ = size_x;
  size_y_ = size_y;
  resolution_ = resolution;
  origin_x_ = origin_x;
  origin_y_ = origin_y;
  owned_.clear();
  owned_.shrink_to_fit();
  cells_ = cells;
  count_ = static_cast<std::size_t>(size_x) * size_y;
  view_ = true;
}

bool Costmap2D::worldToMap(double wx, double wy, unsigned int& mx, unsigned int& my) const
{
  if (!(wx >= origin_x_) || !(wy >= origin_y_)) return false;  // also false for NaN
  const double fx = (wx - origin_x_) / resolution_;
  const double fy = (wy - origin_y_) / resolution_;
  if (!(fx < size_x_) || !(fy < size_y_)) return false;
  mx = static_cast<unsigned int>(fx);
  my = static_cast<unsigned int>(fy);
  return mx < size_x_ && my < size_y_;
}

void Costmap2D::worldToMapNoBounds(double wx, double wy, int& mx, int& my) const
{
  mx = static_cast<int>((wx - origin_x_) / resolution_);
  my = static_cast<int>((wy - origin_y_) / resolution_);
}

namespace
{
int clampedCell(double w, double origin, double resolution, unsigned int size)
{
  if (size == 0) return 0;
  if (!(w >= origin)) return 0;  // NaN goes to the low edge rather than to undefined behaviour
  const double f = (w - origin) / resolution;
  if (f >= size) return static_cast<int>(size) - 1;
  return static_cast<int>(f);
}
}  // namespace

void Costmap2D::worldToMapEnforceBounds(double wx, double wy, int& mx, int& my) const
{
  mx = clampedCell(wx, origin_x_, resolution_, size_x_);
  my = clampedCell(wy, origin_y_, resolution_, size_y_);
}

unsigned int Costmap2D::cellDistance(double world_dist) const
{
  const double cells = std::ceil(world_dist / resolution_);
  if (!(cells > 0.0)) return 0;                   // also NaN
  if (cells >= 4294967295.0) return 0xFFFFFFFFu;  // saturates: a double -> unsigned overflow is undefined
  return static_cast<unsigned int>(cells);
}

void Costmap2D::resizeMap(unsigned int size_x, unsigned int size_y, double resolution, double origin_x, double origin_y)
{
  size_x_ = size_x;
  size_y_ = size_y;
  resolution_ = resolution;
  origin_x_ = origin_x;
  origin_y_ = origin_y;
  count_ = static_cast<std::size_t>(size_x) * size_y;
  owned_.assign(count_, default_value_);
  cells_ = owned_.data();
  view_ = false;
}

void Costmap2D::resetMaps()
{
  std::fill(cells_, cells_ + count_, default_value_);
}

void Costmap2D::resetMap(unsigned int x0, unsigned int y0, unsigned int xn, unsigned int yn)
{
  fillWindow(x0, y0, xn, yn, default_value_);
}

void Costmap2D::fillWindow(unsigned int x0, unsigned int y0, unsigned int xn, unsigned int yn, uint8_t value)
{
  xn = std::min(xn, size_x_);
  yn = std::min(yn, size_y_);
  if (x0 >= xn || y0 >= yn) return;
  for (unsigned int y = y0; y < yn; ++y)
  {
    uint8_t* row = cells_ + static_cast<std::size_t>(y) * size_x_;
    std::memset(row + x0, value, xn - x0);
  }
}

bool Costmap2D::copyWindow(const Costmap2D& source, unsigned int sx0, unsigned int sy0, unsigned int sxn,
                           unsigned int syn, unsigned int dx0, unsigned int dy0)
{
  if (sxn > source.size_x_ || syn > source.size_y_ || sx0 > sxn || sy0 > syn) return false;
  const unsigned int w = sxn - sx0;
  const unsigned int h = syn - sy0;
  if (dx0 + w > size_x_ || dy0 + h > size_y_) return false;
  if (w == 0) return true;
  for (unsigned int k = 0; k < h; ++k)
  {
    const uint8_t* from = source.cells_ + static_cast<std::size_t>(sy0 + k) * source.size_x_ + sx0;
    uint8_t* to = cells_ + static_cast<std::size_t>(dy0 + k) * size_x_ + dx0;
    std::memmove(to, from, w);
  }
  return true;
}

void Costmap2D::updateOrigin(double new_origin_x, double new_origin_y)
{
  // Snap the new origin to the current cell lattice so that kept cells stay aligned.
  const double shift_x = std::floor((new_origin_x - origin_x_) / resolution_);
  const double shift_y = std::floor((new_origin_y - origin_y_) / resolution_);
  // A non-finite pose moves nothing. A shift of a whole grid or more keeps no cell: it is clamped for
  // the int arithmetic below (a far-away pose would overflow int), the origin takes the exact shift.
  if (!std::isfinite(shift_x) || !std::isfinite(shift_y)) return;
  const int cell_ox = clampCellShift(shift_x, size_x_);
  const int cell_oy = clampCellShift(shift_y, size_y_);
  if (cell_ox == 0 && cell_oy == 0) return;
  shiftCells(cell_ox, cell_oy);
  origin_x_ += shift_x * resolution_;
  origin_y_ += shift_y * resolution_;
}

std::pair<int, int> Costmap2D::followOrigin(double lattice_origin_x, double lattice_origin_y)
{
  // Both origins lie on one lattice up to rounding, so the shift is rounded, never floored: a floor
  // of -0.9999999 would put every kept cell one cell off the grid followed.
  const double shift_x = std::round((lattice_origin_x - origin_x_) / resolution_);
  const double shift_y = std::round((lattice_origin_y - origin_y_) / resolution_);
  if (!std::isfinite(shift_x) || !std::isfinite(shift_y)) return {0, 0};
  const int cell_ox = clampCellShift(shift_x, size_x_);
  const int cell_oy = clampCellShift(shift_y, size_y_);
  if (cell_ox != 0 || cell_oy != 0) shiftCells(cell_ox, cell_oy);
  origin_x_ = lattice_origin_x;
  origin_y_ = lattice_origin_y;
  return {cell_ox, cell_oy};
}

void Costmap2D::shiftCells(int cell_ox, int cell_oy)
{
  const int size_x = static_cast<int>(size_x_);
  const int size_y = static_cast<int>(size_y_);
  // Overlap of the old and new windows, in old cells.
  const int lower_left_x = std::min(std::max(cell_ox, 0), size_x);
  const int lower_left_y = std::min(std::max(cell_oy, 0), size_y);
  const int upper_right_x = std::min(std::max(cell_ox + size_x, 0), size_x);
  const int upper_right_y = std::min(std::max(cell_oy + size_y, 0), size_y);
  const int overlap_x = upper_right_x - lower_left_x;
  const int overlap_y = upper_right_y - lower_left_y;

  std::vector<uint8_t> next(count_, default_value_);
  if (overlap_x > 0 && overlap_y > 0)
  {
    const int start_x = lower_left_x - cell_ox;
    const int start_y = lower_left_y - cell_oy;
    for (int k = 0; k < overlap_y; ++k)
    {
      std::memcpy(next.data() + static_cast<std::size_t>(start_y + k) * size_x_ + start_x,
                  cells_ + static_cast<std::size_t>(lower_left_y + k) * size_x_ + lower_left_x,
                  static_cast<std::size_t>(overlap_x));
    }
  }
  if (view_)
  {
    if (count_ > 0) std::memcpy(cells_, next.data(), count_);
  }
  else
  {
    owned_.swap(next);
    cells_ = owned_.data();
  }
}

void Costmap2D::polygonOutlineCells(const std::vector<MapLocation>& polygon, std::vector<MapLocation>& cells) const
{
  if (polygon.empty()) return;
  auto add = [&cells](int x, int y) { cells.push_back({static_cast<unsigned int>(x), static_cast<unsigned int>(y)}); };
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const MapLocation& a = polygon[i];
    const MapLocation& b = polygon[(i + 1) % polygon.size()];
    walkLine(add, static_cast<int>(a.x), static_cast<int>(a.y), static_cast<int>(b.x), static_cast<int>(b.y));
  }
}

void Costmap2D::convexFillCells(const std::vector<MapLocation>& polygon, std::vector<MapLocation>& cells) const
{
  if (polygon.size() < 3)
  {
    polygonOutlineCells(polygon, cells);
    return;
  }
  std::vector<MapLocation> outline;
  polygonOutlineCells(polygon, outline);
  unsigned int min_x = std::numeric_limits<unsigned int>::max(), max_x = 0;
  for (const auto& c : outline)
  {
    min_x = std::min(min_x, c.x);
    max_x = std::max(max_x, c.x);
  }
  // Per column, the lowest and highest outline cell bound the filled span (the polygon is convex).
  std::vector<unsigned int> lo(max_x - min_x + 1, std::numeric_limits<unsigned int>::max());
  std::vector<unsigned int> hi(max_x - min_x + 1, 0);
  for (const auto& c : outline)
  {
    lo[c.x - min_x] = std::min(lo[c.x - min_x], c.y);
    hi[c.x - min_x] = std::max(hi[c.x - min_x], c.y);
  }
  for (unsigned int x = min_x; x <= max_x; ++x)
  {
    for (unsigned int y = lo[x - min_x]; y <= hi[x - min_x]; ++y)
      cells.push_back({x, y});
  }
}

bool Costmap2D::setConvexPolygonCost(const std::vector<Eigen::Vector2d>& polygon, uint8_t cost)
{
  std::vector<MapLocation> map_polygon;
  map_polygon.reserve(polygon.size());
  for (const auto& p : polygon)
  {
    MapLocation loc;
    if (!worldToMap(p.x(), p.y(), loc.x, loc.y)) return false;
    map_polygon.push_back(loc);
  }
  std::vector<MapLocation> cells;
  convexFillCells(map_polygon, cells);
  for (const auto& c : cells)
    setCost(c.x, c.y, cost);
  return true;
}
}  // namespace costmap_layers
