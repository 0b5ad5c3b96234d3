// Applies a layer's setpoints (OutputKind::Setpoints: ZoneParameterFilter) to other nodes through their
// dynamic_reconfigure servers, on a worker thread of its own: the costmap's update thread only hands a
// set over and never waits for a server.
//
// Per set, node by node (in the order the set names them):
//  1. the node's description (<node>/parameter_descriptions, latched) is read, waiting up to the
//     timeout: a setpoint whose parameter the server does not declare, whose value has another type
//     than the declared one, or a number outside the declared [min, max] is refused here and not sent
//     (a server would clamp it or ignore it);
//  2. the rest are sent in one call to <node>/set_parameters (dynamic_reconfigure/Reconfigure), after
//     waiting up to the timeout for the service to appear;
//  3. the configuration the server sends back is compared with each value sent: a parameter missing
//     from it, or holding another value (a server that refused it), is a failed set.
// Every failure is logged as an error naming the node, the parameter and the value, with the stable
// key <layer namespace>/setpoint/<node>/<parameter> (the node without its leading '/'); a call that has
// no answer within the timeout is reported too while it still waits. A set handed over while another
// is being applied waits; a newer one replaces it (sets are complete, so only the newest matters).
#pragma once

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>
#include <ros/ros.h>

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "costmap_layers/core/layer_io.hpp"
#include "costmap_layers/ros/ros_layer_context.hpp"

namespace costmap_layers_ros
{
class SetpointApplier
{
public:
  /// @param nh          resolves node names (relative ones in the costmap's namespace)
  /// @param key_prefix  the layer's namespace, e.g. "/costmap_node/zone_filter"
  /// @param timeout     [s] the longest wait for a description, a service and an answer
  SetpointApplier(ros::NodeHandle nh, std::string key_prefix, double timeout, std::shared_ptr<ThrottledLog> log);
  /// Stops the worker; a call in progress ends when roscpp shuts down.
  ~SetpointApplier();
  SetpointApplier(const SetpointApplier&) = delete;
  SetpointApplier& operator=(const SetpointApplier&) = delete;

  /// Hands a complete set over (any thread, never blocks on a server).
  void submit(std::vector<costmap_layers::Setpoint> set, std::string label);

  /// The request for some setpoints of one node: each value in the list of its type.
  static dynamic_reconfigure::Config request(const std::vector<costmap_layers::Setpoint>& setpoints);
  /// Why a setpoint cannot be sent to a server of that description ("" when it can).
  static std::string checkAgainst(const costmap_layers::Setpoint& s, const dynamic_reconfigure::ConfigDescription& d);
  /// Why the server's answer shows the setpoint not applied ("" when it holds the value sent).
  static std::string checkAnswer(const costmap_layers::Setpoint& s, const dynamic_reconfigure::Config& answer);
  /// The stable key of a setpoint's errors.
  std::string keyOf(const costmap_layers::Setpoint& s) const;

private:
  void run();
  void applyNode(const std::string& node, const std::vector<costmap_layers::Setpoint>& setpoints,
                 const std::string& label);
  void fail(const costmap_layers::Setpoint& s, const std::string& why);
  void watch(const ros::SteadyTimerEvent&);

  ros::NodeHandle nh_;
  std::string key_prefix_;
  double timeout_;
  std::shared_ptr<ThrottledLog> log_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::optional<std::pair<std::vector<costmap_layers::Setpoint>, std::string>> pending_;  ///< guarded by mutex_
  // The call in progress, for the watchdog (guarded by mutex_).
  std::vector<costmap_layers::Setpoint> calling_;
  std::string calling_service_;
  std::chrono::steady_clock::time_point call_started_;
  bool call_reported_ = false;
  ros::SteadyTimer watchdog_;
  std::thread worker_;
};
}  // namespace costmap_layers_ros
