// LayerContext on ROS 1: parameters from the plugin's namespace on the parameter server, transforms
// from tf2, the ROS clock, reports to rosconsole throttled per key. (Subscriptions and publications
// are LayerPorts'.)
#pragma once

#include <ros/ros.h>
#include <tf2_ros/buffer.h>

#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "costmap_layers/core/costmap/layer_context.hpp"

namespace costmap_layers_ros
{
/// Logs each key at most once per period [s]; thread-safe. Keys name a field or a problem, never a
/// value from a message; the table is bounded all the same (kMaxKeys): when it is full, keys not seen
/// for a period are forgotten, and if none is, the message is throttled under one shared overflow key.
/// Each line ends with its key in brackets, e.g. "... [/costmap_node/keepout_filter/mask/data]".
class ThrottledLog
{
public:
  using Sink = std::function<void(costmap_layers::Severity, const std::string&)>;
  using Clock = std::function<double()>;  ///< [s], monotonic
  static constexpr std::size_t kMaxKeys = 1024;

  /// By default messages go to rosconsole and time is the steady clock; tests pass their own.
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
  RosLayerContext(ros::NodeHandle private_nh, costmap_layers::ParamValue params, std::string global_frame,
                  double transform_tolerance, tf2_ros::Buffer& tf, std::shared_ptr<ThrottledLog> log);

  const costmap_layers::ParamValue& params() const override { return params_; }
  const std::string& globalFrame() const override { return global_frame_; }
  double transformTolerance() const override { return transform_tolerance_; }
  std::optional<costmap_layers::Transform2D> lookupTransform(const std::string& target_frame,
                                                             const std::string& source_frame,
                                                             std::string* error) override;
  uint64_t nowNs() const override { return ros::Time::now().toNSec(); }
  void report(costmap_layers::Severity severity, const std::string& key, const std::string& message) override;

private:
  ros::NodeHandle private_nh_;
  costmap_layers::ParamValue params_;
  std::string global_frame_;
  double transform_tolerance_;
  tf2_ros::Buffer& tf_;
  std::shared_ptr<ThrottledLog> log_;
};
}  // namespace costmap_layers_ros
