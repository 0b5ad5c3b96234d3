// SpeedFilter: limits the robot's speed by where it stands on a mask, and publishes the limit
// (MaxSpeed, m/s) whenever it changes and, when speed_limit_topic is set, Nav2's form of it
// (Nav2SpeedLimit: percentage + speed_limit, 0 = no limit). It writes nothing into the costmap.
//
// Three ways to read the mask:
//  - area_id (mask_mode, the default): a cell value v in 1..100 is the id of a speed area, 0 is "in no
//    area". The limit of each area comes from SpeedLimits messages on features_topic (max_speed per
//    area_id).
//  - nav2 (mask_mode): a cell value v in 1..100 encodes the limit itself, as Nav2's speed masks do:
//    limit = base + multiplier * v, in percent (speed_limit_in_percent) or in m/s; 0 means "no limit".
//  - filter_info_topic (Nav2's form, read by the base class): as nav2, with base, multiplier and the
//    unit from the filter info (type 1: percent, type 2: m/s). mask_mode, base, multiplier,
//    speed_limit_in_percent and features_topic must not be set in this form (a start-up error names
//    the parameter): the info holds them.
//
// Nav2's rule for a mask value v (nav2SpeedLimit(), rules/speed_rules.hpp), in the nav2 and filter_info forms:
//   v = 0 -> no limit; v in 1..100 -> L = base + multiplier * v; in percent, L < 0 or L > 100 is
//   out of range; in m/s, L < 0 (or not finite) is; an out-of-range L becomes "no limit" (warned once
//   per mask value). L = 0 is "no limit" too (what 0 means in Nav2's message), without a warning.
//
// What is published, evaluated once per update cycle at the robot's position:
//  - outside the mask, on a 0 cell, switched off, without a mask (or without a filter info yet):
//    no limit, i.e. MaxSpeed default_max_speed (0.0 = no limit) and speed_limit 0;
//  - on a -1 (unknown) cell: what was published last (no limit when nothing was);
//  - on a value outside -1..100 (invalid in an OccupancyGrid): no limit, warned once per value;
//  - area_id: the area's limit in m/s (percentages are taken of default_max_speed); an id without a
//    limit is no area, warned once per id and features message; Nav2SpeedLimit carries the same m/s
//    value with percentage false;
//  - nav2 / filter_info: Nav2SpeedLimit carries exactly Nav2's value (percentage = the unit);
//    MaxSpeed is L in m/s, or default_max_speed * L / 100 in percent, or default_max_speed for no
//    limit. A percentage cannot become m/s while default_max_speed is 0: then MaxSpeed is not
//    published for it (an Error says so when the percent info arrives; Nav2SpeedLimit still is).
// Each output is published on the first evaluation and then only when its value changes; every
// warning says what is published instead.
//
// Path lookahead (Nav2's enable_path_lookahead): the limit published is the strictest one at the
// robot and at the poses of the planned path (path_topic) within the lookahead distance ahead of the
// robot, so that the robot slows before a zone instead of inside it:
//  - speed v = |linear.x| of odometry (odom_topic), averaged over the messages of the last 0.3 s
//    (Nav2's odometry smoother); lookahead = v^2 / (2 |max_decel|) clamped to [min_lookahead,
//    max_lookahead] (lookaheadDistance()); with max_decel 0, max_lookahead. While the limit found
//    ahead differs from the one at the robot, the lookahead does not shrink below the distance that
//    found it (Nav2's hold: slowing down must not lift the limit that made the robot slow down).
//  - the poses walked: from the start of the path segment nearest the robot (searched forward from
//    the last one, from 0 for a new path) along the path while the distance walked is at most the
//    lookahead (lookaheadEnd()); a pose outside the mask or on a -1 cell adds nothing;
//  - strictest: the smallest positive limit (speed_limit as Nav2SpeedLimit carries it; 0 = none).
//  - the path is transformed into the global frame each cycle (tf); an empty path means "no plan":
//    the robot's own cell only, as without lookahead.
//  - without odometry, or when the newest is older than odom_timeout: max_lookahead (the cautious
//    choice), with an error; a path that cannot be transformed: the robot's own cell only, with an
//    error. A path with a non-finite or absurd position, more than limits::kMaxPathPoses poses or
//    no frame is refused with an error naming the field (the previous path stays); so is odometry
//    with a non-finite or absurd twist (the previous speed stays).
//
// Features are checked entry by entry; a bad entry is reported (Error) and dropped, the others kept:
// ids outside 1..100 (no mask cell can hold them), NaN, infinite or negative max_speed, percentages
// outside (0, 100] in percent mode. A duplicate id is warned and the later entry wins.
//
// Parameters (in the filter's namespace):
//   mask_topic             "/map_filter"   (read by the base; or filter_info_topic, Nav2's form)
//   filter_info_topic      ""              (read by the base) CostmapFilterInfo
//   features_topic         "/features"     SpeedLimits, area_id mode only
//   max_speed_topic        "/max_speed"    MaxSpeed output (latched)
//   speed_limit_topic      ""              Nav2SpeedLimit output (latched); empty: not published
//   default_max_speed      0.0   [m/s] >= 0; 0 = no limit
//   speed_limit_in_percent false  percent mode needs default_max_speed > 0 (else start-up fails)
//   mask_mode              "area_id" | "nav2"
//   base                   0.0   nav2 mode
//   multiplier             1.0   nav2 mode
//   enable_path_lookahead  false
//   max_decel              -0.5  [m/s^2] <= 0 (Nav2's sign: negative); 0 = always max_lookahead
//   min_lookahead          0.3   [m] >= 0
//   max_lookahead          5.0   [m] >= min_lookahead
//   path_topic             "plan"  nav_msgs/Path (move_base: e.g. /move_base/NavfnROS/plan)
//   odom_topic             "odom"  nav_msgs/Odometry
//   odom_timeout           0.5   [s] > 0: older odometry is stale (this package's own)
#pragma once

