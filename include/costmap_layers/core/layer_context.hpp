// What a layer may ask of the world around it: its parameters, its inputs, its outputs, transforms,
// the clock and a place to report problems. The ROS adapter implements it with topics and tf2;
// costmap_tool implements it with files. Layers never see ROS.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "costmap_layers/core/grid_data.hpp"
#include "costmap_layers/core/param_value.hpp"
#include "costmap_layers/core/sensor_data.hpp"
#include "costmap_layers/core/transform2d.hpp"

namespace costmap_layers
{
enum class Severity
{
  Debug,
  Info,
  Warn,
  Error
};

/// What a grid subscription is for, so that an offline host knows which file feeds it.
enum class GridKind
{
  Map,
  Mask
};

using GridCallback = std::function<void(const std::shared_ptr<const OccupancyGridData>&)>;
using GridUpdateCallback = std::function<void(const std::shared_ptr<const OccupancyGridUpdateData>&)>;
using SpeedLimitsCallback = std::function<void(const std::shared_ptr<const SpeedLimitsData>&)>;
template <class Reading>
using SensorCallback = std::function<void(const std::shared_ptr<const Reading>&, const SensorPose&)>;
using MaxSpeedPublisher = std::function<void(double max_speed)>;

class LayerContext
{
public:
  virtual ~LayerContext() = default;

  /// This layer's own parameter namespace (a Map, or Null when nothing was set).
  virtual const ParamValue& params() const = 0;
  /// The frame the costmap is expressed in.
  virtual const std::string& globalFrame() const = 0;
  /// How old a transform may be [s].
  virtual double transformTolerance() const = 0;

  /// Delivers every grid received on topic (also one published before the subscription, when latched).
  /// Callbacks may run on another thread than the update loop.
  virtual void subscribeGrid(const std::string& topic, GridKind kind, GridCallback cb) = 0;
  /// Partial map updates (map_msgs/OccupancyGridUpdate). Hosts without such a source ignore it.
  virtual void subscribeGridUpdates(const std::string& topic, GridUpdateCallback cb) { (void)topic, (void)cb; }
  virtual void subscribeSpeedLimits(const std::string& topic, SpeedLimitsCallback cb) = 0;
  /// Sensor readings, delivered only once the host has the transform from the reading's frame into the
  /// global frame at the reading's stamp (it waits a bounded time for tf, then drops the reading with a
  /// throttled warning naming the frames). `sensor_frame`, when not empty, overrides the frame whose
  /// origin is the sensor origin. Hosts without sensors ignore these.
  virtual void subscribeLaserScan(const std::string& topic, const std::string& sensor_frame,
                                  SensorCallback<LaserScanData> cb)
  {
    (void)topic, (void)sensor_frame, (void)cb;
  }
  virtual void subscribePointCloud2(const std::string& topic, const std::string& sensor_frame,
                                    SensorCallback<PointCloud2Data> cb)
  {
    (void)topic, (void)sensor_frame, (void)cb;
  }
  virtual void subscribeRange(const std::string& topic, SensorCallback<RangeData> cb) { (void)topic, (void)cb; }
  /// A latched publisher of the current speed limit [m/s] on topic.
  virtual MaxSpeedPublisher advertiseMaxSpeed(const std::string& topic) = 0;
  /// Registers a run-time on/off switch for this layer (a ~<name>/toggle service in the node).
  virtual void advertiseToggle(std::function<void(bool)> cb) = 0;

  /// The transform mapping points in source_frame into target_frame, or nullopt with *error set.
  virtual std::optional<Transform2D> lookupTransform(const std::string& target_frame, const std::string& source_frame,
                                                     std::string* error) = 0;
  /// Wall or simulated time [ns].
  virtual uint64_t nowNs() const = 0;

  /// Reports a problem or event; the host logs it, at most once per throttle period per key.
  virtual void report(Severity severity, const std::string& key, const std::string& message) = 0;
};
}  // namespace costmap_layers
