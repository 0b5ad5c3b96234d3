// costmap_2d's StaticLayer: a map from a topic, interpreted into costs once per map, copied (or
// maximised) into the master grid. When the costmap is not rolling the master takes the map's size,
// resolution and origin; in a rolling window the map is sampled through the transform from the
// costmap's frame into the map's frame. Maps arrive on another thread: they are validated there, handed
// over under a mutex, and interpreted on the update thread (in updateBounds).
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "costmap_layers/core/costmap/costmap_layer.hpp"
#include "costmap_layers/core/data/grid_data.hpp"
#include "costmap_layers/core/grid/grid_sampler.hpp"
#include "costmap_layers/core/rules/map_value_rule.hpp"
#include "costmap_layers/core/rules/stamp_order.hpp"

namespace costmap_layers
{
class ParamReader;

struct StaticConfig
{
  std::string map_topic = "map";
  bool first_map_only = false;        ///< ignore every map after the first accepted one
  bool subscribe_to_updates = false;  ///< accept applyUpdate() (the adapter subscribes <map_topic>_updates)
  bool track_unknown_space = true;    ///< default: the costmap's track_unknown_space
  bool use_maximum = false;           ///< max into the master instead of overwriting it
  int lethal_cost_threshold = 100;    ///< occupancy at or above this is lethal (clamped to [0, 100])
  int unknown_cost_value = -1;        ///< the occupancy value meaning "unknown" (compared as a byte)
  bool trinary_costmap = true;        ///< below the threshold: free, else scaled
  /// Nav2's: the map's cells under the robot's footprint read FREE_SPACE in the copy into the master
  /// (a robot started or localised inside a mapped obstacle can move out) ...
  bool footprint_clearing_enabled = false;
  /// ... and are the map's again afterwards (false: they stay free until the next map).
  bool restore_cleared_footprint = true;
};

/// Reads the parameters with costmap_2d's names; track_unknown_space defaults to default_track_unknown.
/// Throws std::invalid_argument naming the parameter.
StaticConfig parseStaticConfig(const ParamReader& params, bool default_track_unknown);

/// mapValueCost() (rules/map_value_rule.hpp) with this layer's parameters.
inline uint8_t interpretStaticValue(int8_t value, const StaticConfig& config)
{
  return mapValueCost(value, MapValueRule{config.unknown_cost_value, config.lethal_cost_threshold,
                                          config.trinary_costmap, config.track_unknown_space});
}

class StaticLayer : public CostmapLayer
{
public:
  void updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y, double* max_x,
                    double* max_y) override;
  void updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j) override;
  /// True when the map is in, the costmap does not roll and use_maximum is off: updateCosts() then
  /// copies its own grid (of the master's size) over the whole window, as costmap_2d's true overwrite.
  bool overwritesWindow(const Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j) const override;
  /// Not rolling: follows the master (keeping the map when the geometry is unchanged). Rolling: the own
  /// grid is the map's and stays.
  void matchSize() override;
  /// Redraws the whole map on the next update.
  void reset() override;
  void activate() override { reset(); }

  const StaticConfig& config() const { return config_; }

  /// Hands over a new map; safe from any thread. A map failing validateGrid() or stamped before the map
  /// in force (isOutOfOrder()) is rejected and the previous map stays. With first_map_only, maps after
  /// the first accepted one are ignored.
  /// @return an empty string when accepted (or ignored), else the reason (also reported as an Error).
  std::string setMap(std::shared_ptr<const OccupancyGridData> map);
  /// A partial update of the latest map (map_msgs/OccupancyGridUpdate): width x height values, row-major,
  /// for the cells [x, x + width) x [y, y + height). Safe from any thread; applied on the next update.
  /// Rejected (returned and reported) when subscribe_to_updates is off, before any map, when it is
  /// stamped before the map in force (it was meant for an older map), when the data size is not
  /// width * height or when the rectangle leaves the map (validateGridUpdate()). Updates wait for the
  /// next cycle in a queue of at most kMaxPendingUpdateCells cells and kMaxPendingUpdates updates; past
  /// that the oldest are dropped, counted in a throttled warning (a flood cannot grow memory).
  /// @param stamp_ns  the update's header.stamp [ns], 0 for none
  std::string applyUpdate(int64_t x, int64_t y, uint32_t width, uint32_t height, const std::vector<int8_t>& data,
                          uint64_t stamp_ns = 0);
  static constexpr std::size_t kMaxPendingUpdates = 256;
  static constexpr uint64_t kMaxPendingUpdateCells = 64ull << 20;

  /// True once a map has been interpreted (on the update thread).
  bool mapReceived() const { return map_received_; }
  /// True once a map has been accepted (setMap(); any thread), before the update thread has seen it.
  bool mapAccepted() const;
  /// The frame of the map in force.
  const std::string& mapFrame() const { return map_frame_; }
  /// ERROR while no map was accepted (naming the topic and the last rejection), WARN when the latest map
  /// was rejected (the previous one stays), else OK with the map in force and when it arrived.
  LayerStatus status() const override;