#include <bitset>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "costmap_layers/core/filters/output_filter.hpp"
#include "costmap_layers/core/filters/speed_window.hpp"
#include "costmap_layers/core/rules/speed_rules.hpp"
#include "costmap_layers/core/rules/stamp_order.hpp"

namespace costmap_layers
{
class ParamReader;

enum class SpeedMaskMode
{
  AreaId,
  Nav2
};

struct SpeedFilterConfig
{
  bool filter_info = false;  ///< filter_info_topic is set: the info gives the unit, base and multiplier
  std::string features_topic = "/features";
  std::string max_speed_topic = "/max_speed";
  std::string speed_limit_topic;   ///< empty: no Nav2SpeedLimit output
  double default_max_speed = 0.0;  ///< [m/s]; 0 = no limit
  bool speed_limit_in_percent = false;
  SpeedMaskMode mask_mode = SpeedMaskMode::AreaId;
  double base = 0.0;        ///< nav2 mode: limit = base + multiplier * v
  double multiplier = 1.0;  ///< nav2 mode
  bool enable_path_lookahead = false;
  double max_decel = -0.5;     ///< [m/s^2], <= 0
  double min_lookahead = 0.3;  ///< [m]
  double max_lookahead = 5.0;  ///< [m]
  std::string path_topic = "plan";
  std::string odom_topic = "odom";
  double odom_timeout = 0.5;  ///< [s]
};

/// Reads the parameters above. Throws std::invalid_argument on a bad value, when
/// speed_limit_in_percent is true while default_max_speed is 0 (a percentage of "no limit"), and when
/// filter_info_topic is set together with a parameter the info holds.
SpeedFilterConfig parseSpeedFilterConfig(const ParamReader& params);

/// Checks a features message entry by entry (see the file comment) and converts percentages into
/// m/s with config.default_max_speed (the rule: buildSpeedLimitTable() in rules/speed_rules.hpp).
/// Problems are appended to issues (may be nullptr).
SpeedLimitTable buildSpeedLimitTable(const SpeedLimitsData& limits, const SpeedFilterConfig& config,
                                     std::vector<SpeedLimitIssue>* issues);

class SpeedFilter : public OutputFilter
{
public:
  const SpeedFilterConfig& config() const { return config_; }

  /// Checks and installs a features message (what the features_topic subscription calls). Bad entries
  /// are reported through the context and dropped; a message stamped before the one in force
  /// (isOutOfOrder()) is reported and dropped whole. Safe to call from any thread; takes effect at the
  /// next update cycle.
  /// @return the number of dropped entries
  std::size_t setSpeedLimits(const SpeedLimitsData& limits);

  /// The value published last on max_speed_topic [m/s], nullopt before the first publication.
  /// Update thread only.
  std::optional<double> lastPublished() const { return last_published_; }
  /// What was published last on speed_limit_topic (percentage, speed_limit); nullopt before the first
  /// publication and when speed_limit_topic is not set. Update thread only.
  std::optional<std::pair<bool, double>> lastSpeedLimit() const { return last_speed_limit_; }
  /// The lookahead distance of the last cycle [m] (0 before the first, or without lookahead).
  /// Update thread only.
  double lastLookahead() const { return last_lookahead_; }

