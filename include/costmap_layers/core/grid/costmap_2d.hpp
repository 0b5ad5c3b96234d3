// The 2-D cost grid: uint8 cells, row-major, row 0 = lowest y, cell (0,0)'s lower-left corner at the
// origin. Coordinates follow costmap_2d: cell centres at origin + (m + 0.5) * resolution, world to
// map by truncation. No ROS here.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace costmap_layers
{
struct MapLocation
{
  unsigned int x = 0;
  unsigned int y = 0;
};

class Costmap2D
{
public:
  Costmap2D() = default;
  /// @param size_x, size_y [cells]; resolution [m/cell]; origin [m]; every cell starts at default_value.
  Costmap2D(unsigned int size_x, unsigned int size_y, double resolution, double origin_x, double origin_y,
            uint8_t default_value = 0);
  /// A copy owns its cells, also when the original is a view (see viewMemory).
  Costmap2D(const Costmap2D& other);
  Costmap2D& operator=(const Costmap2D& other);
  Costmap2D(Costmap2D&& other) noexcept;
  Costmap2D& operator=(Costmap2D&& other) noexcept;

  /// Makes this grid a view of cells it does not own: size_x * size_y bytes, row-major, row 0 = lowest
  /// y, e.g. move_base's costmap_2d master grid (getCharMap()), so that a layer hosted inside move_base
  /// writes into it without a copy. The caller keeps the memory alive while the view is used and calls
  /// this again after the memory moves or changes size. resizeMap makes the grid own its cells again;
  /// updateOrigin shifts the viewed cells in place.
  void viewMemory(uint8_t* cells, unsigned int size_x, unsigned int size_y, double resolution, double origin_x,
                  double origin_y);
  bool isView() const { return view_; }

  unsigned int getSizeInCellsX() const { return size_x_; }
  unsigned int getSizeInCellsY() const { return size_y_; }
  /// Full extent [m] (costmap_2d returns (size - 0.5) * resolution here; this is the true size).
  double getSizeInMetersX() const { return size_x_ * resolution_; }
  double getSizeInMetersY() const { return size_y_ * resolution_; }
  double getResolution() const { return resolution_; }
  double getOriginX() const { return origin_x_; }
  double getOriginY() const { return origin_y_; }
  uint8_t getDefaultValue() const { return default_value_; }
  void setDefaultValue(uint8_t v) { default_value_ = v; }

  unsigned int getIndex(unsigned int mx, unsigned int my) const { return my * size_x_ + mx; }
  void indexToCells(unsigned int index, unsigned int& mx, unsigned int& my) const
  {
    my = index / size_x_;
    mx = index - my * size_x_;
  }
  uint8_t getCost(unsigned int mx, unsigned int my) const { return cells_[getIndex(mx, my)]; }
  uint8_t getCost(unsigned int index) const { return cells_[index]; }
  void setCost(unsigned int mx, unsigned int my, uint8_t cost) { cells_[getIndex(mx, my)] = cost; }

  /// Read-only view of all cells (size_x * size_y, row-major).
  const uint8_t* data() const { return cells_; }
  /// Writable view for layers that fill whole rows; valid until the next resize.
  uint8_t* data() { return cells_; }
  std::size_t cellCount() const { return count_; }

  /// World coordinates of the centre of cell (mx, my).
  void mapToWorld(unsigned int mx, unsigned int my, double& wx, double& wy) const
  {
    wx = origin_x_ + (mx + 0.5) * resolution_;
    wy = origin_y_ + (my + 0.5) * resolution_;
  }
  /// @return false when (wx, wy) lies outside the grid (mx, my are then unspecified).
  bool worldToMap(double wx, double wy, unsigned int& mx, unsigned int& my) const;
  /// Truncating conversion without any bounds check (may give negative or too large indices).
  void worldToMapNoBounds(double wx, double wy, int& mx, int& my) const;
  /// Like worldToMap, but clamps a point outside the grid to the nearest edge cell.
  void worldToMapEnforceBounds(double wx, double wy, int& mx, int& my) const;

  /// A world distance [m] in cells, rounded up; 0 for negative or NaN distances, 2^32 - 1 for huge ones.
  unsigned int cellDistance(double world_dist) const;

  /// Reallocates the grid and fills it with the default value.
  void resizeMap(unsigned int size_x, unsigned int size_y, double resolution, double origin_x, double origin_y);
  /// A whole-cell shift (finite) clamped to [-(size + 1), size + 1]: shifts beyond the grid keep no cell
  /// either way, and the clamped value is safe in int arithmetic (updateOrigin, VoxelLayer).
  static int clampCellShift(double shift, unsigned int size)
  {
    const double lim = static_cast<double>(size) + 1.0;
    return static_cast<int>(shift < -lim ? -lim : (shift > lim ? lim : shift));
  }
  /// Sets every cell to the default value.
  void resetMaps();
  /// Sets the window [x0, xn) x [y0, yn) to the default value (clamped to the grid).
  void resetMap(unsigned int x0, unsigned int y0, unsigned int xn, unsigned int yn);
  /// Sets the window [x0, xn) x [y0, yn) to value (clamped to the grid).
  void fillWindow(unsigned int x0, unsigned int y0, unsigned int xn, unsigned int yn, uint8_t value);

  /// Copies source's window [sx0, sxn) x [sy0, syn) to this grid at (dx0, dy0).
  /// @return false (and copies nothing) when either window does not fit its grid.
  bool copyWindow(const Costmap2D& source, unsigned int sx0, unsigned int sy0, unsigned int sxn, unsigned int syn,
                  unsigned int dx0, unsigned int dy0);

  /// Moves the origin (snapped to whole cells of the current grid), keeping the cells that the old and
  /// new windows share and setting the rest to the default value (for rolling windows).
  void updateOrigin(double new_origin_x, double new_origin_y);
  /// Moves the grid onto the origin of a grid on the same lattice (a rolling layer's own grid following
  /// the master, whichever rule moved the master: costmap_2d truncates, updateOrigin floors). The shift
  /// is rounded to whole cells, the origin becomes exactly the one given. Returns the shift applied in
  /// cells (clamped as clampCellShift; {0, 0} for a non-finite origin, which moves nothing).
  std::pair<int, int> followOrigin(double lattice_origin_x, double lattice_origin_y);

  /// Cells on the outline of a polygon given in map cells (consecutive vertices joined, closed).
  void polygonOutlineCells(const std::vector<MapLocation>& polygon, std::vector<MapLocation>& cells) const;
  /// Cells inside a convex polygon given in map cells, outline included.
  void convexFillCells(const std::vector<MapLocation>& polygon, std::vector<MapLocation>& cells) const;
  /// Sets every cell of a convex polygon given in world coordinates [m] to cost.
  /// @return false when a vertex lies outside the grid (nothing is written then).
  bool setConvexPolygonCost(const std::vector<Eigen::Vector2d>& polygon, uint8_t cost);

  /// Walks the cells of the line (x0,y0)-(x1,y1) with Bresenham's algorithm, calling at(index) on each
  /// cell from the start, skipping the first min_length cells: n = min(major-axis cells, max_length
  /// scaled to the line) steps, then the cell where the walk stopped, so n + 1 cells, the end cell
  /// itself included when max_length does not cut the line (costmap_2d's and Nav2's bresenham2D, whose
  /// last call comes after the loop). Nothing is allocated.
  template <class ActionType>
  void raytraceLine(ActionType&& at, unsigned int x0, unsigned int y0, unsigned int x1, unsigned int y1,
                    unsigned int max_length = 0xFFFFFFFFu, unsigned int min_length = 0) const;

  /// Calls at(x, y) on every cell of the line (x0,y0)-(x1,y1), both ends included.
  template <class ActionType>
  static void walkLine(ActionType&& at, int x0, int y0, int x1, int y1);

private:
  /// Size, resolution, origin and default value of other (not the cells).
  void copyGeometry(const Costmap2D& other);
  /// Moves the cells by a whole-cell shift of the origin (clamped), the new ones at the default value;
  /// the origin itself is the caller's.
  void shiftCells(int cell_ox, int cell_oy);
  template <class ActionType>
  static void bresenham(ActionType& at, unsigned int abs_da, unsigned int abs_db, int error_b, int offset_a,
                        int offset_b, unsigned int offset, unsigned int max_length);

  unsigned int size_x_ = 0;
  unsigned int size_y_ = 0;
  double resolution_ = 1.0;
  double origin_x_ = 0.0;
  double origin_y_ = 0.0;
  uint8_t default_value_ = 0;
  std::vector<uint8_t> owned_;  ///< the cells when the grid owns them
  uint8_t* cells_ = nullptr;    ///< owned_.data(), or the viewed memory
  std::size_t count_ = 0;
  bool view_ = false;
};

template <class ActionType>
void Costmap2D::bresenham(ActionType& at, unsigned int abs_da, unsigned int abs_db, int error_b, int offset_a,
                          int offset_b, unsigned int offset, unsigned int max_length)
{
  const unsigned int end = abs_da < max_length ? abs_da : max_length;
  for (unsigned int i = 0; i < end; ++i)
  {
    at(offset);
    offset += offset_a;
    error_b += abs_db;
    if (static_cast<unsigned int>(error_b) >= abs_da)
    {
      offset += offset_b;
      error_b -= abs_da;
    }
  }
  at(offset);
}

template <class ActionType>
void Costmap2D::raytraceLine(ActionType&& at, unsigned int x0, unsigned int y0, unsigned int x1, unsigned int y1,
                             unsigned int max_length, unsigned int min_length) const
{
  int dx_full = static_cast<int>(x1) - static_cast<int>(x0);
  int dy_full = static_cast<int>(y1) - static_cast<int>(y0);
  const double dist = std::hypot(static_cast<double>(dx_full), static_cast<double>(dy_full));
  if (dist < min_length) return;

  // Start min_length cells along the ray.
  unsigned int min_x0 = x0, min_y0 = y0;
  if (dist > 0.0)
  {
    min_x0 = static_cast<unsigned int>(static_cast<int>(x0) + dx_full / dist * min_length);
    min_y0 = static_cast<unsigned int>(static_cast<int>(y0) + dy_full / dist * min_length);
  }
  const int dx = static_cast<int>(x1) - static_cast<int>(min_x0);
  const int dy = static_cast<int>(y1) - static_cast<int>(min_y0);
  const unsigned int abs_dx = static_cast<unsigned int>(std::abs(dx));
  const unsigned int abs_dy = static_cast<unsigned int>(std::abs(dy));
  const int offset_dx = dx > 0 ? 1 : -1;
  const int offset_dy = (dy > 0 ? 1 : -1) * static_cast<int>(size_x_);
  const unsigned int offset = min_y0 * size_x_ + min_x0;

  // Scale max_length so that the walk along the major axis stops at the right Euclidean distance.
  const double scale = dist == 0.0 ? 1.0 : std::min(1.0, max_length / dist);
  unsigned int length;
  if (abs_dx >= abs_dy)
  {
    length = static_cast<unsigned int>(scale * abs_dx);
    bresenham(at, abs_dx, abs_dy, static_cast<int>(abs_dx / 2), offset_dx, offset_dy, offset, length);
  }
  else
  {
    length = static_cast<unsigned int>(scale * abs_dy);
    bresenham(at, abs_dy, abs_dx, static_cast<int>(abs_dy / 2), offset_dy, offset_dx, offset, length);
  }
}

template <class ActionType>
void Costmap2D::walkLine(ActionType&& at, int x0, int y0, int x1, int y1)
{
  const int dx = std::abs(x1 - x0), sx = x0 < x1 ? 1 : -1;
  const int dy = -std::abs(y1 - y0), sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  while (true)
  {
    at(x0, y0);
    if (x0 == x1 && y0 == y1) break;
    const int e2 = 2 * err;
    if (e2 >= dy)
    {
      err += dy;
      x0 += sx;
    }
    if (e2 <= dx)
    {
      err += dx;
      y0 += sy;
    }
  }
}
}  // namespace costmap_layers
