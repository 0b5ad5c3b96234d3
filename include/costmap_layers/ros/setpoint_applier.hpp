// Applies a layer's setpoints (OutputKind::Setpoints: ZoneParameterFilter) to other nodes through their
// dynamic_reconfigure servers, on a worker thread of its own: the costmap's update thread only hands a
// set over and never waits for a server.
//
// Per node of a set:
//  1. the node's description (<node>/parameter_descriptions, latched) is read, waiting up to the
//     timeout: a setpoint whose parameter the server does not declare, whose value has another type
//     than the declared one, or a number outside the declared [min, max] is refused here and not sent
//     (a server would clamp it or ignore it);
//  2. the rest are sent in one call to <node>/set_parameters (dynamic_reconfigure/Reconfigure), after
//     waiting up to the timeout for the service to appear;
//  3. the configuration the server sends back is compared with each value sent: a parameter missing
//     from it, or holding another value (a server that refused it), is a failed set.
// Every failure is logged as an error naming the node, the parameter and the value, with the stable
// key <layer namespace>/setpoint/<node>/<parameter> (the node without its leading '/').
//
// A server that accepts the call and never answers: roscpp's calls have no timeout, so the call goes
// through a connection of the applier's own, which a watchdog drops once the call has waited longer
// than the timeout (reported as "no answer ... within"); the worker then goes on. A server that
// vanishes mid-call ends the call at once ("the call ... failed").
//
// Sets are complete (every parameter the layer ever sets, with the value that must hold now), so only
// the newest matters: a set handed over replaces the one held, and every node it names is marked to be
// applied again; a node's values are read from the newest set when its turn comes. The nodes take
// turns round-robin, so a node whose server keeps timing out delays the others by one timeout per
// turn and never starves them. Memory is one set and one flag per node, however fast sets come.
// The destructor interrupts every wait (description, service, call) and joins within about 0.1 s.
#pragma once

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <ros/ros.h>
#include <ros/service_server_link.h>

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "costmap_layers/core/costmap/layer_io.hpp"
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
  /// Stops the worker: interrupts its waits and drops the call in progress, then joins it.
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
  /// The nodes a set names, in the order it first names them.
  static std::vector<std::string> nodesOf(const std::vector<costmap_layers::Setpoint>& set);
  /// The node to apply next: the first node of `order` after `last` (wrapping round; from the start
  /// when `last` is not in `order`) that is in `due`; "" when none is.
  static std::string nextNode(const std::vector<std::string>& order, const std::vector<std::string>& due,
                              const std::string& last);

private:
  void run();
  void applyNode(const std::string& node, const std::vector<costmap_layers::Setpoint>& setpoints,
                 const std::string& label);
  void fail(const costmap_layers::Setpoint& s, const std::string& why);
  /// The watchdog thread: drops a call that waited longer than the timeout.
  void watchCalls();
  bool stopping();
  /// The node's description, waiting up to the timeout; null on a timeout or a stop.
  dynamic_reconfigure::ConfigDescriptionConstPtr waitForDescription(const std::string& topic);
  /// Whether the service exists, waiting up to the timeout; false on a timeout or a stop.
  bool waitForService(const std::string& service);
  /// The call through a connection the watchdog and the destructor can drop. @return false when it
  /// failed, was dropped (then *abandoned is true) or its answer does not deserialise.
  bool call(const std::string& service, const std::vector<costmap_layers::Setpoint>& to_send,
            dynamic_reconfigure::Reconfigure& srv, bool* abandoned);

  ros::NodeHandle nh_;
  std::string key_prefix_;
  double timeout_;
  std::shared_ptr<ThrottledLog> log_;
  std::mutex mutex_;
  std::condition_variable wake_;        ///< the worker: a set came, or stop
  std::condition_variable watch_wake_;  ///< the watchdog: a call started, or stop
  // Guarded by mutex_:
  bool stop_ = false;
  std::vector<costmap_layers::Setpoint> latest_;  ///< the newest set
  std::string latest_label_;
  std::vector<std::string> due_;  ///< nodes of latest_ not applied since it came
  std::string last_node_;         ///< the node applied last (round-robin)
  // The call in progress, for the watchdog:
  std::vector<costmap_layers::Setpoint> calling_;
  std::string calling_service_;
  std::chrono::steady_clock::time_point call_started_;
  ros::ServiceServerLinkPtr link_;  ///< dropped to end the call
  std::thread worker_;
  std::thread watchdog_;
};
}  // namespace costmap_layers_ros