protected:
  void onInitialize() override;

private:
  struct PendingUpdate
  {
    uint32_t x, y, width, height;
    std::vector<int8_t> data;
  };
  void processMap(const OccupancyGridData& map);
  void processUpdate(const PendingUpdate& update);
  void markDirty(unsigned x0, unsigned y0, unsigned x1, unsigned y1);
  /// footprint_clearing_enabled: sets the own cells under footprint_ to FREE_SPACE, remembering them
  /// (none when a vertex is off the map, as costmap_2d's polygon fill); own: the own grid's placement
  /// in the map's frame, to_map: the costmap's frame -> the map's.
  void clearFootprintCells(const GridPlacement& own, const Transform2D& to_map);
  /// The own grid's placement (its cells), with the given yaw in the map's frame.
  GridPlacement ownPlacement(double yaw) const;
  /// Puts the cells clearFootprintCells() cleared back (restore_cleared_footprint), and forgets them.
  void restoreFootprintCells();
  void rebuildTable();

  StaticConfig config_;
  uint8_t table_[256] = {};  ///< cost per occupancy byte

  // Shared with the threads that deliver maps and updates.
  mutable std::mutex mutex_;
  std::shared_ptr<const OccupancyGridData> pending_map_;
  std::vector<PendingUpdate> pending_updates_;
  uint64_t pending_update_cells_ = 0;
  uint64_t dropped_updates_ = 0;  ///< since the layer started, for the flood warning
  bool accepted_any_ = false;     ///< a map was accepted (for first_map_only and updates)
  uint32_t latest_width_ = 0, latest_height_ = 0;
  uint64_t map_stamp_ns_ = 0;  ///< header.stamp of the latest accepted map
  // For status(): what arrived, and when (context clock).
  uint64_t maps_accepted_ = 0, maps_rejected_ = 0, updates_accepted_ = 0, updates_rejected_ = 0;
  uint64_t map_received_ns_ = 0;
  StartupGrace startup_grace_;  ///< before the first map: when "waiting for the map" is said (update thread)
  std::string last_rejection_;    ///< why the latest rejected map was refused
  bool latest_rejected_ = false;  ///< the newest map that arrived was rejected

  // Update thread only.
  bool map_received_ = false;
  bool dirty_ = false;
  unsigned dirty_x0_ = 0, dirty_y0_ = 0, dirty_x1_ = 0, dirty_y1_ = 0;  ///< own cells [x0, x1) x [y0, y1)
  std::string map_frame_;
  GridSampler sampler_;                       ///< update thread only: master cells -> map cells in a rolling window
  std::vector<Eigen::Vector2d> footprint_;    ///< the robot's, in the costmap's frame (update)
  std::vector<MapLocation> footprint_cells_;  ///< scratch of clearFootprintCells
  std::vector<std::pair<std::size_t, uint8_t>> cleared_;  ///< own cells cleared this copy, their costs
  double map_yaw_ = 0.0;
};
}  // namespace costmap_layers
