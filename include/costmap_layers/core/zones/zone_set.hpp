// The zones' editing model: a layout that changes only by checked steps (what zone_server edits).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "costmap_layers/core/data/grid_data.hpp"
#include "costmap_layers/core/zones/zone_layout.hpp"

namespace costmap_layers
{
/// A layout that changes only by checked steps: every change is validated (the shape it changes, and
/// the layout as a whole: names, extent, work) and applied only when valid, so the last good layout
/// always stays in force. The shapes it holds are valid, so an edit checks only the one it changes.
class ZoneSet
{
public:
  /// Throws std::invalid_argument when layout is not valid.
  explicit ZoneSet(ZoneLayout layout);

  const ZoneLayout& layout() const { return layout_; }
  /// The shape of that name, or nullptr.
  const ZoneShape* find(const std::string& name) const;

  /// Adds the shape, or replaces the one of the same name in its place. @return the error, or ok()
  InputError upsert(const ZoneShape& shape);
  /// Removes the shape of that name (an error when there is none).
  InputError remove(const std::string& name);
  /// Moves one handle of a shape to (x, y): polygon vertex `index` (0-based); for a circle, handle 0
  /// moves the centre (keeping the radius) and handle 1 sets the radius to the distance from the
  /// centre. @return the error (unknown shape or handle, or the shape it would make is invalid)
  InputError moveHandle(const std::string& name, std::size_t index, double x, double y);
  /// Replaces the whole layout (a reload). @return the error, or ok()
  InputError replace(const ZoneLayout& layout);
  /// The mask of the layout (rasterizeZones() without checking it again).
  OccupancyGridData rasterize() const;

private:
  /// @param shapes_valid  every shape of next has been validated (only the layout-wide checks run)
  InputError commit(ZoneLayout next, bool shapes_valid);
  ZoneLayout layout_;
};

/// The handle positions of a shape, in the order moveHandle() numbers them: a polygon's vertices; a
/// circle's centre, then the point at radius along +x from the centre.
std::vector<ZonePoint> zoneHandles(const ZoneShape& shape);

/// Where a shape's name goes: a polygon's area centroid (inside a convex one, either winding), a
/// circle's centre. Summed relative to the first vertex, so shapes far from the origin lose no precision;
/// a polygon of zero area (never a valid one) gives its vertices' mean.
ZonePoint zoneCentroid(const ZoneShape& shape);
}  // namespace costmap_layers
