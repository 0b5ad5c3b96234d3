// costmap_2d's ObstacleLayer: LaserScan and PointCloud2 sources mark obstacles and clear the free
// space along the rays from each sensor origin. Readings arrive on the host's threads: they are
// validated, projected into the global frame and height-filtered there, then buffered per source
// (ObservationBuffer). updateBounds (update thread) clears along every ray of the clearing observations,
// then marks the hits of the marking observations, then (optionally) clears the robot's footprint.
// The per-observation work is virtual so that VoxelLayer replaces only the grid it works on.
#pragma once

#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "costmap_layers/core/costmap/costmap_layer.hpp"
#include "costmap_layers/core/data/sensor_data.hpp"
#include "costmap_layers/core/grid/footprint.hpp"
#include "costmap_layers/core/layers/observation_buffer.hpp"

namespace costmap_layers
{
class ParamReader;

enum class SensorDataType
{
  LaserScan,
  PointCloud2,
  PointCloud  ///< sensor_msgs/PointCloud, the older type (costmap_2d's default)
};

/// The data_type value that names it: "LaserScan", "PointCloud2" or "PointCloud".
const char* sensorDataTypeName(SensorDataType type);

/// One entry of observation_sources, read from the sub-namespace named after it.
struct ObservationSourceConfig
{
  std::string name;
  std::string topic;                                       ///< default: the source name
  std::string sensor_frame;                                ///< "" = the reading's own frame
  double observation_persistence = 0.0;                    ///< [s] 0 = only the newest reading
  double expected_update_rate = 0.0;                       ///< [s] a period, see ObservationBufferConfig; 0 = unchecked
  SensorDataType data_type = SensorDataType::PointCloud2;  ///< "LaserScan", "PointCloud2" or "PointCloud"
  double min_obstacle_height = 0.0;  ///< [m] global z; points outside are dropped (also for clearing)
  double max_obstacle_height = 2.0;  ///< [m]
  bool inf_is_valid = false;         ///< LaserScan +inf = no return up to range_max (clears only)
  bool marking = true;
  bool clearing = false;
  double obstacle_min_range = 0.0;         ///< [m] 3-D distance from the sensor origin, inclusive
  double obstacle_max_range = 2.5;         ///< [m] inclusive; the old name obstacle_range is accepted
  double raytrace_min_range = 0.0;         ///< [m] cells nearer to the origin are not cleared
  double raytrace_max_range = 3.0;         ///< [m] rays are cut there; the old name raytrace_range is accepted
  double observation_keep_distance = 0.0;  ///< [m] 0 = off, see ObservationBufferConfig
};

struct ObstacleConfig
{
  bool footprint_clearing_enabled = true;
  /// [m] hits below are never marked: Nav2's layer-level limit (costmap_2d has none: -infinity unless
  /// set; a layer typed nav2_costmap_2d:: gets Nav2's 0.0 from applyCostmap2dRules).
  double min_obstacle_height = -std::numeric_limits<double>::infinity();
  double max_obstacle_height = 2.0;  ///< [m] hits above are never marked
  /// Whether a hit at height z may be marked (the layer's limits; each source has its own too).
  bool marksHeight(double z) const { return z >= min_obstacle_height && z <= max_obstacle_height; }
  /// 0: overwrite (own cost unless unknown), 1: max, 2: max without overwriting unknown master cells,
  /// 99: nothing (costmap_2d's "Do nothing").
  int combination_method = 1;
  bool track_unknown_space = false;  ///< default: the costmap's
  std::vector<ObservationSourceConfig> sources;
};

/// Reads one source from its own namespace. Throws std::invalid_argument naming the parameter.
ObservationSourceConfig parseObservationSourceConfig(const ParamReader& params, const std::string& name);
/// Reads footprint_clearing_enabled, min_obstacle_height, max_obstacle_height, combination_method (0, 1, 2 or 99),
/// track_unknown_space and observation_sources (a space-separated string or a list of names; each
/// name's parameters in the sub-namespace of that name). Throws std::invalid_argument.
ObstacleConfig parseObstacleConfig(const ParamReader& params, bool default_track_unknown);

class ObstacleLayer : public CostmapLayer
{
public:
  void updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y, double* max_x,
                    double* max_y) override;
  void updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j) override;
  /// Clears the grid and every buffered observation (static ones included).
  void reset() override;
  /// Accepts readings again and restarts the update-rate checks.
  void activate() override;
  /// Ignores readings until activate().
  void deactivate() override;
  bool isClearable() override { return true; }
  void matchSize() override;

  const ObstacleConfig& config() const { return config_; }
  std::size_t sourceCount() const { return buffers_.size(); }
  const ObservationBuffer& buffer(std::size_t source) const { return *buffers_.at(source); }
  /// Per source: readings accepted and rejected, the age of the last one, expected_update_rate. WARN
  /// for each source that is late (ObservationBuffer::isCurrent()) or whose every reading was rejected.
  LayerStatus status() const override;

  /// What the subscriptions call (safe from any thread): validates and projects a reading of source
  /// `source` into the global frame and buffers it. A reading stamped more than
  /// kFutureStampToleranceNs ahead of now is refused. @return "" when buffered, else the reason (also
  /// reported as a Warn naming the source).
  std::string addLaserScan(std::size_t source, const LaserScanData& scan, const SensorPose& pose);
  std::string addPointCloud2(std::size_t source, const PointCloud2Data& cloud, const SensorPose& pose);
  /// Observations that never expire (costmap_2d's addStaticObservation), for tests and tools.
  void addStaticObservation(const Observation& observation, bool marking, bool clearing);
  void clearStaticObservations(bool marking, bool clearing);

