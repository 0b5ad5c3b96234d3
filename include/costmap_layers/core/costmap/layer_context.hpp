// What a layer may ask of the world around it while it works: its parameters, transforms, the clock
// and a place to report problems. Inputs and outputs are not here: a layer declares them as ports
// (layer_io.hpp) and the host owns every subscription and publication. The ROS adapter implements
// this with the parameter server, tf2 and rosconsole; costmap_tool with files. Layers never see ROS.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "costmap_layers/core/config/param_value.hpp"
#include "costmap_layers/core/grid/transform2d.hpp"

namespace costmap_layers
{
enum class Severity
{
  Debug,
  Info,
  Warn,
  Error
};

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

  /// The transform mapping points in source_frame into target_frame, or nullopt with *error set.
  virtual std::optional<Transform2D> lookupTransform(const std::string& target_frame, const std::string& source_frame,
                                                     std::string* error) = 0;
  /// Wall or simulated time [ns].
  virtual uint64_t nowNs() const = 0;

  /// Reports a problem or event. `key` names the problem (a field, never a value from a message);
  /// the host logs each key at most once per throttle period.
  virtual void report(Severity severity, const std::string& key, const std::string& message) = 0;
};
}  // namespace costmap_layers
