// dynamic_reconfigure for one layer, the ROS 1 way (rqt_reconfigure, dynparam, the Python client):
// ~<layer>/parameter_descriptions, ~<layer>/parameter_updates and ~<layer>/set_parameters. The
// description comes from the layer's own parse function (recorded by ParamReader), so names,
// defaults and ranges are declared once, next to the parsing.
#pragma once

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <ros/ros.h>

#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "costmap_layers/core/costmap/layer.hpp"
#include "costmap_layers/ros/ros_layer_context.hpp"

namespace costmap_layers_ros
{
/// dynamic_reconfigure's name of a parameter type: "bool", "int", "double" or "str".
const char* reconfigureTypeName(costmap_layers::ParamValue::Type t);
/// Adds name = value to the config, in the list of value's type (bools, ints, doubles, or strs for any
/// other type).
void addToConfig(dynamic_reconfigure::Config& config, const std::string& name, const costmap_layers::ParamValue& value);

/// What a set_parameters request makes of a layer's parameters (the part of the service that needs no
/// layer and no node, for tests).
struct ReconfigureChange
{
  costmap_layers::ParamValue next;  ///< current (a map; a new one when current is not) with each known name set
  std::string ignored;              ///< the names that cannot change, as logged: " a b ... (N in all)"
  std::size_t ignored_count = 0;    ///< how many names in all could not change
};
/// Applies config's bools, ints, doubles and strs, in that order, to current: a name among specs is set
/// to the value of its list's type; any other is ignored (the first kReconfigureNamesShown listed, each
/// clipped to 64 characters, then "(N in all)" when there were more).
ReconfigureChange applyConfig(const costmap_layers::ParamValue& current,
                              const std::vector<costmap_layers::ParamSpec>& specs,
                              const dynamic_reconfigure::Config& config);
/// How many ignored names a log line lists: a caller's thousands of megabyte names must not become a
/// log line that size.
constexpr std::size_t kReconfigureNamesShown = 8;

class LayerReconfigure
{
public:
  /// Runs a change: the host calls fn under its update lock, then redraws the whole map next cycle.
  using RunLocked = std::function<void(const std::function<void()>& fn)>;

  /// @param layer_nh  the layer's namespace (~<name>)
  /// @param params    the layer's parameter namespace as loaded
  LayerReconfigure(ros::NodeHandle layer_nh, std::shared_ptr<costmap_layers::Layer> layer,
                   costmap_layers::ParamValue params, RunLocked run_locked);

  /// The description the layer's tunable parameters make (exposed for tests).
  static dynamic_reconfigure::ConfigDescription describe(const std::vector<costmap_layers::ParamSpec>& specs,
                                                         const std::vector<costmap_layers::ParamSpec>& defaults);
  /// The values of specs as a Config.
  static dynamic_reconfigure::Config toConfig(const std::vector<costmap_layers::ParamSpec>& specs, bool use_defaults,
                                              int which = 0);

private:
  bool onSet(dynamic_reconfigure::Reconfigure::Request& req, dynamic_reconfigure::Reconfigure::Response& res);

  ros::NodeHandle nh_;
  std::shared_ptr<costmap_layers::Layer> layer_;
  costmap_layers::ParamValue params_;  ///< guarded by mutex_
  RunLocked run_locked_;
  std::mutex mutex_;
  ThrottledLog errors_{1.0};  ///< the service's error lines: at most one per second
  ros::Publisher descriptions_;
  ros::Publisher updates_;
  ros::ServiceServer service_;
};
}  // namespace costmap_layers_ros
