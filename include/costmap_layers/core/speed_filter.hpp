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
// Nav2's rule for a mask value v (nav2SpeedLimit()), in the nav2 and filter_info forms:
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
#pragma once

#include <array>
#include <bitset>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
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
  bool filter_info = false;  ///< filter_info_topic is set: the info gives the unit, base and multiplier
  std::string features_topic = "/features";
  std::string max_speed_topic = "/max_speed";
  std::string speed_limit_topic;   ///< empty: no Nav2SpeedLimit output
  double default_max_speed = 0.0;  ///< [m/s]; 0 = no limit
  bool speed_limit_in_percent = false;
  SpeedMaskMode mask_mode = SpeedMaskMode::AreaId;
  double base = 0.0;        ///< nav2 mode: limit = base + multiplier * v
  double multiplier = 1.0;  ///< nav2 mode
};

/// Reads the parameters above. Throws std::invalid_argument on a bad value, when
/// speed_limit_in_percent is true while default_max_speed is 0 (a percentage of "no limit"), and when
/// filter_info_topic is set together with a parameter the info holds.
SpeedFilterConfig parseSpeedFilterConfig(const ParamReader& params);

/// Nav2's speed limit for a mask value v in 0..100 (see the file comment).
struct Nav2SpeedLimit
{
  double speed_limit = 0.0;   ///< what Nav2 publishes: [%] or [m/s], 0 = no limit
  double computed = 0.0;      ///< base + multiplier * v (0 for v = 0)
  bool out_of_range = false;  ///< computed was replaced by "no limit"
};
Nav2SpeedLimit nav2SpeedLimit(int v, double base, double multiplier, bool percent);

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

  /// The value published last on max_speed_topic [m/s], nullopt before the first publication.
  /// Update thread only.
  std::optional<double> lastPublished() const { return last_published_; }
  /// What was published last on speed_limit_topic (percentage, speed_limit); nullopt before the first
  /// publication and when speed_limit_topic is not set. Update thread only.
  std::optional<std::pair<bool, double>> lastSpeedLimit() const { return last_speed_limit_; }

protected:
  void onInitializeFilter(const ParamReader& params) override;
  FilterFamily filterFamily() const override { return FilterFamily::Speed; }
  void onFilterInfo(const FilterInfoData& info) override;
  /// Changes default_max_speed, speed_limit_in_percent, base and multiplier at run time (the topics and
  /// mask_mode cannot change); the last features message is re-evaluated.
  void onReconfigure(const ParamValue& params) override;
  std::vector<ParamSpec> tunableLayerParameters(const ParamValue& params) const override;
  /// Writes nothing, so a new mask (or a switch) asks for no redraw of the costmap.
  bool drawsCosts() const override { return false; }
  /// Writes nothing: the speed filter acts through its MaxSpeed output only.
  void process(Costmap2D&, const CellWindow&, const OccupancyGridData&, const MaskMapping&, double, double,
               double) override
  {
  }
  void processPose(const OccupancyGridData& mask, const Transform2D& to_mask, double robot_x, double robot_y,
                   double robot_yaw) override;
  /// Switched off or without a mask: no zone limits the robot, so default_max_speed is in force.
  void processInactive() override { publishIfChanged(noLimit()); }

private:
  /// One evaluation's result, for both outputs.
  struct Publication
  {
    std::optional<double> max_speed;  ///< [m/s]; nullopt: cannot be given in m/s (percent, no default)
    bool percentage = false;          ///< Nav2SpeedLimit
    double speed_limit = 0.0;         ///< Nav2SpeedLimit: [%] or [m/s], 0 = no limit
  };
  /// The unit, base and multiplier in force: from the info in the filter_info form.
  bool nav2Rule() const;
  bool percentUnit() const;
  Publication noLimit() const;
  /// Nav2's limit L ([%] or [m/s]) as both outputs carry it.
  Publication fromNav2Limit(double speed_limit) const;
  /// "publishing ... on <topic> and ... on <topic>", for warnings.
  std::string describe(const Publication& p) const;
  void publishIfChanged(const Publication& p);
  /// What to publish for a mask value other than -1, warning as documented.
  Publication limitForValue(int8_t v, const SpeedLimitTable* table);
  void warnValueOnce(int8_t v, const std::string& message);

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
};
}  // namespace costmap_layers
