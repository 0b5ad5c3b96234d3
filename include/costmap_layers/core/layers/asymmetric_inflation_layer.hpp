// Nav2's AsymmetricInflationLayer: the InflationLayer's exact inflation, with the cost falling off more
// slowly from obstacles on one side of the robot's planned path than from those on the other, so that a
// robot keeps to one side of a corridor. As in Nav2:
//  - every cell first gets the symmetric inflation with the larger factor, max(left, right);
//  - the side of an obstacle cell is the side (sign of the cross product) of the plan segment nearest to
//    it, when that segment is within inflation_radius of it (else, or on the segment's line, no side);
//  - the boundary obstacle cells (on the map's edge or with a free 4-neighbour) on the side whose factor
//    is smaller are the sources of a second inflation with that smaller factor, merged by maximum;
//  - there is no asymmetry without a plan of two poses or more, with equal factors, or while the robot is
//    within goal_distance_threshold of the plan's last pose.
// Distances are the distance engine's exact ones (Nav2 quantises them to 1/100 cell).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "costmap_layers/core/data/path_data.hpp"
#include "costmap_layers/core/layers/inflation_layer.hpp"

namespace costmap_layers
{
class ParamReader;

struct AsymmetricInflationConfig
{
  /// inflation_radius (Nav2's default here is 2.0 m), inflate_unknown, inflate_around_unknown,
  /// num_threads; cost_scaling_factor is max(left, right), not a parameter.
  InflationConfig inflation;
  double cost_scaling_factor_left = 4.0;   ///< [1/m] the fall-off left of the plan
  double cost_scaling_factor_right = 4.0;  ///< [1/m] the fall-off right of the plan
  std::string plan_topic = "plan";         ///< nav_msgs/Path
  double goal_distance_threshold = 1.5;    ///< [m] no asymmetry this close to the plan's last pose
};

/// Reads Nav2's parameters (inflation_radius, cost_scaling_factor_left/_right >= 0,
/// goal_distance_threshold >= 0, plan_topic, inflate_unknown, inflate_around_unknown, num_threads).
/// Throws std::invalid_argument naming the parameter.
AsymmetricInflationConfig parseAsymmetricInflationConfig(const ParamReader& params);

/// Which side of a path a point lies on, seen along the path's direction.
enum class PathSide : int8_t
{
  Right = -1,
  None = 0,
  Left = 1
};

/// One straight piece of a path, from a to b [m].
struct PathSegment
{
  double ax = 0, ay = 0, bx = 0, by = 0;
};

/// Nav2's rule for one point against the given segments (in this order): the nearest segment (the first
/// of equally near ones) decides by the sign of its cross product (b - a) x (p - a); no side when it is
/// farther than `radius`, when the point is on its line, or when it is shorter than 1 mm.
PathSide sideOfSegments(const PathSegment* segments, const uint32_t* indices, std::size_t count, double radius,
                        double x, double y);

/// The segments near each part of a rectangle, so that sideOfSegments() looks at a few of them only:
/// square buckets at least `radius` wide, each listing (in path order) every segment that comes within
/// `radius` of it. The index holds its own copy of the segments (a caller's vector may go away or change
/// after build()); buffers are kept between builds.
class PathSideIndex
{
public:
  /// Indexes `segments` over [x0, x1] x [y0, y1]. Fails (false, the index then answers None everywhere)
  /// when more than max_entries bucket entries would be needed: a plan crossing the area very many times.
  bool build(const std::vector<PathSegment>& segments, double radius, double x0, double y0, double x1, double y1,
             std::size_t max_entries);
  /// The side of (x, y), a point of the rectangle.
  PathSide side(double x, double y) const;
  /// Bucket entries of the last build.
  std::size_t entries() const { return indices_.size(); }

private:
  std::vector<PathSegment> segments_;  ///< the segments of the last build, indices_ point into them
  double radius_ = 0, x0_ = 0, y0_ = 0, size_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<uint32_t> first_;    ///< per bucket, where its list starts in indices_ (and one past the end)
  std::vector<uint32_t> indices_;  ///< the lists, bucket after bucket
  std::vector<uint32_t> count_;    ///< scratch of build()
};

class AsymmetricInflationLayer : public InflationLayer
{
public:
  void updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y, double* max_x,
                    double* max_y) override;
  void updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j) override;
  LayerStatus status() const override;

  const AsymmetricInflationConfig& asymmetricConfig() const { return config_; }
  /// Hands a plan over, as the plan input does (any thread). A plan is refused (an error naming the field
  /// and its value, the previous plan kept) when it has fewer than two poses, more than
  /// limits::kMaxPathPoses, a pose not finite or beyond limits::kMaxCoordinate, or no frame.
  /// Returns the error, empty when taken.
  std::string setPlan(const std::shared_ptr<const PathData>& plan);
  /// Whether the last updateBounds() found the asymmetry in force.
  bool asymmetryActive() const { return active_; }
  /// The plan's segments in the global frame near the costmap, as the last updateBounds() found them.
  const std::vector<PathSegment>& segments() const { return segments_; }

  /// The most bucket entries a plan may need (PathSideIndex): 4 M entries, 16 MB.
  static constexpr std::size_t kMaxIndexEntries = std::size_t{1} << 22;

protected:
  void onInitialize() override;
  void onReconfigure(const ParamValue& params) override;
  std::vector<ParamSpec> tunableLayerParameters(const ParamValue& params) const override;

private:
  /// Why there is no asymmetry this cycle (None: there is).
  enum class Off
  {
    None,
    NoPlan,
    EqualFactors,
    NearGoal,
    NoTransform,
    TooManyEntries
  };
  /// The plan in the global frame, culled to the costmap, and whether the asymmetry applies.
  Off preparePlan(double robot_x, double robot_y);
  /// The table of the smaller factor, rebuilt when its inputs changed.
  void rebuildSideTable(double resolution);

  AsymmetricInflationConfig config_;
  std::string plan_topic_;  ///< set once at initialisation: read by the plan handler on any thread

  mutable std::mutex plan_mutex_;
  std::shared_ptr<const PathData> plan_;  ///< the last plan taken
  uint64_t plan_generation_ = 0;          ///< counts plans taken

  // Update thread only.
  bool active_ = false;
  Off off_ = Off::NoPlan;
  bool said_no_plan_ = false;
  uint64_t used_generation_ = UINT64_MAX;
  Transform2D used_transform_;
  std::array<double, 4> used_rect_{};  ///< the costmap's extent the segments were culled to
  bool index_ok_ = false;
  std::vector<PathSegment> segments_;
  PathSideIndex index_;
  TableKey side_key_;  ///< what side_costs_ was built for (the InflationLayer's key)
  DistanceCosts side_costs_;
  DistanceTransformScratch side_scratch_;
  std::vector<uint8_t> seeds_;  ///< 1 where a disfavoured-side boundary obstacle cell is, over the padded window
};
}  // namespace costmap_layers
