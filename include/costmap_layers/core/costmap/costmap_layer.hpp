// A layer that keeps its own grid and merges it into the master grid with one of costmap_2d's
// merge rules. Each merge works row by row on the window only, with no per-cell calls.
#pragma once

#include "costmap_layers/core/grid/costmap_2d.hpp"
#include "costmap_layers/core/costmap/layer.hpp"

namespace costmap_layers
{
class CostmapLayer : public Layer
{
public:
  /// Resizes the own grid to the master grid's size, resolution and origin.
  void matchSize() override;
  const Costmap2D& costmap() const { return costmap_; }
  Costmap2D& costmap() { return costmap_; }

  /// Sets the cells [x0, xn) x [y0, yn) of the own grid to value: NO_INFORMATION to forget them (a
  /// "clear costmaps" request: the master then keeps what the layers below give there), the grid's
  /// default value to reset them. A layer with more state per cell (the voxel layer's columns) clears
  /// that too. The window is cut to the grid.
  virtual void clearCells(unsigned int x0, unsigned int y0, unsigned int xn, unsigned int yn, uint8_t value)
  {
    costmap_.fillWindow(x0, y0, xn, yn, value);
  }

  /// Asks for [mx0, mx1] x [my0, my1] [m] to be included in the next bounds (e.g. after a map update).
  void addExtraBounds(double mx0, double my0, double mx1, double my1);

  /// Per cell: an unknown own cell changes nothing; otherwise the master takes the own cost when the
  /// master is unknown or lower.
  void updateWithMax(Costmap2D& master, int min_i, int min_j, int max_i, int max_j) const;
  /// Per cell: copies the own cost, unknown included.
  void updateWithTrueOverwrite(Costmap2D& master, int min_i, int min_j, int max_i, int max_j) const;
  /// Per cell: copies the own cost unless it is unknown.
  void updateWithOverwrite(Costmap2D& master, int min_i, int min_j, int max_i, int max_j) const;
  /// Per cell: an unknown own cell changes nothing; an unknown master takes the own cost; otherwise the
  /// sum, clamped to MAX_NON_OBSTACLE (252).
  void updateWithAddition(Costmap2D& master, int min_i, int min_j, int max_i, int max_j) const;
  /// Per cell: like updateWithMax, but unknown master cells stay unknown.
  void updateWithMaxWithoutUnknownOverwrite(Costmap2D& master, int min_i, int min_j, int max_i, int max_j) const;

protected:
  /// Grows the bounds to include the point (x, y) [m].
  static void touch(double x, double y, double* min_x, double* min_y, double* max_x, double* max_y);
  /// Adds the extra bounds requested with addExtraBounds() and forgets them.
  void useExtraBounds(double* min_x, double* min_y, double* max_x, double* max_y);
  /// In a rolling costmap, moves the own grid onto the master's origin, cell for cell (call it in
  /// updateBounds: the master has moved already, by LayeredCostmap::updateMap, or under move_base by
  /// costmap_2d, which truncates the shift where this package floors it). Returns the shift in cells.
  std::pair<int, int> followRollingMaster();

  Costmap2D costmap_;

private:
  bool has_extra_bounds_ = false;
  double extra_min_x_ = 0, extra_min_y_ = 0, extra_max_x_ = 0, extra_max_y_ = 0;
};
}  // namespace costmap_layers
