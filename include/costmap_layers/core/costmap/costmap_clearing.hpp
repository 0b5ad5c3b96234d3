// "Clear costmaps": what move_base's recovery and the node's ~clear services do to clearable layers
// (the sensor layers; static layers and filters are not clearable).
#pragma once

namespace costmap_layers
{
class Layer;
class LayeredCostmap;

/// Resets every clearable plugin. @return how many were reset.
int resetClearableLayers(LayeredCostmap& costmap);

/// In every clearable plugin that keeps its own grid, sets the cells outside the square of side
/// keep_size [m] centred on (x, y) to NO_INFORMATION (the layer forgets them, as costmap_2d's
/// clear-costmap recovery makes it: the master keeps what the layers below give there), and asks for a redraw of the
/// whole map; other clearable plugins are reset. A cell is kept when it meets the closed square (its upper edges
/// excluded). The robot may be anywhere, also off the grid (then the square may keep part of the grid or nothing);
/// keep_size may be 0 (the robot's cell) or +inf (everything).
/// @return how many plugins were cleared, or -1 (and nothing is touched) when x or y is not finite or
/// keep_size is NaN or negative.
int clearClearableLayersAround(LayeredCostmap& costmap, double x, double y, double keep_size);

/// costmap_2d's CostmapLayer::clearArea on one clearable layer (what move_base's clear-costmap recovery
/// asks of the layers it clears): in the layer's own grid, the cells strictly between (x0, y0) and
/// (x1, y1) (both ends excluded) are kept and every other cell is set to NO_INFORMATION; with
/// invert, the cells between are cleared and the others kept. Then a redraw of the whole map is asked
/// for. The indices may be anything an int holds (off the grid, reversed: then nothing is between). A
/// clearable layer without its own grid is reset.
/// @return false, touching nothing, when the layer is not clearable (a static layer, a filter).
bool clearLayerArea(Layer& layer, int x0, int y0, int x1, int y1, bool invert);

/// Sets every cell of the layer's own grid to the grid's default value (costmap_2d's
/// Costmap2D::resetMaps; a voxel layer's columns too) and asks for a redraw of the whole map.
/// @return false, touching nothing, when the layer keeps no grid of its own.
bool resetLayerCells(Layer& layer);
}  // namespace costmap_layers
