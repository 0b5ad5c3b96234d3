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
/// map; other clearable plugins are reset. @return how many plugins were cleared.
int clearClearableLayersAround(LayeredCostmap& costmap, double x, double y, double keep_size);
}  // namespace costmap_layers
