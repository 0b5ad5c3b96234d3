// "Clear costmaps": what move_base's recovery and the node's ~clear services do to clearable layers
// (the sensor layers; static layers and filters are not clearable).
#pragma once

namespace costmap_layers
{
class LayeredCostmap;

/// Resets every clearable plugin. @return how many were reset.
int resetClearableLayers(LayeredCostmap& costmap);

/// In every clearable plugin that keeps its own grid, sets the cells outside the square of side
/// keep_size [m] centred on (x, y) to the grid's default value, and asks for a redraw of the whole
/// map; other clearable plugins are reset. A cell is kept when it meets the closed square (its upper
/// edges excluded). The robot may be anywhere, also off the grid (then the square may keep part of the
/// grid or nothing); keep_size may be 0 (the robot's cell) or +inf (everything).
/// @return how many plugins were cleared, or -1 (and nothing is touched) when x or y is not finite or
/// keep_size is NaN or negative.
int clearClearableLayersAround(LayeredCostmap& costmap, double x, double y, double keep_size);
}  // namespace costmap_layers
