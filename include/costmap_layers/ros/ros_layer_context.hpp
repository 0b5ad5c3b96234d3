// LayerContext on ROS 1: parameters from the plugin's namespace on the parameter server, inputs from
// topics, outputs to latched topics and a toggle service, transforms from tf2, reports to rosconsole
// throttled per key.
#pragma once

#include <ros/ros.h>
#include <tf2_ros/buffer.h>

#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "costmap_layers/core/layer_context.hpp"

namespace costmap_layers_ros
{
/// Logs each key at most once per period [s]; thread-safe. Keys name a field or a problem, never a
/// value from a message; the table is bounded all the same (kMaxKeys): when it is full, keys not seen
/// for a period are forgotten, and if none is, the message is throttled under one shared overflow key.
class ThrottledLog
{
public:
  using Sink = std::function<void(costmap_layers::Severity, const std::string&)>;
  using Clock = std::function<double()>;  ///< [s], monotonic
  static constexpr std::size_t kMaxKeys = 1024;

  /// By default messages go to rosconsole and time is the wall clock; tests pass their own.
  explicit ThrottledLog(double period = 5.0, Sink sink = {}, Clock clock = {});
  void log(costmap_layers::Severity severity, const std::string& key, const std::string& message);
  std::size_t keyCount() const;

private:
  double period_;
  Sink sink_;
  Clock clock_;
  mutable std::mutex mutex_;
  std::map<std::string, double> last_;
};

/// The latest transform mapping source_frame points into target_frame, projected to the plane;
/// nullopt with *error when tf has none or it is older than tolerance [s] (static ones never are).
std::optional<costmap_layers::Transform2D> lookupTransform2D(const tf2_ros::Buffer& tf, const std::string& target_frame,
                                                             const std::string& source_frame, double tolerance,
                                                             std::string* error);

class RosLayerContext : public costmap_layers::LayerContext
{
public:
  /// @param private_nh  the plugin's own namespace (~<name>); params is its parameter tree
  RosLayerContext(ros::NodeHandle public_nh, ros::NodeHandle private_nh, costmap_layers::ParamValue params,
                  std::string global_frame, double transform_tolerance, tf2_ros::Buffer& tf,
                  std::shared_ptr<ThrottledLog> log);

  /// Relative topic names resolve against ns (an absolute namespace such as "/") instead of
  /// public_nh's namespace: move_base's costmaps resolve them against move_base's node handle.
  /// Empty (the default): public_nh's namespace. (roscpp cannot make a NodeHandle for "/" from a node
  /// in another namespace, so this is done by name.)
  void setTopicNamespace(std::string ns) { topic_ns_ = std::move(ns); }
  /// The name a topic is subscribed or advertised under.
  std::string resolveTopic(const std::string& topic) const;

  const costmap_layers::ParamValue& params() const override { return params_; }
  const std::string& globalFrame() const override { return global_frame_; }
  double transformTolerance() const override { return transform_tolerance_; }
  void subscribeGrid(const std::string& topic, costmap_layers::GridKind kind, costmap_layers::GridCallback cb) override;
  void subscribeGridUpdates(const std::string& topic, costmap_layers::GridUpdateCallback cb) override;
  void subscribeSpeedLimits(const std::string& topic, costmap_layers::SpeedLimitsCallback cb) override;
  void subscribeLaserScan(const std::string& topic, const std::string& sensor_frame,
                          costmap_layers::SensorCallback<costmap_layers::LaserScanData> cb) override;
  void subscribePointCloud2(const std::string& topic, const std::string& sensor_frame,
                            costmap_layers::SensorCallback<costmap_layers::PointCloud2Data> cb) override;
  void subscribeRange(const std::string& topic, costmap_layers::SensorCallback<costmap_layers::RangeData> cb) override;
  costmap_layers::MaxSpeedPublisher advertiseMaxSpeed(const std::string& topic) override;
  void advertiseToggle(std::function<void(bool)> cb) override;
  std::optional<costmap_layers::Transform2D> lookupTransform(const std::string& target_frame,
                                                             const std::string& source_frame,
                                                             std::string* error) override;
  uint64_t nowNs() const override { return ros::Time::now().toNSec(); }
  void report(costmap_layers::Severity severity, const std::string& key, const std::string& message) override;

private:
  /// Subscribes through a tf gate (see ros_layer_context.cpp): a reading is delivered once its frame
  /// can be transformed into the global frame at its stamp, or dropped with a throttled warning.
  template <class Msg, class Reading>
  void subscribeSensor(const std::string& topic, const std::string& sensor_frame,
                       costmap_layers::SensorCallback<Reading> cb);

  ros::NodeHandle public_nh_;
  ros::NodeHandle private_nh_;
  std::string topic_ns_;
  costmap_layers::ParamValue params_;
  std::string global_frame_;
  double transform_tolerance_;
  tf2_ros::Buffer& tf_;
  std::shared_ptr<ThrottledLog> log_;
  std::vector<ros::Subscriber> subscribers_;
  std::vector<ros::Publisher> publishers_;
  std::vector<ros::ServiceServer> services_;
  std::vector<std::shared_ptr<void>> sensor_inputs_;  ///< tf gates with their subscribers
};
}  // namespace costmap_layers_ros
