// The ROS side of one layer's ports: every subscription and publication of the layer lives here, not
// in the core. Each input port becomes a subscription (sensors through a tf gate: a reading reaches
// the layer once tf can place it), each output port a latched publisher of the layer's events (a
// Setpoints port: a SetpointApplier, which sets them through dynamic_reconfigure on its own thread), and a
// filter's switch a ~<name>/toggle service. What happens to a message once it arrives is in
// port_dispatch.hpp (conversion and delivery), tf_gate.hpp (sensors) and port_receipts.hpp (counts):
// plain functions and classes a test can feed without a master.
#pragma once

#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <boost/make_shared.hpp>

#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "costmap_layers/core/costmap/layer.hpp"
#include "costmap_layers/ros/port_receipts.hpp"
#include "costmap_layers/ros/ros_layer_context.hpp"
#include "costmap_layers/ros/setpoint_applier.hpp"

namespace costmap_layers_ros
{
/// The ROS message type LayerPorts subscribes for an input of this kind ("sensor_msgs/LaserScan").
std::string portMessageType(costmap_layers::InputKind kind);
/// The ROS message type LayerPorts advertises for an output of this kind; "" for one it publishes on
/// no topic (Setpoints: parameters set through other nodes' dynamic_reconfigure servers).
std::string portMessageType(costmap_layers::OutputKind kind);
/// The services LayerPorts offers in the layer's own namespace (a filter's switch, std_srvs/SetBool).
std::vector<std::string> layerServices(const costmap_layers::Layer& layer);

class LayerPorts
{
public:
  /// @param public_nh   resolves the layers' topics
  /// @param private_nh  the layer's own namespace (~<name>): its toggle service
  /// @param topic_ns    when not empty, relative topic names resolve against this absolute namespace
  ///                    instead of public_nh's: move_base's costmaps resolve them against move_base's
  ///                    node handle. (roscpp cannot make a NodeHandle for "/" from a node in another
  ///                    namespace, so this is done by name.)
  /// The layer must outlive this object; the destructor detaches from the layer's outputs.
  LayerPorts(ros::NodeHandle public_nh, ros::NodeHandle private_nh, costmap_layers::Layer& layer,
             std::string global_frame, tf2_ros::Buffer& tf, std::shared_ptr<ThrottledLog> log,
             std::string topic_ns = "");
  /// The name a topic is subscribed or advertised under.
  std::string resolveTopic(const std::string& topic) const;
  /// Per subscribed topic (resolved name): "N message(s), last X s ago" or "nothing yet", counted when a
  /// message arrives (before tf or validation), for /diagnostics.
  std::vector<std::pair<std::string, std::string>> receipts() const;
  /// How many messages arrived on a topic and when (port_receipts.hpp).
  using Receipts = PortReceipts;
  ~LayerPorts();
  LayerPorts(const LayerPorts&) = delete;
  LayerPorts& operator=(const LayerPorts&) = delete;

private:
  /// The subscription of one non-sensor port (none when its topic is empty).
  ros::Subscriber subscribe(const costmap_layers::InputPort& in);
  /// Subscribes topic with the given queue length; each message is counted and handed to dispatch()
  /// (port_dispatch.hpp) with cb.
  template <class Msg, class Callback>
  ros::Subscriber subscribePort(const std::string& topic, uint32_t queue, Callback cb);
  /// Subscribes through a tf gate (tf_gate.hpp), retried whenever tf changes (TfChangeWake): a reading is
  /// delivered once its frame can be transformed into the global frame at its stamp, or dropped with a
  /// throttled warning.
  template <class Msg, class Reading>
  void subscribeSensor(const std::string& topic, const std::string& sensor_frame,
                       costmap_layers::SensorCallback<Reading> cb);
  void publish(const costmap_layers::OutputEvent& event);
  /// An on-demand output's publisher: its readers coming and going set Layer::setOutputWanted().
  ros::Publisher advertiseOnDemand(const costmap_layers::OutputPort& out);
  /// A voxel snapshot as the message of its port, when the port still has a reader.
  void publishVoxels(const costmap_layers::OutputEvent& event, ros::Publisher& pub);
  /// The receipt counter of a topic (created on first use).
  std::shared_ptr<Receipts> receiptsFor(const std::string& topic);

  ros::NodeHandle public_nh_;
  ros::NodeHandle private_nh_;
  costmap_layers::Layer& layer_;
  std::string topic_ns_;
  std::string global_frame_;
  tf2_ros::Buffer& tf_;
  std::shared_ptr<ThrottledLog> log_;
  std::mutex ports_mutex_;
  std::vector<ros::Subscriber> port_subscribers_;     ///< by input index (guarded by ports_mutex_)
  std::vector<std::string> port_topics_;              ///< their topics as receipts_ keys them (the same)
  std::deque<double> move_log_times_;                 ///< [s] when replaced ports were logged (ports_mutex_)
  std::size_t moves_unlogged_ = 0;                    ///< replacements since, not logged (ports_mutex_)
  std::vector<std::shared_ptr<void>> sensor_inputs_;  ///< tf gates with their subscribers, queues and tf wakes
  std::map<std::pair<costmap_layers::OutputKind, std::string>, ros::Publisher> publishers_;  ///< by kind, topic
  std::vector<ros::ServiceServer> toggles_;  ///< a filter's switch: `toggle` and Nav2's `toggle_filter`
  /// Tracked by the on-demand publishers' connection callbacks: none runs once this object is gone.
  ros::VoidConstPtr alive_ = boost::make_shared<int>(0);
  std::unique_ptr<SetpointApplier> setpoints_;  ///< the Setpoints output's worker (ZoneParameterFilter)
  /// By resolved topic, in order. Guarded by receipts_mutex_: a port replaced at run time adds a topic
  /// on a callback thread while the diagnostics read them on another.
  mutable std::mutex receipts_mutex_;
  std::vector<std::pair<std::string, std::shared_ptr<Receipts>>> receipts_;
};
}  // namespace costmap_layers_ros
