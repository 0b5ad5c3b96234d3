// The master grid and its ordered layers. updateMap() asks every enabled layer for its bounds, then
// lets each write into the accumulated window, in the configured order. Filters (an optional second
// list) run after all plugins on a combined copy, so their output is never fed back into the plugins'
// grid on the next cycle.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "costmap_layers/core/grid/costmap_2d.hpp"
#include "costmap_layers/core/grid/footprint.hpp"

namespace costmap_layers
{
class Layer;

/// A window of cells [x0, xn) x [y0, yn).
struct CellWindow
{
  int x0 = 0, y0 = 0, xn = 0, yn = 0;
  bool empty() const { return xn <= x0 || yn <= y0; }
};

class LayeredCostmap
{
public:
  /// @param track_unknown  when true, cells start (and are reset to) NO_INFORMATION, else FREE_SPACE.
  LayeredCostmap(std::string global_frame, bool rolling_window, bool track_unknown);
  ~LayeredCostmap();
  LayeredCostmap(const LayeredCostmap&) = delete;
  LayeredCostmap& operator=(const LayeredCostmap&) = delete;

  /// Layers run in the order they were added.
  void addPlugin(std::shared_ptr<Layer> plugin);
  /// Filters run after all plugins, on the combined copy.
  void addFilter(std::shared_ptr<Layer> filter);
  const std::vector<std::shared_ptr<Layer>>& getPlugins() const { return plugins_; }
  const std::vector<std::shared_ptr<Layer>>& getFilters() const { return filters_; }
  /// The plugin or filter with that name, or a layer one of them holds (Layer::heldLayers(), named
  /// "<container>/<plugin>"), or nullptr.
  std::shared_ptr<Layer> findLayer(const std::string& name) const;
  /// The layers the plugins and filters hold, and those these hold, depth first: the host wires their
  /// ports, reconfiguration and diagnostics as its plugins'.
  std::vector<std::shared_ptr<Layer>> nestedLayers() const;

  /// One update cycle at the robot pose (global frame) [m, rad].
  void updateMap(double robot_x, double robot_y, double robot_yaw);

  /// Resizes the grids and tells every layer (matchSize). With size_locked, StaticLayer-like layers
  /// must not resize the map.
  void resizeMap(unsigned int size_x, unsigned int size_y, double resolution, double origin_x, double origin_y,
                 bool size_locked = false);

  /// The result: the master grid after plugins and filters (as in Nav2, the combined copy when there
  /// are filters). Both grids always share size, resolution and origin.
  /// A host that owns the master grid elsewhere (move_base's costmap_2d, see ros/move_base_bridge.hpp):
  /// the master becomes a view of its cells (Costmap2D::viewMemory). Every layer's matchSize runs when
  /// the size, the resolution or (not rolling) the origin differ from the previous geometry, as after
  /// resizeMap. Only for a costmap without filters (a host runs filters as plugins).
  void viewMaster(uint8_t* cells, unsigned int size_x, unsigned int size_y, double resolution, double origin_x,
                  double origin_y);
  /// Where resizeMap goes when the master is a view: the host resizes its own grid and calls viewMaster.
  using ResizeHandler = std::function<void(unsigned int size_x, unsigned int size_y, double resolution, double origin_x,
                                           double origin_y, bool size_locked)>;
  void setResizeHandler(ResizeHandler handler) { resize_handler_ = std::move(handler); }

  const Costmap2D& getCostmap() const { return filters_.empty() ? primary_ : combined_; }
  Costmap2D& getCostmap() { return filters_.empty() ? primary_ : combined_; }

  /// Makes the next updateMap() cover the whole grid (after a run-time parameter change, say).
  void requestFullUpdate() { full_update_ = true; }
  /// Whether a full update was asked for since the last call (for a host that runs the cycle itself).
  bool takeFullUpdateRequest()
  {
    const bool asked = full_update_;
    full_update_ = false;
    return asked;
  }

  /// The window the last updateMap() changed (empty before the first update).
  CellWindow getUpdatedBounds() const { return updated_; }

  const std::string& getGlobalFrameID() const { return global_frame_; }
  bool isRolling() const { return rolling_window_; }
  bool isTrackingUnknown() const { return track_unknown_; }
  bool isSizeLocked() const { return size_locked_; }
  /// True after the first completed update.
  bool isInitialized() const { return initialized_; }
  /// True when every enabled layer and filter is current.
  bool isCurrent() const;

  /// Sets the padded footprint (robot frame) and tells every layer (onFootprintChanged).
  void setFootprint(const Footprint& footprint);
  const Footprint& getFootprint() const { return footprint_; }
  double getInscribedRadius() const { return inscribed_radius_; }
  double getCircumscribedRadius() const { return circumscribed_radius_; }

private:
  std::string global_frame_;
  bool rolling_window_;
  bool track_unknown_;
  bool size_locked_ = false;
  bool initialized_ = false;
  bool full_update_ = false;
  Costmap2D primary_;
  Costmap2D combined_;
  std::vector<std::shared_ptr<Layer>> plugins_;
  std::vector<std::shared_ptr<Layer>> filters_;
  ResizeHandler resize_handler_;
  CellWindow updated_;
  Footprint footprint_;
  double inscribed_radius_ = 0.0;
  double circumscribed_radius_ = 0.0;
};
}  // namespace costmap_layers
