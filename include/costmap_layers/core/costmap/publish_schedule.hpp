// What the costmap node publishes and when: the window changed since the last publish, kept valid for
// the grid it describes across resizes, and a publish clock on the intended period. No ROS: the node
// feeds it the grid after each cycle and the time, and sends what it answers.
#pragma once

#include <cstdint>

#include "costmap_layers/core/grid/costmap_2d.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"

namespace costmap_layers
{
/// The cells window clipped to a grid of sx x sy cells (empty when they do not meet). Overflow-free
/// for any int window, including one inverted or far outside.
CellWindow clipWindow(const CellWindow& window, unsigned int sx, unsigned int sy);

/// Size, origin and resolution of a grid: a change of any of them invalidates every cell window.
struct GridGeometry
{
  unsigned int size_x = 0, size_y = 0;
  double origin_x = 0, origin_y = 0, resolution = 0;
  static GridGeometry of(const Costmap2D& grid);
  bool operator==(const GridGeometry& o) const;
  bool operator!=(const GridGeometry& o) const { return !(*this == o); }
};

/// What to send at a publish: the whole grid, a window of it (never past the grid), or nothing.
struct PublishDecision
{
  bool full = false;
  CellWindow window;  ///< when !full: the changed cells, inside the grid (empty: nothing to send)
};

class PublishSchedule
{
public:
  /// @param publish_frequency  [Hz] > 0, or 0 for never
  /// @param always_full        send the whole grid at every publish (costmap_2d's always_send_full_costmap)
  PublishSchedule(double publish_frequency, bool always_full);

  /// After each update cycle: the grid as it is now and the window that cycle changed. A change of the
  /// grid's geometry since the last cycle drops the pending window (its cells no longer exist or mean
  /// other places) and makes the next publish a full one.
  void noteCycle(const Costmap2D& grid, const CellWindow& changed);
  /// True when a publish is due at now_s [s, any monotonic clock]. Publishes fall on the intended
  /// period (start + k / frequency), so F Hz gives F publishes a second; after a stall longer than a
  /// period the schedule restarts from now instead of bursting to catch up.
  bool due(double now_s);
  /// What to send now for the grid as it is; resets the pending window. new_subscriber asks for a full one.
  PublishDecision take(const Costmap2D& grid, bool new_subscriber);

private:
  double period_s_;
  bool always_full_;
  bool started_ = false;
  double next_s_ = 0.0;
  bool full_needed_ = true;  ///< nothing published yet, or the geometry changed
  bool have_geometry_ = false;
  GridGeometry geometry_;   ///< of the grid at the last cycle
  GridGeometry published_;  ///< of the grid at the last full publish
  CellWindow pending_;
};
}  // namespace costmap_layers
