// Nav2's Costmap2DROS defaults where they differ from costmap_2d's (which are this package's), for a
// namespace read from a Nav2 file. The defaults of Nav2's layer types (min_obstacle_height, an
// observation source's data_type) come with their type names, in applyCostmap2dRules().
#pragma once

#include "costmap_layers/core/config/costmap2d_rules.hpp"

namespace costmap_layers
{
/// Sets each of publish_frequency, width, height and resolution that r.params lacks to Nav2's default,
/// and robot_radius when neither it nor a polygon footprint is set; each one taken is said in r.notes.
void applyNav2CostmapDefaults(CompatResult& r);
}  // namespace costmap_layers
