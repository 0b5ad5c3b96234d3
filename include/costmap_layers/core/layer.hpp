// The plugin contract of costmap_2d: LayeredCostmap asks every enabled layer first how much of the
// map it wants to update (updateBounds, bounds only ever grow), then lets it write into the master
// grid inside the accumulated window (updateCosts). Layers are loaded by pluginlib against this class.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "costmap_layers/core/layer_context.hpp"
#include "costmap_layers/core/param_reader.hpp"

namespace costmap_layers
{
class Costmap2D;
class LayeredCostmap;

class Layer
{
public:
  Layer() = default;
  virtual ~Layer() = default;
  Layer(const Layer&) = delete;
  Layer& operator=(const Layer&) = delete;

  /// Called once by the host after construction; ends by calling onInitialize().
  /// @param parent   the costmap that owns this layer (not owned here; it outlives the layer)
  /// @param name     the instance name from the plugin list
  /// @param context  parameters, inputs, outputs and transforms for this instance
  /// Throws std::invalid_argument on a bad configuration.
  void initialize(LayeredCostmap* parent, const std::string& name, std::shared_ptr<LayerContext> context);

  /// Grows the window [m] this layer wants updated; the robot pose is in the global frame [m, rad].
  virtual void updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y,
                            double* max_x, double* max_y) = 0;
  /// Writes into master inside [min_i, max_i) x [min_j, max_j) [cells].
  virtual void updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j) = 0;
  /// Called when the master grid's size, resolution or origin changed.
  virtual void matchSize() {}
  /// Called when LayeredCostmap::setFootprint() changed the footprint.
  virtual void onFootprintChanged() {}
  /// Drops what the layer has accumulated.
  virtual void reset() {}
  /// Restarts inputs after deactivate().
  virtual void activate() {}
  /// Stops inputs.
  virtual void deactivate() {}
  /// Whether a "clear costmaps" request should reset this layer.
  virtual bool isClearable() { return false; }

  /// Run-time reconfiguration (dynamic_reconfigure in the node): `params` is the layer's whole
  /// namespace with the changes applied. Validates everything first and throws std::invalid_argument
  /// (keeping the current configuration) on a bad value. The host then redraws the whole map. The
  /// default handles `enabled` only.
  virtual void reconfigure(const ParamValue& params);
  /// What reconfigure() accepts: each tunable parameter's type, range, default and current value
  /// (as read from params), recorded from the same parse function that reads them.
  virtual std::vector<ParamSpec> tunableParameters(const ParamValue& params) const;

  /// Whether the layer's inputs are up to date.
  bool isCurrent() const { return current_; }
  bool enabled() const { return enabled_; }
  void setEnabled(bool enabled) { enabled_ = enabled; }
  bool isInitialized() const { return initialized_; }
  const std::string& getName() const { return name_; }
  /// The padded footprint of the parent costmap, in the robot frame [m].
  const std::vector<Eigen::Vector2d>& getFootprint() const;

protected:
  /// Reads parameters and sets up inputs. Throws std::invalid_argument on a bad configuration.
  virtual void onInitialize() {}

  LayeredCostmap* layered_costmap_ = nullptr;
  std::shared_ptr<LayerContext> context_;
  std::string name_;
  bool current_ = true;
  bool enabled_ = true;

private:
  bool initialized_ = false;
};
}  // namespace costmap_layers
