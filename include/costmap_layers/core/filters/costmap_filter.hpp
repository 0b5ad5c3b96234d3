// The base of costmap filters (Nav2's design): the base owns the mask, its frame transform and the
// robot pose; a subclass only says what a mask value means, in process(). A new mask replaces the old
// one atomically, and the next update covers the union of the old and new mask extents.
//
// Where the mask comes from, one of two forms (setting both is a start-up error naming both):
//  - `mask_topic`: the mask is read from that topic (default: the filter's defaultMaskTopic()).
//  - `filter_info_topic` (Nav2's form): the filter reads a filter info (CostmapFilterInfo, as
//    published by costmap_filter_info_server) there, and reads the mask from the topic the info names,
//    with the info's type, base and multiplier (filter_info.hpp says which types a filter takes).
//    Until an info arrives the filter does nothing and says so (a throttled "waiting" warning); an
//    info the filter cannot use is reported (an Error keyed "filter_info/<field>") and ignored, the
//    previous info staying in force. A later info naming another mask topic moves the subscription:
//    the mask from the old topic is dropped (it is not what the new info describes) and the filter
//    waits for a mask on the new one; masks still arriving from the old topic are ignored. An info
//    naming the same topic keeps the mask and changes only how it is read.
//
// The lifecycle (Nav2's resetFilter() / initializeFilter(); in ROS 1 move_base's costmap stop() and
// start()): deactivate() drops the mask and the filter info, ends their subscriptions and puts the
// outputs to "no effect"; masks and infos that still arrive are ignored. activate() subscribes again
// (a latched mask or info comes anew) and the filter waits for them as at start.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/core/costmap/layer.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/filters/filter_info.hpp"
#include "costmap_layers/core/grid/costmap_2d.hpp"
#include "costmap_layers/core/grid/grid_sampler.hpp"
#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/core/rules/stamp_order.hpp"

namespace costmap_layers
{
class ParamReader;

/// Checks a mask or map: data size, dimensions (at most max_cells), resolution in
/// [limits::kMinResolution, limits::kMaxResolution], origin x/y within limits::kMaxCoordinate and yaw
/// within limits::kMaxYaw (see limits.hpp for why).
/// @return ok() when valid, else the field at fault and one line naming it and its value.
InputError validateGrid(const OccupancyGridData& grid, uint64_t max_cells = limits::kMaxGridCells);

/// Checks a partial update (x, y, width x height, data_size values) against a grid of
/// grid_width x grid_height cells, in arithmetic that cannot overflow or wrap for any field values.
/// @return ok() when it fits, else the field at fault and one line naming it and its value.
InputError validateGridUpdate(int64_t x, int64_t y, uint32_t width, uint32_t height, std::size_t data_size,
                              uint32_t grid_width, uint32_t grid_height);

class CostmapFilter : public Layer
{
public:
  /// Whether the filter writes costs into the master grid (drawsCosts()).
  bool writesCosts() const override { return drawsCosts(); }
  /// Takes the newest mask, looks up the transform (global -> mask frame) once for the cycle and calls
  /// processPose(); grows the bounds by the old and new mask extents when the mask changed (and the
  /// filter drawsCosts()).
  void updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y, double* max_x,
                    double* max_y) override;
  /// Calls process(); skips (writing nothing) when disabled, without a mask, or without a transform.
  void updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j) final;
  bool isClearable() override { return false; }
  /// Drops the mask and the filter info (the mask's costs go at the next update), ends the inputs'
  /// subscriptions (the host unsubscribes ports whose topic is empty) and puts the outputs to "no
  /// effect" (processInactive()), as Nav2's ZoneParameterFilter::resetFilter(). Any thread; a second
  /// call does nothing.
  void deactivate() override;
  /// After deactivate(): subscribes the mask (or the filter info) again, so that a latched one comes
  /// anew, and waits for it as at start (the "no mask yet" grace starts again). Otherwise nothing.
  void activate() override;
  /// Whether a mask is in force, with its info in the filter_info_topic form (Nav2's isActive()): false
  /// before the first one and from deactivate() until a new one arrives.
  bool isActive() const;

  /// Replaces the mask, unless it is invalid or stamped before the mask in force (isOutOfOrder()): then
  /// the previous mask stays, and the reason is reported (an Error keyed by the field) and returned.
  /// Safe to call from another thread than the update loop.
  /// @return an empty string when accepted, else the error.
  std::string setMask(std::shared_ptr<const OccupancyGridData> mask);
  /// The mask in force (nullptr before the first one).
  std::shared_ptr<const OccupancyGridData> getMask() const;
  /// The topic the mask is read from: `mask_topic`, or the one the filter info named (empty before
  /// the first info).
  std::string maskTopic() const;

  /// Whether the filter is configured in Nav2's form (`filter_info_topic`).
  bool usesFilterInfo() const { return !filter_info_topic_.empty(); }
  const std::string& filterInfoTopic() const { return filter_info_topic_; }
  /// Installs a filter info (what the filter_info_topic subscription calls), as the file comment says.
  /// Thread-safe; infos are applied one at a time.
  /// @return an empty string when accepted, else the error (also reported).
  std::string setFilterInfo(std::shared_ptr<const FilterInfoData> info);
  /// The filter info in force (nullptr before the first accepted one, and always in the mask_topic form).
  std::shared_ptr<const FilterInfoData> getFilterInfo() const;
  /// OK when switched off, deactivated or when a mask is in force; WARN while no mask has arrived
  /// (naming the topic and the last rejection), when the latest mask was rejected, or when the mask
  /// cannot be placed (no transform into its frame).
  LayerStatus status() const override;