protected:
  void onInitialize() override;

  /// The rolling window's own grid moved by this many cells (VoxelLayer moves its columns with it).
  virtual void onGridShifted(int /*cells_x*/, int /*cells_y*/) {}
  /// Clears the cells from the observation's origin towards each of its points.
  virtual void raytraceFreespace(const Observation& observation, double* min_x, double* min_y, double* max_x,
                                 double* max_y);
  /// Marks the observation's hits within its obstacle ranges and max_obstacle_height.
  virtual void markObservation(const Observation& observation, double* min_x, double* min_y, double* max_x,
                               double* max_y);

  /// Where a ray from the origin to (wx, wy) ends once cut at max_range and at the grid's border:
  /// the fraction t in [0, 1] of the way. False when the origin is outside the grid.
  bool clipRay2D(double ox, double oy, double wx, double wy, double max_range, double& t) const;
  /// Whether a hit marks: within max_obstacle_height (and the layer's minimum), within the
  /// observation's obstacle ranges from its origin, and inside the grid, whose cell it returns.
  bool marksPoint(const Observation& observation, const Point3f& p, unsigned int& mx, unsigned int& my) const;
  /// The source index used in report keys and messages.
  std::string sourceLabel(std::size_t source) const;
  /// Reports what the buffers dropped by themselves since the last call: a clock jump back (once for
  /// all sources) and, per source, the readings a flood pushed out.
  void reportClockJump();

  ObstacleConfig config_;

private:
  /// Why a valid reading of `source` stamped stamp_ns cannot be buffered at now_ns ("" when it can):
  /// stamped ahead of now, or older than the source's persistence (reported).
  std::string refuseStamp(std::size_t source, uint64_t stamp_ns, uint64_t now_ns);
  /// An empty observation of `source` (from the pool) at `pose`, stamped stamp_ns (or now_ns).
  std::shared_ptr<Observation> startObservation(std::size_t source, uint64_t stamp_ns, uint64_t now_ns,
                                                const SensorPose& pose);
  /// Reports a reading the parser refused; returns the reason.
  std::string refuseReading(std::size_t source, const std::string& error);

  /// Records what happened to one reading of `source` for status(); returns result.
  std::string noteReading(std::size_t source, std::string result);

  std::vector<std::unique_ptr<ObservationBuffer>> buffers_;
  /// Where readings are projected into: no allocation per reading once the sensors run.
  std::shared_ptr<ObservationPool> pool_ = ObservationPool::make();
  struct SourceCounts
  {
    uint64_t accepted = 0, rejected = 0;
    uint64_t last_accepted_ns = 0;
    std::string last_rejection;
  };
  mutable std::mutex counts_mutex_;
  std::vector<SourceCounts> counts_;  ///< per source, guarded by counts_mutex_
  std::atomic<bool> active_{true};

  std::mutex static_mutex_;
  std::vector<std::shared_ptr<const Observation>> static_marking_, static_clearing_;

  // Update thread only; kept between cycles so that a cycle allocates nothing once warm.
  std::vector<std::shared_ptr<const Observation>> marking_, clearing_, scratch_;
  /// The cells where the rays of the observation being traced ended: one bit per cell, and the list of
  /// the bits set, so that starting over costs what the last observation set.
  class CellSet
  {
  public:
    void reset(std::size_t cells)
    {
      if (bits_.size() != (cells + 63) / 64)
      {
        bits_.assign((cells + 63) / 64, 0);
        set_.clear();
      }
      for (const std::size_t w : set_)
        bits_[w] = 0;
      set_.clear();
    }
    bool test(std::size_t cell) const { return (bits_[cell / 64] >> (cell % 64)) & 1u; }
    void set(std::size_t cell)
    {
      uint64_t& w = bits_[cell / 64];
      if (w == 0) set_.push_back(cell / 64);
      w |= uint64_t{1} << (cell % 64);
    }

  private:
    std::vector<uint64_t> bits_;
    std::vector<std::size_t> set_;  ///< the words with a bit set
  };
  CellSet ray_ends_;
  Footprint transformed_footprint_;
};
}  // namespace costmap_layers
