// Nav2's RangeSensorLayer: sonar / IR Range readings update the cells of the sensor's cone with a
// probabilistic model. The own grid holds occupancy probabilities as costs (p * 254, unknown = 127);
// each reading takes every cell of the cone's bounding box (or, with inflate_cone < 1, of the partly
// inflated triangle) as prior, applies sensor_model(r, phi, theta) by Bayes' rule, and stores the
// posterior. updateCosts writes LETHAL_OBSTACLE where p > mark_threshold and FREE_SPACE where
// p < clear_threshold, over unknown or lower master cells.
// Readings are queued by the host's threads and applied in updateBounds.
#pragma once

#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/costmap/costmap_layer.hpp"
#include "costmap_layers/core/rules/range_model.hpp"
#include "costmap_layers/core/layers/sensor_parsing.hpp"
#include "costmap_layers/core/rules/stamp_order.hpp"

namespace costmap_layers
{
class ParamReader;

struct RangeSensorConfig
{
  std::vector<std::string> topics;    ///< a list, or one space-separated string
  double phi = 1.2;                   ///< [m] distance where delta() falls to one half (Nav2's phi_v_)
  double inflate_cone = 1.0;          ///< 0..1: 1 updates the cone's whole bounding box
  double no_readings_timeout = 0.0;   ///< [s] not current after this long without readings; 0 = off
  double clear_threshold = 0.2;       ///< probability below which a cell is written FREE_SPACE
  double mark_threshold = 0.8;        ///< probability above which a cell is written LETHAL_OBSTACLE
  bool clear_on_max_reading = false;  ///< a max-range reading clears its whole cone
  RangeInputType input_sensor_type = RangeInputType::All;  ///< "ALL", "VARIABLE" or "FIXED"
};

/// Reads the parameters with Nav2's names and defaults. Throws std::invalid_argument naming the
/// parameter (thresholds in [0, 1] with clear_threshold <= mark_threshold, phi > 0, inflate_cone in
/// [0, 1], no_readings_timeout >= 0).
RangeSensorConfig parseRangeSensorConfig(const ParamReader& params);


class RangeSensorLayer : public CostmapLayer
{
public:
  void updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y, double* max_x,
                    double* max_y) override;
  void updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j) override;
  /// Every cell back to p = 0.5; queued readings dropped.
  void reset() override;
  void activate() override;
  void deactivate() override;
  bool isClearable() override { return true; }

  const RangeSensorConfig& config() const { return config_; }

  /// Queues a reading (safe from any thread). Malformed readings, and readings stamped more than
  /// kFutureStampToleranceNs ahead of now, are rejected here: the reason is returned and reported as a
  /// Warn; "" when queued or when the reading says nothing. At most kMaxPending readings wait for the
  /// next update (a flood cannot grow memory or the work of one cycle, which runs under the costmap's
  /// lock): past that the oldest are dropped, counted and reported (throttled) at the next update.
  std::string addRange(const RangeData& range, const SensorPose& pose);
  static constexpr std::size_t kMaxPending = 128;
  /// The most cells one update may visit for range readings (each cone costs the cells of its bounding
  /// box on the grid): past that, the oldest readings of the cycle are dropped, counted and reported.
  static constexpr uint64_t kMaxCellsPerUpdate = 2'000'000;
  /// Readings waiting for the next update.
  std::size_t pending() const;
  /// Readings accepted and rejected and when; WARN when not current (no_readings_timeout passed) or when
  /// every reading was rejected.
  LayerStatus status() const override;

protected:
  void onInitialize() override;

private:
  struct Pending
  {
    double ox, oy, tx, ty;  ///< sensor origin and the reading's end point [m], global frame
    double range;           ///< [m]
    double max_angle;       ///< half the field of view [rad]
    bool clear;
  };
  std::string queueRange(const RangeData& range, const SensorPose& pose);
  void applyReading(const Pending& reading);
  void updateCell(double ox, double oy, double ot, double r, double max_angle, unsigned int x, unsigned int y,
                  bool clear);

  RangeSensorConfig config_;
  mutable std::mutex mutex_;
  std::deque<Pending> queue_;
  uint64_t dropped_ = 0;  ///< readings pushed out of the full queue since the last update
  uint64_t readings_accepted_ = 0, readings_rejected_ = 0, last_accepted_ns_ = 0;  ///< for status()
  std::string last_rejection_;
  bool active_ = true;

  // Update thread only.
  std::deque<Pending> work_;
  double touched_min_x_ = 0, touched_min_y_ = 0, touched_max_x_ = 0, touched_max_y_ = 0;
  bool touched_ = false;
  uint64_t last_reading_ns_ = 0;  ///< no_readings_timeout counts from here
  ClockWatch clock_;              ///< a jump back restarts no_readings_timeout at the jump
  bool was_reset_ = false;
};
}  // namespace costmap_layers
