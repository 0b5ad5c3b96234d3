// The plugin contract of costmap_2d: LayeredCostmap asks every enabled layer first how much of the
// map it wants to update (updateBounds, bounds only ever grow), then lets it write into the master
// grid inside the accumulated window (updateCosts). Layers are loaded by pluginlib against this class.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "costmap_layers/core/costmap/layer_context.hpp"
#include "costmap_layers/core/costmap/layer_io.hpp"
#include "costmap_layers/core/costmap/layer_status.hpp"
#include "costmap_layers/core/config/param_reader.hpp"

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
  /// @param context  parameters, transforms, the clock and problem reports for this instance
  /// Throws std::invalid_argument on a bad configuration. Reads `enabled` (the one place it is read).
  void initialize(LayeredCostmap* parent, const std::string& name, std::shared_ptr<LayerContext> context);

  /// What the layer takes from outside (declared while it initialised): the host subscribes to each
  /// port and hands every message to its handler.
  const std::vector<InputPort>& inputs() const { return inputs_; }
  /// What the layer gives out: the host advertises each port and publishes the events the layer emits.
  const std::vector<OutputPort>& outputs() const { return outputs_; }
  /// Where port replacements go (replaceInput()): the host re-subscribes that input. The latest
  /// replacement of each port made before a listener is set is delivered to it at once. The listener
  /// is called with the layer's input lock held, so replacements of one layer reach it one at a time
  /// and in order; it must not call back into setInputListener().
  void setInputListener(InputListener listener);
  /// Where emitted events go. The latest event of each port emitted before a listener is set is
  /// delivered to it at once (outputs are latched).
  void setOutputListener(OutputListener listener);
  /// Whether anyone reads the on-demand output (OutputPort::on_demand) on `topic`: the host says so as
  /// readers come and go, and the layer builds that output only while it is true. Any thread.
  void setOutputWanted(const std::string& topic, bool wanted);

  /// Grows the window [m] this layer wants updated; the robot pose is in the global frame [m, rad].
  virtual void updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y,
                            double* max_x, double* max_y) = 0;
  /// Writes into master inside [min_i, max_i) x [min_j, max_j) [cells].
  virtual void updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j) = 0;
  /// Whether the next updateCosts() with this window writes every cell of it without reading master
  /// (the host then skips resetting the window before the first layer). Asked on the update thread,
  /// right before updateCosts(). The default: no.
  virtual bool overwritesWindow(const Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j) const
  {
    (void)master_grid, (void)min_i, (void)min_j, (void)max_i, (void)max_j;
    return false;
  }
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
  /// The layers this one holds and runs itself (a PluginContainerLayer's plugins), for the host to wire
  /// their ports as it does its own plugins'. The default: none.
  virtual std::vector<std::shared_ptr<Layer>> heldLayers() const { return {}; }

  /// Run-time reconfiguration (dynamic_reconfigure in the node): `params` is the layer's whole
  /// namespace with the changes applied. Reads `enabled`, lets the layer validate and apply the rest
  /// (onReconfigure(), which throws std::invalid_argument and keeps the current configuration on a
  /// bad value), then sets the switch (setEnabled()). The host then redraws the whole map.
  void reconfigure(const ParamValue& params);
  /// What reconfigure() accepts: `enabled`, then each parameter tunableLayerParameters() records.
  std::vector<ParamSpec> tunableParameters(const ParamValue& params) const;

  /// Whether the layer's inputs are up to date.
  bool isCurrent() const { return current_; }
  /// What the layer has received and when, and what it waits for: one level, one line and key/values,
  /// for /diagnostics. The host calls it on the update thread between cycles (the node holds its
  /// update lock), so update-thread state may be read; state shared with input threads needs its lock.
  /// The default says enabled / current (isCurrent()) and lists the inputs; layers with inputs say more.
  virtual LayerStatus status() const;
  /// The layer's one on/off switch: whether it takes part in updates. Hosts (LayeredCostmap, the
  /// move_base bridge) never call updateBounds / updateCosts of a disabled layer, so layers need no
  /// guard of their own. Any thread.
  bool enabled() const { return enabled_; }
  /// What `enabled` (at start and at run time) and, for filters, the ~toggle service set. Any thread.
  /// A change calls onEnabledChanged() (on the caller's thread) and is noted for the host, which
  /// redraws the whole grid at its next cycle (takeEnabledFlip()), so that a switched-off layer's
  /// cells go and a switched-on layer's appear at once.
  void setEnabled(bool on);
  /// Whether the switch changed since the last call (the host's question, once per cycle).
  bool takeEnabledFlip() { return enabled_flipped_.exchange(false); }
  /// Whether the layer writes into the grid: a switch of one that does not (a filter acting through
  /// its outputs only) asks for no redraw.
  virtual bool writesCosts() const { return true; }
  bool isInitialized() const { return initialized_; }
  const std::string& getName() const { return name_; }
  /// The padded footprint of the parent costmap, in the robot frame [m].
  const std::vector<Eigen::Vector2d>& getFootprint() const;

protected:
  /// Reads parameters and declares inputs and outputs. Throws std::invalid_argument on a bad configuration.
  virtual void onInitialize() {}
  /// The switch changed (setEnabled(), on its caller's thread; not at initialisation). A filter turns
  /// its outputs to "no effect" here. The default does nothing.
  virtual void onEnabledChanged(bool on) { (void)on; }
  /// Validates and applies a new configuration (everything but `enabled`); throws std::invalid_argument
  /// before changing anything. The default accepts nothing else.
  virtual void onReconfigure(const ParamValue& params) { (void)params; }
  /// The run-time tunable parameters besides `enabled`, recorded from the layer's parse function.
  virtual std::vector<ParamSpec> tunableLayerParameters(const ParamValue& params) const
  {
    (void)params;
    return {};
  }
  void addInput(InputPort port) { inputs_.push_back(std::move(port)); }
  void addOutput(OutputPort port) { outputs_.push_back(std::move(port)); }
  /// Replaces input `index` (declared with addInput()) by `port` of the same kind at run time, from any
  /// thread: the host unsubscribes the old topic (waiting for a delivery in progress) and subscribes
  /// port.topic with port's handler. inputs() keeps what was declared.
  void replaceInput(std::size_t index, InputPort port);
  /// Emits an event on an output port (any thread); the host publishes it.
  void emit(OutputKind kind, const std::string& topic, double value);
  void emit(const OutputEvent& event);
  /// Whether the host said someone reads the on-demand output on `topic` (setOutputWanted()). Cheap
  /// when nothing is wanted (one atomic load), so that a layer may ask every cycle.
  bool outputWanted(const std::string& topic) const;

  LayeredCostmap* layered_costmap_ = nullptr;
  std::shared_ptr<LayerContext> context_;
  std::string name_;
  bool current_ = true;

private:
  std::atomic<bool> enabled_{true};
  std::atomic<bool> enabled_flipped_{false};
  bool initialized_ = false;
  std::vector<InputPort> inputs_;
  std::vector<OutputPort> outputs_;
  std::mutex output_mutex_;
  OutputListener listener_;
  std::vector<OutputEvent> latest_;  ///< the latest event of each port, for a listener set later
  mutable std::mutex wanted_mutex_;
  std::vector<std::string> wanted_;         ///< on-demand outputs someone reads (wanted_mutex_)
  std::atomic<std::size_t> wanted_count_{0};  ///< wanted_.size(), read without the lock
  std::mutex input_mutex_;
  InputListener input_listener_;
  std::vector<std::pair<std::size_t, InputPort>> replaced_;  ///< the latest replacement of each port
};
}  // namespace costmap_layers
