// BinaryFilter (Nav2's): a switch that flips where the robot stands on a mask, published as a
// std_msgs/Bool (cameras off in private areas, headlights on outdoors, a beeper in shared aisles).
// It writes nothing into the costmap.
//
// Rule, evaluated once per update cycle at the robot's position (binaryState()):
//   a mask value v in 0..100 gives the filter-space value base + multiplier * v; above
//   flip_threshold the state is !default_state, otherwise default_state.
//   On a -1 (unknown) cell the state stays what it was (Nav2: "do nothing").
//   Outside the mask, without a mask (or without a filter info yet), and while switched off:
//   default_state. A value outside -1..100 (invalid in an OccupancyGrid): default_state, warned once
//   per value.
// The state is published once at start (default_state, latched) and then only when it changes.
//
// Parameters (in the filter's namespace; the mask topic or filter_info_topic are the base's):
//   binary_state_topic  "binary_state"  std_msgs/Bool output (latched), resolved like every topic
//   default_state       false
//   flip_threshold      50.0   the filter-space value above which the state flips
//   base, multiplier    0.0, 1.0   mask_topic form only; with filter_info_topic the info (type 3) gives
//                                  them, and setting them is a start-up error naming the parameter
#pragma once

#include <bitset>
#include <optional>
#include <string>
#include <vector>

#include "costmap_layers/core/filters/output_filter.hpp"

namespace costmap_layers
{
class ParamReader;

struct BinaryFilterConfig
{
  bool filter_info = false;  ///< filter_info_topic is set: the info gives base and multiplier
  std::string binary_state_topic = "binary_state";
  bool default_state = false;
  double flip_threshold = 50.0;
  double base = 0.0;
  double multiplier = 1.0;
};

/// Reads the parameters above; throws std::invalid_argument naming the parameter and the value.
BinaryFilterConfig parseBinaryFilterConfig(const ParamReader& params);

/// Nav2's binary rule for a mask value v in 0..100: base + multiplier * v > flip_threshold flips the
/// state away from default_state.
bool binaryState(int v, double base, double multiplier, double flip_threshold, bool default_state);

class BinaryFilter : public OutputFilter
{
public:
  const BinaryFilterConfig& config() const { return config_; }
  /// The state published last (default_state from the start). Update thread only.
  bool state() const { return state_; }

protected:
  void onInitializeFilter(const ParamReader& params) override;
  FilterFamily filterFamily() const override { return FilterFamily::Binary; }
  /// Changes default_state, flip_threshold, base and multiplier at run time (not the topic).
  void onReconfigure(const ParamValue& params) override;
  std::vector<ParamSpec> tunableLayerParameters(const ParamValue& params) const override;
  void processPose(const OccupancyGridData& mask, const Transform2D& to_mask, double robot_x, double robot_y,
                   double robot_yaw) override;
  /// Switched off or without a mask: default_state.
  void processInactive() override
  {
    if (state_ != config_.default_state) setState(config_.default_state, "no mask in force, or switched off");
  }

private:
  void setState(bool state, const std::string& why);

  BinaryFilterConfig config_;
  bool state_ = false;              ///< update thread only
  std::bitset<256> warned_values_;  ///< invalid mask values, warned once
};
}  // namespace costmap_layers
