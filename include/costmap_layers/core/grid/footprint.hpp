// Robot footprints as costmap_2d builds them: a polygon in the robot frame [m], or a 16-gon from a
// radius, padded outward, with its inscribed and circumscribed radii.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace costmap_layers
{
class ParamReader;

using Footprint = std::vector<Eigen::Vector2d>;

/// The 16-gon costmap_2d makes for a circular robot of the given radius [m].
Footprint makeFootprintFromRadius(double radius);
/// Moves every vertex outward by padding [m] along x and y (costmap_2d's padFootprint).
void padFootprint(Footprint& footprint, double padding);
/// Smallest distance from the origin to an edge (inscribed radius) and largest to a vertex
/// (circumscribed radius) [m].
void calculateMinAndMaxDistances(const Footprint& footprint, double& min_dist, double& max_dist);
/// Parses "[[x1, y1], [x2, y2], ...]". Throws std::invalid_argument naming the text on error, and
/// when there are fewer than 3 points or a value is not finite.
Footprint parseFootprintString(const std::string& text);
/// What makes a polygon unusable as a footprint, or "" when it is not: fewer than 3 points, a vertex
/// that is not finite, or one farther than limits::kMaxDistance from the robot's centre (the message
/// names the vertex and its values).
std::string footprintProblem(const Footprint& footprint);
/// The footprint moved to the pose (x, y, yaw) [m, rad].
Footprint transformFootprint(double x, double y, double yaw, const Footprint& footprint);

/// Footprint settings with costmap_2d's names and defaults.
struct FootprintConfig
{
  Footprint footprint;              ///< unpadded, robot frame [m]; empty means "use robot_radius"
  double robot_radius = 0.46;       ///< [m]
  double footprint_padding = 0.01;  ///< [m]

  /// The padded polygon the costmap uses.
  Footprint padded() const;
};

/// Reads footprint (a string or a list of [x, y] pairs), robot_radius and footprint_padding.
FootprintConfig parseFootprintConfig(const ParamReader& params);
}  // namespace costmap_layers
