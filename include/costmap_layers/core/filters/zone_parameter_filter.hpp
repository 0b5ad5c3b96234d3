// ZoneParameterFilter: Nav2's zone parameter filter, the ROS 1 way. The mask value at the robot picks
// a named state; each state holds setpoints (node, parameter, value) that the host applies through
// the nodes' dynamic_reconfigure servers (<node>/set_parameters) when the robot enters the zone, and
// `nominal_defaults` hold the values restored on leaving. The filter writes nothing into the costmap.
// The core decides the state; the host (LayerPorts) applies the setpoints on a worker thread and
// reports every failed set.
//
// What the mask means (Nav2's rule: the mask value itself is the state id; base and multiplier of a
// filter info play no part, and an info whose base or multiplier is not 0 / 1 is warned about):
//   outside the mask, a 0 cell, switched off, no mask yet  -> state 0: the nominal defaults
//   a -1 (unknown) cell                                      -> the state in force stays
//   v in 1..100 with a state of id v                         -> that state
//   v in 1..100 without one (or a value outside -1..100)     -> state 0, an Error once per value and
//                                                               mask ("mask/state"); Nav2 stops there
// Evaluated once per update cycle at the robot's position (the robot's centre, as Nav2).
//
// What is applied: on every change of state (and once at the first update), the complete set of
// values that must hold from then on: every nominal default, with the new state's own setpoints in
// place of the defaults for the same (node, parameter). So parameters a previous state changed are
// restored in the same step, and a later set replaces an earlier one the host has not applied yet.
// The state id is emitted on state_event_topic (std_msgs/UInt8, latched) on every change.
//
// Parameters (in the filter's namespace), Nav2's names; the ROS 1 form of nominal_defaults differs
// (a map of entries: ROS 1 cannot hold a list and a namespace under one name):
//   mask_topic / filter_info_topic  (read by the base; an info must have type 4)
//   state_event_topic   "zone_filter_state"  std_msgs/UInt8, latched
//   setpoint_timeout    5.0 s   how long the host waits for a server to appear and to answer
//   states              []      names of the states, each a namespace:
//     <state>/id          1..100  the mask value of the state (unique)
//     <state>/setpoints   []      names of its setpoints, each a namespace <state>/<setpoint>:
//        node: "/move_base/DWAPlannerROS", parameter: "max_vel_x", value: 0.3
//   nominal_defaults    {}      <name>: {node, parameter, value}: the values outside every zone
// Start-up fails with one error naming the parameter for: a missing or bad id, a duplicate id, a
// setpoint without node, parameter or value, a value that is not a bool, integer, finite number or
// string, a (node, parameter) set twice in one state or in nominal_defaults, a state setpoint without a
// nominal default for the same (node, parameter) (leaving the zone could not restore it: Nav2 only
// warns), or a state value whose type differs from its default's (a generated dynamic_reconfigure
// server reads a double parameter only from the request's doubles: write 1.0, not 1).
#pragma once

#include <bitset>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "costmap_layers/core/filters/output_filter.hpp"

namespace costmap_layers
{
class ParamReader;

struct ZoneState
{
  std::string name;
  int id = 0;  ///< 1..100
  std::vector<Setpoint> setpoints;
};

struct ZoneParameterConfig
{
  std::string state_event_topic = "zone_filter_state";
  double setpoint_timeout = 5.0;  ///< [s]
  std::vector<ZoneState> states;
  std::vector<Setpoint> nominal_defaults;
};

/// Reads the parameters above. Throws std::invalid_argument naming the parameter and the value.
ZoneParameterConfig parseZoneParameterConfig(const ParamReader& params);

/// The complete set of values in force in state `id` (0: the nominal defaults), as the file comment
/// says; in nominal_defaults' order. An id without a state gives the nominal defaults.
std::vector<Setpoint> zoneSetpoints(const ZoneParameterConfig& config, int id);

/// The state the rule above gives.
/// @param value    the mask value at the robot; nullopt outside the mask
/// @param current  the state in force (0 before any)
/// @param unknown  set to true when the value named no declared state (may be nullptr)
int zoneStateFor(std::optional<int> value, int current, const ZoneParameterConfig& config, bool* unknown);

/// The name of state `id` ("nominal" for 0, "" when there is none).
std::string zoneStateName(const ZoneParameterConfig& config, int id);

class ZoneParameterFilter : public OutputFilter
{
public:
  const ZoneParameterConfig& config() const { return config_; }
  /// The state emitted last (nullopt before the first update). Update thread only.
  std::optional<int> stateInForce() const { return state_; }
  /// The filter's status, with the state in force.
  LayerStatus status() const override;

protected:
  void onInitializeFilter(const ParamReader& params) override;
  FilterFamily filterFamily() const override { return FilterFamily::ZoneParameter; }
  void onFilterInfo(const FilterInfoData& info) override;
  void processPose(const OccupancyGridData& mask, const Transform2D& to_mask, double robot_x, double robot_y,
                   double robot_yaw) override;
  /// Switched off or without a mask: no zone holds, so the nominal defaults are in force.
  void processInactive() override { enter(0); }

private:
  /// Emits the state and its setpoints when it differs from the one in force (or none was emitted).
  void enter(int id);

  ZoneParameterConfig config_;
  std::optional<int> state_;  ///< update thread only
  std::bitset<256> warned_values_;
  std::shared_ptr<const OccupancyGridData> warned_for_mask_;  ///< the mask warned_values_ belongs to
};
}  // namespace costmap_layers