protected:
  /// Reads the base's parameters (mask_topic or filter_info_topic), calls onInitializeFilter(), then
  /// declares the inputs: the mask (with an empty topic in the filter_info_topic form, until an info
  /// names it) and, in that form, the filter info.
  void onInitialize() final;
  /// The switch (Layer::setEnabled: `enabled`, the ~<name>/toggle service): the mask's extent is
  /// redrawn at the next update, and switched off the outputs say "no effect" at once
  /// (processInactive()).
  void onEnabledChanged(bool on) final;
  /// Which infos this filter takes (checkFilterInfoFor()).
  virtual FilterFamily filterFamily() const { return FilterFamily::Keepout; }
  /// Called once an info was accepted (any thread), for the subclass's own warnings.
  virtual void onFilterInfo(const FilterInfoData& info) { (void)info; }
  virtual void onInitializeFilter(const ParamReader& params) { (void)params; }
  /// The subclass's meaning of the mask. `mapping` maps the window onto `mask`.
  /// robot pose in the global frame [m, rad].
  virtual void process(Costmap2D& master_grid, const CellWindow& window, const OccupancyGridData& mask,
                       const GridSampler& mapping, double robot_x, double robot_y, double robot_yaw) = 0;
  /// Called every cycle with the mask in force and the transform, even when no cell is updated (what
  /// SpeedFilter needs). robot pose in the global frame [m, rad].
  virtual void processPose(const OccupancyGridData& mask, const Transform2D& to_mask, double robot_x, double robot_y,
                           double robot_yaw)
  {
    (void)mask, (void)to_mask, (void)robot_x, (void)robot_y, (void)robot_yaw;
  }
  /// Called instead of processPose() when the filter has no mask yet (every cycle; not when only the
  /// transform is missing), and once when it is switched off: SpeedFilter restores its default there.
  virtual void processInactive() {}
  /// Whether the filter writes costs into the master grid. A filter that does not (SpeedFilter) asks for
  /// no redraw when its mask changes or it is switched: the next update's bounds stay what the other
  /// layers ask for.
  virtual bool drawsCosts() const { return true; }
  /// Default topic of the mask, overridable per filter type.
  virtual std::string defaultMaskTopic() const { return "/map_filter"; }
  /// The mask value at a world point (global frame), or nullopt when outside the mask.
  static std::optional<int8_t> maskValueAt(const OccupancyGridData& mask, const Transform2D& to_mask, double wx,
                                           double wy);
  /// The mask of the current cycle (the one process() receives); the pointer changes only when a new
  /// mask was accepted, so subclasses can key derived data on it.
  const std::shared_ptr<const OccupancyGridData>& activeMask() const { return active_mask_; }
  /// The filter info of the current cycle (update thread only; nullptr in the mask_topic form). While
  /// the filter waits for its first info, no mask is active either.
  const std::shared_ptr<const FilterInfoData>& activeInfo() const { return active_info_; }
  /// The transform used by the last update (global frame -> mask frame).
  const Transform2D& lastTransform() const { return to_mask_; }
  /// Asks that this update cover the mask's whole extent, as when a new mask arrived (a subclass whose
  /// costs changed for another reason). Update thread only; call it from processPose().
  void requestRedraw() { redraw_requested_ = true; }

