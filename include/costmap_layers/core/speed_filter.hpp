// SpeedFilter: limits the robot's speed by where it stands on a mask, and publishes the limit
// (MaxSpeed, m/s) whenever it changes. It writes nothing into the costmap.
//
// Two ways to read the mask (parameter mask_mode):
//  - area_id (default): a cell value v in 1..100 is the id of a speed area, 0 is "in no area". The
//    limit of each area comes from SpeedLimits messages on features_topic (max_speed per area_id).
//  - nav2: a cell value v in 1..100 encodes the limit itself, as Nav2's speed masks do:
//    limit = base + multiplier * v, in percent of default_max_speed or in m/s
//    (speed_limit_in_percent); 0 means "no limit". No features are needed.
//
// What is published, evaluated once per update cycle at the robot's position:
//  - outside the mask, on a 0 cell, or on an area id without a (valid) limit: default_max_speed
//    (0.0 by the Nav2 convention means "no limit"); an id without a limit is warned once per id and
//    features message;
//  - on a -1 (unknown) cell: the value published last (default_max_speed when none was published);
//  - on a value outside -1..100 (invalid in an OccupancyGrid): default_max_speed, warned once per value;
//  - in area_id mode, on an area with a limit: that limit (in percent mode, default_max_speed * p / 100);
//  - in nav2 mode: L = base + multiplier * v. Nav2 replaces a limit out of range (percent outside
//    [0, 100], m/s below 0) by "no limit"; this filter does the same, and since a limit of 0 also means
//    "no limit" in the MaxSpeed convention, it counts 0 as out of range too: percent limits must lie in
//    (0, 100] and m/s limits must be > 0 (and finite), else default_max_speed is published and the
//    mask value warned once. Percent limits are never clamped.
// A value is published on the first evaluation and then only when it changes.
//
// Features are checked entry by entry; a bad entry is reported (Error) and dropped, the others kept:
// ids outside 1..100 (no mask cell can hold them), NaN, infinite or negative max_speed, percentages
// outside (0, 100] in percent mode. A duplicate id is warned and the later entry wins.
//
// Parameters (in the filter's namespace):
//   mask_topic             "/map_filter"   (read by the base)
//   features_topic         "/features"     SpeedLimits, area_id mode only
//   max_speed_topic        "/max_speed"    MaxSpeed output (latched)
//   default_max_speed      0.0   [m/s] >= 0; 0 = no limit
//   speed_limit_in_percent false  percent mode needs default_max_speed > 0 (else start-up fails)
//   mask_mode              "area_id" | "nav2"
//   base                   0.0   nav2 mode
//   multiplier             1.0   nav2 mode
#pragma once

#include <array>
#include <bitset>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "costmap_layers/core/costmap_filter.hpp"

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
  std::string features_topic = "/features";
  std::string max_speed_topic = "/max_speed";
  double default_max_speed = 0.0;  ///< [m/s]; 0 = no limit
  bool speed_limit_in_percent = false;
  SpeedMaskMode mask_mode = SpeedMaskMode::AreaId;
  double base = 0.0;        ///< nav2 mode: limit = base + multiplier * v
  double multiplier = 1.0;  ///< nav2 mode
};

/// Reads the parameters above. Throws std::invalid_argument on a bad value, and when
/// speed_limit_in_percent is true while default_max_speed is 0 (a percentage of "no limit").
SpeedFilterConfig parseSpeedFilterConfig(const ParamReader& params);

/// The valid limits of one features message, by area id, already in m/s.
struct SpeedLimitTable
{
  static constexpr int kMaxAreaId = 100;
  /// limit_mps[id] for id in 1..100; nullopt when the message gave none (or only bad ones).
  std::array<std::optional<double>, kMaxAreaId + 1> limit_mps{};
};

/// One problem found in a features message.
struct SpeedLimitIssue
{
  bool error = true;      ///< true: the entry was dropped; false: a warning (duplicate id)
  std::size_t index = 0;  ///< index of the entry in the message
  uint32_t area_id = 0;
  std::string message;  ///< one line, names the entry, its values and the rule
};

/// Checks a features message entry by entry (see the file comment) and converts percentages into
/// m/s with config.default_max_speed. Problems are appended to issues (may be nullptr).
SpeedLimitTable buildSpeedLimitTable(const SpeedLimitsData& limits, const SpeedFilterConfig& config,
                                     std::vector<SpeedLimitIssue>* issues);

class SpeedFilter : public CostmapFilter
{
public:
  const SpeedFilterConfig& config() const { return config_; }

  /// Checks and installs a features message (what the features_topic subscription calls). Bad entries
  /// are reported through the context and dropped; a message stamped before the one in force
  /// (isOutOfOrder()) is reported and dropped whole. Safe to call from any thread; takes effect at the
  /// next update cycle.
  /// @return the number of dropped entries
  std::size_t setSpeedLimits(const SpeedLimitsData& limits);


  /// The value published last [m/s], nullopt before the first publication. Update thread only.
  std::optional<double> lastPublished() const { return last_published_; }

protected:
  void onInitializeFilter(const ParamReader& params) override;
  /// Changes default_max_speed, speed_limit_in_percent, base and multiplier at run time (the topics and
  /// mask_mode cannot change); the last features message is re-evaluated.
  void onReconfigure(const ParamValue& params) override;
  std::vector<ParamSpec> tunableLayerParameters(const ParamValue& params) const override;
  /// Writes nothing: the speed filter acts through its MaxSpeed output only.
  void process(Costmap2D&, const CellWindow&, const OccupancyGridData&, const MaskMapping&, double, double,
               double) override
  {
  }
  void processPose(const OccupancyGridData& mask, const Transform2D& to_mask, double robot_x, double robot_y,
                   double robot_yaw) override;
  /// Switched off or without a mask: no zone limits the robot, so default_max_speed is in force.
  void processInactive() override { publishIfChanged(config_.default_max_speed); }

private:
  void publishIfChanged(double speed);
  /// The limit [m/s] for a mask value in 0..100 (not -1), warning as documented.
  double limitForValue(int8_t v, const SpeedLimitTable* table);
  void warnValueOnce(int8_t v, const std::string& message);

  SpeedFilterConfig config_;

  mutable std::mutex limits_mutex_;
  std::shared_ptr<const SpeedLimitTable> limits_;         ///< guarded by limits_mutex_
  std::shared_ptr<const SpeedLimitsData> last_features_;  ///< guarded by limits_mutex_

  // Update thread only.
  std::shared_ptr<const SpeedLimitTable> active_limits_;
  std::optional<double> last_published_;
  std::bitset<256> warned_ids_;     ///< area ids without a limit, warned for active_limits_
  std::bitset<256> warned_values_;  ///< invalid / out-of-range mask values, warned once
};
}  // namespace costmap_layers
