// The zones' rasteriser: a layout drawn into an occupancy-grid mask (the rules: zone_shapes.hpp).
#pragma once

#include <vector>

#include "costmap_layers/core/data/grid_data.hpp"
#include "costmap_layers/core/zones/zone_layout.hpp"

namespace costmap_layers
{
/// The mask of a valid layout (frame_id, resolution, extent, values). Throws std::invalid_argument for
/// an invalid one (validateLayout()'s message).
OccupancyGridData rasterizeZones(const ZoneLayout& layout);

/// rasterizeZones() of a layout known to be valid, without checking it again (ZoneSet::rasterize()).
OccupancyGridData rasterizeValidLayout(const ZoneLayout& layout);

/// Whether a point is inside a polygon by the half-open crossing rule (zone_shapes.hpp; the rule itself:
/// grid/polygon.hpp, the crossing interpolated from each edge's first vertex).
bool pointInZonePolygon(const std::vector<ZonePoint>& polygon, double x, double y);

}  // namespace costmap_layers