  /// Checks and installs a planned path (what the path_topic subscription calls); a bad one is
  /// reported and dropped, the previous one staying. Any thread. @return empty, or the error.
  std::string setPath(const std::shared_ptr<const PathData>& path);
  /// Checks and records odometry (the odom_topic subscription). Any thread. @return empty, or the error.
  std::string setOdometry(const OdometryData& odom);

protected:
  void onInitializeFilter(const ParamReader& params) override;
  FilterFamily filterFamily() const override { return FilterFamily::Speed; }
  void onFilterInfo(const FilterInfoData& info) override;
  /// Changes default_max_speed, speed_limit_in_percent, base and multiplier at run time (the topics and
  /// mask_mode cannot change); the last features message is re-evaluated.
  void onReconfigure(const ParamValue& params) override;
  std::vector<ParamSpec> tunableLayerParameters(const ParamValue& params) const override;
  void processPose(const OccupancyGridData& mask, const Transform2D& to_mask, double robot_x, double robot_y,
                   double robot_yaw) override;
  /// Switched off or without a mask: no zone limits the robot, so default_max_speed is in force.
  void processInactive() override { publishIfChanged(noLimit()); }

private:
  /// One evaluation's result, for both outputs.
  using Publication = SpeedPublication;
  /// The unit, base and multiplier in force: from the info in the filter_info form.
  bool nav2Rule() const;
  bool percentUnit() const;
  /// The settings the speed rules read, as in force now.
  SpeedRule rule() const;
  Publication noLimit() const;
  /// "publishing ... on <topic> and ... on <topic>", for warnings.
  std::string describe(const Publication& p) const;
  void publishIfChanged(const Publication& p);
  /// What to publish for a mask value other than -1 (speedLimitForValue()), warning as documented.
  Publication limitForValue(int8_t v, const SpeedLimitTable* table);
  void warnValueOnce(int8_t v, const std::string& message);
  /// The robot's speed for the lookahead [m/s], or nullopt (reported) when odometry is missing or stale.
  std::optional<double> currentSpeed();
  /// With motion_mutex_ held: when the clock jumped back (ClockWatch), drops every odometry sample and
  /// returns the latest time seen before the jump; else 0.
  uint64_t dropOdometryBeforeJumpLocked(uint64_t now);
  void reportOdometryJump(uint64_t from_ns, uint64_t now);
  /// The strictest publication at the robot and along the path ahead (see the file comment).
  std::optional<Publication> lookahead(const OccupancyGridData& mask, const Transform2D& to_mask, double robot_x,
                                       double robot_y, const std::optional<Publication>& at_robot);

  SpeedFilterConfig config_;

  mutable std::mutex limits_mutex_;
  std::shared_ptr<const SpeedLimitTable> limits_;         ///< guarded by limits_mutex_
  std::shared_ptr<const SpeedLimitsData> last_features_;  ///< guarded by limits_mutex_

  // Update thread only.
  std::shared_ptr<const SpeedLimitTable> active_limits_;
  std::optional<double> last_published_;
  std::optional<std::pair<bool, double>> last_speed_limit_;
  std::bitset<256> warned_ids_;     ///< area ids without a limit, warned for active_limits_
  std::bitset<256> warned_values_;  ///< invalid / out-of-range mask values, warned once per info
  std::shared_ptr<const FilterInfoData> warned_for_info_;

  // Path lookahead: the topics, set once at start (input threads name them in reports) ...
  std::string path_topic_, odom_topic_;
  // ... inputs (guarded by motion_mutex_) ...
  mutable std::mutex motion_mutex_;
  ClockWatch odom_clock_;  ///< the odometry's clock: a jump back drops speeds_
  std::shared_ptr<const PathData> path_;
  OdometrySpeedWindow speeds_;  ///< the last 0.3 s of odometry
  // ... and their use (update thread only).
  std::shared_ptr<const PathData> active_path_;
  std::vector<PathData::Point> path_global_;  ///< active_path_ in the global frame
  std::size_t segment_ = 0;                   ///< nearest segment found last
  double held_lookahead_ = 0.0;               ///< [m] Nav2's hold
  double last_lookahead_ = 0.0;
};
}  // namespace costmap_layers
