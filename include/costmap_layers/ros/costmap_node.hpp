// The costmap node: reads its parameters, loads the plugin lists through pluginlib, follows the robot
// through tf2 and runs the update loop; publishes ~costmap, ~costmap_updates and ~footprint.
#pragma once

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include "costmap_layers/ros/tf_listener.hpp"

#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "costmap_layers/core/config/config_compat.hpp"
#include "costmap_layers/core/costmap/costmap_config.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/costmap/loop_pacer.hpp"
#include "costmap_layers/core/costmap/publish_schedule.hpp"
#include "costmap_layers/core/grid/transform2d.hpp"
#include "costmap_layers/ros/layer_ports.hpp"
#include "costmap_layers/ros/layer_reconfigure.hpp"
#include "costmap_layers/ros/plugin_factory.hpp"
#include "costmap_layers/ros/ros_layer_context.hpp"

namespace costmap_layers_ros
{
/// A configuration error that stopped start-up; it has been logged (ROS_FATAL) already.
struct StartupError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// Reads the whole parameter namespace of nh into a tree (an empty map when nothing is set).
costmap_layers::ParamValue readNamespace(const ros::NodeHandle& nh);
/// The keys costmap_2d finds with searchParam (costmap_layers::searchedKeys()) as set in each parent
/// namespace of ns, nearest first, up to the root.
std::vector<costmap_layers::ParentNamespace> readParentNamespaces(const std::string& ns);

class CostmapNode
{
public:
  /// Logs one clear ROS_FATAL line and throws StartupError on a bad parameter or an unknown plugin type.
  /// @param topic_ns  when not empty, the absolute namespace relative topic names resolve against
  ///                  (RosLayerContext::setTopicNamespace()); else nh's namespace
  CostmapNode(ros::NodeHandle nh, ros::NodeHandle private_nh, std::string topic_ns = "");
  ~CostmapNode();

  /// Runs the update loop until ROS shuts down (callbacks need a spinner on other threads).
  void run();
  /// One cycle: robot pose, updateMap, publish when due. @return false when the pose was unavailable.
  bool updateOnce();
  /// True (and said, throttled, and in the diagnostics) while /use_sim_time is true and no /clock came.
  bool clockMissing();
  /// Sleeps on the steady clock, in slices that end early at shutdown.
  static void sleepWhileOk(double seconds);

  const costmap_layers::LayeredCostmap& costmap() const { return *costmap_; }
  const costmap_layers::CostmapConfig& config() const { return config_; }

private:
  void setUp();
  std::optional<costmap_layers::Transform2D> robotPose();
  /// Sends what the schedule says for the grid as it is now (caller holds update_mutex_).
  void publish();
  /// costmap_2d's rule: each new subscriber of ~costmap gets the current grid at once.
  void sendCurrentGrid(const ros::SingleSubscriberPublisher& subscriber);
  /// /diagnostics: one status for the costmap and one per layer (Layer::status() plus what arrived on
  /// each of its topics). Called from a timer on a spinner thread, under update_mutex_.
  void setUpDiagnostics(const std::vector<std::string>& layer_names);
  void costmapStatus(diagnostic_updater::DiagnosticStatusWrapper& stat);
  void layerStatus(const std::string& name, std::size_t ports_index, diagnostic_updater::DiagnosticStatusWrapper& stat);

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  std::string topic_ns_;
  /// The costmap's namespace after costmap_2d's rules (pre-Hydro conversion, searchParam look-ups).
  std::unique_ptr<costmap_layers::CompatResult> params_;
  costmap_layers::CostmapConfig config_;
  std::shared_ptr<ThrottledLog> log_;
  tf2_ros::Buffer tf_;
  GuardedTfListener tf_listener_;
  // Declared before the costmap: layers must be destroyed while their plugin library is loaded.
  PluginFactory factory_;
  std::unique_ptr<costmap_layers::LayeredCostmap> costmap_;
  ros::Publisher costmap_pub_;
  ros::Publisher update_pub_;
  ros::Publisher footprint_pub_;
  std::vector<std::unique_ptr<LayerPorts>> ports_;              ///< every layer's subscriptions and publications
  std::vector<std::unique_ptr<LayerReconfigure>> reconfigure_;  ///< one dynamic_reconfigure server per layer
  ros::ServiceServer clear_srv_;
  ros::ServiceServer clear_around_srv_;
  // Nav2's costmap services: ~get_cost, ~clear_entirely, ~clear_except_region, ~clear_around_pose.
  ros::ServiceServer get_cost_srv_, clear_entirely_srv_, clear_except_srv_, clear_around_pose_srv_;
  void advertiseNav2Services();
  std::mutex update_mutex_;                                    ///< one update cycle or one clear request at a time
  double last_x_ = 0, last_y_ = 0;                             ///< the robot position of the last update [m]
  bool cycled_once_ = false;                                   ///< a whole update cycle ran: the grid is worth sending
  std::unique_ptr<costmap_layers::PublishSchedule> schedule_;  ///< guarded by update_mutex_
  // For the costmap's diagnostics, guarded by update_mutex_.
  uint64_t cycles_ = 0;         ///< update cycles run
  double last_cycle_s_ = 0.0;   ///< how long the last cycle took [s]
  double worst_cycle_s_ = 0.0;  ///< the longest cycle since the last diagnostics [s]
  /// The loop's pacing and stall rule, on the steady clock (see steadySeconds()).
  std::unique_ptr<costmap_layers::LoopPacer> pacer_;
  bool waiting_for_clock_ = false;  ///< /use_sim_time is true and no /clock has arrived: no cycles
  double last_diagnostics_s_ = -1;  ///< steady time of the last /diagnostics publish (-1: none yet)
  std::string pose_error_;          ///< why the last attempt had no robot pose ("" = it had one)
  std::unique_ptr<diagnostic_updater::Updater> diagnostics_;
  ros::WallTimer diagnostics_timer_;
};
}  // namespace costmap_layers_ros