private:
  /// The mask's extent as a box in the global frame [m], when the transform is known: the one given
  /// (global frame -> mask frame, as to_mask_), or else looked up now.
  bool maskBoundsInGlobal(const OccupancyGridData& mask, const std::optional<Transform2D>& to_mask, double& x0,
                          double& y0, double& x1, double& y1);
  /// updateBounds' request for the mask's extent: where the mask is to be drawn, where a mask was drawn
  /// that is to be cleared (replaced, switched off, or placed elsewhere by a changed transform), and
  /// again after a cycle that could not draw it (no transform).
  void requestMaskExtent(bool changed, const std::shared_ptr<const OccupancyGridData>& old, double* min_x,
                         double* min_y, double* max_x, double* max_y);

  /// setMask() for a mask delivered by the subscription of mask generation `generation`: masks of an
  /// older generation (a topic no longer in force) are ignored.
  std::string setMaskOf(uint64_t generation, std::shared_ptr<const OccupancyGridData> mask);

  /// The mask input's port for masks of generation `generation` (as subscribed by setFilterInfo()).
  InputPort maskPort(const std::string& topic, uint64_t generation);

  std::string filter_info_topic_;  ///< set once in onInitialize()
  std::size_t mask_port_ = 0;      ///< index of the mask input
  std::size_t info_port_ = 0;      ///< index of the filter info input (filter_info_topic form)
  std::mutex lifecycle_mutex_;     ///< one activate() / deactivate() at a time
  /// Serialises processPose() / processInactive() between the update thread and a switch-off
  /// (onEnabledChanged() on the toggle service's thread).
  std::mutex outputs_mutex_;
  StartupGrace startup_grace_;  ///< before the first mask: when "no mask yet" is said (update thread)
  std::mutex info_mutex_;       ///< one setFilterInfo() at a time, so that port replacements stay in order
  mutable std::mutex mask_mutex_;
  std::string mask_topic_;                      ///< guarded by mask_mutex_
  uint64_t mask_generation_ = 0;                ///< guarded by mask_mutex_; +1 per topic change and per (de)activation
  bool deactivated_ = false;                    ///< guarded by mask_mutex_: between deactivate() and activate()
  bool restart_grace_ = false;                  ///< guarded by mask_mutex_: activate() asks the update thread
  std::shared_ptr<const FilterInfoData> info_;  ///< guarded by mask_mutex_
  std::shared_ptr<const OccupancyGridData> mask_;         ///< guarded by mask_mutex_
  std::shared_ptr<const OccupancyGridData> pending_old_;  ///< the mask replaced since the last bounds
  bool mask_changed_ = false;                             ///< guarded by mask_mutex_
  // For status(), guarded by mask_mutex_: what arrived and when (context clock).
  uint64_t masks_accepted_ = 0, masks_rejected_ = 0, mask_received_ns_ = 0;
  std::string last_rejection_;
  bool latest_rejected_ = false;
  std::string transform_error_;  ///< why the last cycle could not place the mask (update thread)
  std::shared_ptr<const OccupancyGridData> active_mask_;  ///< the mask of this cycle (update thread only)
  std::shared_ptr<const FilterInfoData> active_info_;     ///< the info of this cycle (update thread only)
  bool have_transform_ = false;
  bool redraw_requested_ = false;  ///< update thread only (requestRedraw())
  /// The transform the active mask was last drawn with (update thread; nullopt: not drawn yet), and
  /// whether a cycle skipped drawing since (no transform: the cells updated then lack the mask).
  std::optional<Transform2D> drawn_with_;
  bool draw_incomplete_ = false;
  double robot_x_ = 0, robot_y_ = 0, robot_yaw_ = 0;
  Transform2D to_mask_;
  GridSampler mapping_;
};
}  // namespace costmap_layers
