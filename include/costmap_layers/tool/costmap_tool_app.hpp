// costmap_tool: the offline twin of costmap_node. It builds the same LayeredCostmap from the same
// params YAML through the same plugin loading, feeds files where the node gets topics, runs updates
// and writes the result. No ROS master is needed.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace costmap_layers_ros
{
/// Runs the tool with its command-line arguments (without the program name). Diagnostics go to err;
/// the last line on out is one JSON object. @return the process exit code (0 on success).
int runCostmapTool(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
}  // namespace costmap_layers_ros
