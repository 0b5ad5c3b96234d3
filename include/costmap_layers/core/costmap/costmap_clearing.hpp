// "Clear costmaps": what move_base's recovery and the node's ~clear services do to clearable layers
// (the sensor layers; static layers and filters are not clearable).
#pragma once

#include <string>
#include <vector>

namespace costmap_layers
{
class Layer;
class LayeredCostmap;

/// Which part of the square a square clear clears: Nav2's clear_except_region keeps the square (and
/// clears the rest), its clear_around_pose clears the square (and keeps the rest).
enum class SquareClear
{
  KeepSquare,
  ClearSquare
};

/// What is wrong with the plugins list of one of Nav2's clearing services (their `plugins` field):
/// each name that is not a configured plugin or names a plugin that is not clearable (a static layer,
/// an inflation layer, a filter), as Nav2's ClearCostmapService::validatePlugins lists them; the first
/// few, with their count. Empty when the list is empty or every name is a clearable plugin.
std::string clearPluginsProblem(const LayeredCostmap& costmap, const std::vector<std::string>& plugins);

/// Nav2's clear_except_region (KeepSquare) and clear_around_pose (ClearSquare) on the named plugins, or
/// on every clearable plugin when plugins is empty. The square has side `size` [m], is centred on (x, y)
/// and holds the cells that meet it, its upper edges excluded (the rule of clearClearableLayersAround
/// below, for both modes: what one keeps, the other clears). Cleared cells become NO_INFORMATION in the
/// layer's own grid and the whole map is redrawn; a clearable plugin without a grid of its own is reset
/// (it cannot forget a part). size may be 0 (one cell) or +inf (the whole grid).
/// @return how many plugins were cleared, or -1 with `error` set, touching nothing, when x or y is not
/// finite, size is NaN or negative, or the plugins list names a plugin that is missing or not clearable.
int clearSquare(LayeredCostmap& costmap, double x, double y, double size, SquareClear mode,
                const std::vector<std::string>& plugins, std::string& error);

/// Nav2's clear_entirely. An empty plugins list: every plugin and every filter is reset (as Nav2's
/// Costmap2DROS::resetLayers: sensor layers forget what they saw, the static layer draws its map again)
/// and the whole master grid is rebuilt at the next update. Else only the named plugins, which must be
/// clearable: each grid is set to its default value (Nav2's resetMap), then the master is rebuilt.
/// @return how many layers were reset, or -1 with `error` set (nothing touched) for a bad plugins list.
int clearEntirely(LayeredCostmap& costmap, const std::vector<std::string>& plugins, std::string& error);

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
