#pragma once
// Any costmap_layers layer or filter as a costmap_2d plugin, so that it runs inside move_base's global
// and local costmaps and move_base's planners see what it draws. Built only when costmap_2d is found.

#include <costmap_2d/costmap_layer.h>
#include <costmap_2d/layer.h>

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "costmap_layers/core/costmap/layer.hpp"
#include "costmap_layers/core/config/param_value.hpp"

namespace costmap_layers
{
class LayeredCostmap;
class StaticLayer;
}  // namespace costmap_layers
namespace costmap_layers_ros
{
class LayerPorts;
class LayerReconfigure;
class RosLayerContext;
class ThrottledLog;
}  // namespace costmap_layers_ros

namespace costmap_layers
{
namespace move_base
{
/// Hosts one core layer inside costmap_2d: move_base's master grid is the core layer's master (a view of
/// the same memory, no copy), its parameters come from the plugin's namespace (~/<costmap>/<name>, as
/// costmap_2d's own layers read theirs), its transforms from move_base's tf2 buffer, and the layer's
/// inputs, outputs, `toggle` service and dynamic_reconfigure server live in that namespace too.
/// Base is costmap_2d::Layer, or costmap_2d::CostmapLayer for ClearableLayerBridge.
template <class Base>
class LayerBridgeOn : public Base
{
public:
  /// @param class_name  the core class's name, e.g. "KeepoutFilter" (for messages and the table of the
  ///                    parameters costmap_2d and Nav2 know for it)
  LayerBridgeOn(std::shared_ptr<costmap_layers::Layer> core, std::string class_name);
  ~LayerBridgeOn() override;
  LayerBridgeOn(const LayerBridgeOn&) = delete;
  LayerBridgeOn& operator=(const LayerBridgeOn&) = delete;

  void updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y, double* max_x,
                    double* max_y) override;
  void updateCosts(costmap_2d::Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j) override;
  void matchSize() override;
  void onFootprintChanged() override;
  void reset() override;
  void activate() override;
  void deactivate() override;

  /// The hosted layer (for tests).
  const costmap_layers::Layer& core() const { return *core_; }
  /// For a filter that draws costs: why a plugin after it in costmap_2d's list overwrites what it
  /// draws (a static layer), or "" (warned at run time; for tests).
  const std::string& orderProblem() const { return order_problem_; }
  costmap_layers::Layer& core() { return *core_; }

protected:
  void onInitialize() override;

private:
  void setUp();
  /// The layer's parameters: its namespace, with what costmap_2d's rules give a layer of the type this
  /// one stands in for (applyCostmap2dRulesAsRole), reported.
  costmap_layers::ParamValue layerParameters(const ros::NodeHandle& nh);
  /// Blocks start-up until the static layer has a map (costmap_2d's StaticLayer does), spinning the
  /// global queue its subscription is on.
  void waitForMap(const costmap_layers::StaticLayer& layer, const ros::NodeHandle& nh);
  /// Points the core master at move_base's master grid (its memory moves on a resize).
  void viewMaster();
  void expandToWholeMap(double* min_x, double* min_y, double* max_x, double* max_y) const;
  /// For ClearableLayerBridge, this plugin's own costmap_2d grid's mutex, locked (what
  /// clear_costmap_recovery holds while it clears: see ClearableLayerBridge::clearArea); otherwise no
  /// lock. Taken after the costmap's mutex wherever both are held.
  boost::unique_lock<costmap_2d::Costmap2D::mutex_t> lockOwnGrid();
  /// Sets order_problem_ and warns when this is a filter that draws costs and a later plugin overwrites
  /// the master (a static layer not using its maximum): the filter's cells would be lost.
  void checkPluginOrder();
  /// Fills costmap2d_static_layers_ from the costmap's `plugins` list on the parameter server.
  void readCostmap2dStaticLayers(const ros::NodeHandle& nh);

  std::shared_ptr<costmap_layers::Layer> core_;
  std::string class_name_;
  std::unique_ptr<costmap_layers::LayeredCostmap> host_;
  std::shared_ptr<costmap_layers_ros::ThrottledLog> log_;
  std::shared_ptr<costmap_layers_ros::RosLayerContext> context_;
  std::unique_ptr<costmap_layers_ros::LayerPorts> ports_;
  std::unique_ptr<costmap_layers_ros::LayerReconfigure> reconfigure_;
  /// The same for the layers the core layer holds (a PluginContainerLayer's plugins).
  std::vector<std::unique_ptr<costmap_layers_ros::LayerPorts>> held_ports_;
  std::vector<std::unique_ptr<costmap_layers_ros::LayerReconfigure>> held_reconfigure_;
  std::atomic<bool> full_update_{true};     ///< redraw the whole map next cycle (start, reconfigure, reset)
  std::vector<std::string> consumed_keys_;  ///< layer keys costmap_2d's rules used up (not "unknown")
  std::string order_problem_;               ///< see orderProblem()
  /// The names (as costmap_2d names its plugins, <costmap>/<entry>) of the costmap's plugins that are
  /// costmap_2d's own StaticLayer without use_maximum: they overwrite the master every cycle. Known by
  /// the type in the costmap's plugin list, not by a cast, so that this library does not link
  /// costmap_2d's plugin library (liblayers): one the dynamic linker has mapped already, class_loader
  /// never registers the factories of, and move_base could then load none of costmap_2d's own layers.
  std::vector<std::string> costmap2d_static_layers_;
};

extern template class LayerBridgeOn<costmap_2d::Layer>;
extern template class LayerBridgeOn<costmap_2d::CostmapLayer>;

/// The bridge for layers without a clear operation (static layer, inflation, filters).
using LayerBridge = LayerBridgeOn<costmap_2d::Layer>;

/// The bridge for clearable core layers (obstacle, voxel, range): a costmap_2d::CostmapLayer, as
/// costmap_2d's own sensor layers are, so that move_base's clear-costmap recovery
/// (clear_costmap_recovery, which clears only CostmapLayers) clears it. Its costmap_2d grid is a view
/// of the core layer's own grid (no copy: what costmap_2d code reads there is what the layer holds),
/// kept on the core grid's memory and geometry after every change; clearArea clears the core layer's
/// cells by costmap_2d's rule (clearLayerArea). Everything the bridge does to the core layer happens
/// under this grid's own mutex, which the recovery holds while it clears.
class ClearableLayerBridge : public LayerBridgeOn<costmap_2d::CostmapLayer>
{
public:
  using LayerBridgeOn<costmap_2d::CostmapLayer>::LayerBridgeOn;
  /// The grid is the core layer's: costmap_2d must not free it.
  ~ClearableLayerBridge() override;
  ClearableLayerBridge(const ClearableLayerBridge&) = delete;
  ClearableLayerBridge& operator=(const ClearableLayerBridge&) = delete;

  void updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y, double* max_x,
                    double* max_y) override;
  void matchSize() override;
  void clearArea(int start_x, int start_y, int end_x, int end_y, bool invert_area) override;

protected:
  void onInitialize() override;
  // Costmap2D's allocation hooks: the cells are the core layer's, never allocated or freed here.
  void deleteMaps() override;
  void initMaps(unsigned int size_x, unsigned int size_y) override;
  /// Resets every cell to the grid's default value (resetLayerCells), then asks for a redraw.
  void resetMaps() override;

private:
  /// Points costmap_2d's grid fields at the core layer's grid (memory, size, resolution, origin).
  void viewCoreGrid();
};

}  // namespace move_base
}  // namespace costmap_layers
