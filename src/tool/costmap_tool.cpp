// rosrun costmap_layers costmap_tool ...: the offline twin of costmap_node (no ROS master needed).
#include <iostream>

#include "costmap_layers/tool/costmap_tool_app.hpp"

int main(int argc, char** argv)
{
  return costmap_layers_ros::runCostmapTool(std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr);
}
