// rosrun costmap_layers costmap_node: a layered costmap configured by its private parameters.
#include <ros/ros.h>

#include <iostream>

#include "costmap_layers/ros/costmap_node.hpp"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "costmap_node");
  try
  {
    costmap_layers_ros::CostmapNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::AsyncSpinner spinner(2);  // topic and service callbacks, while run() updates the map
    spinner.start();
    node.run();
  }
  catch (const costmap_layers_ros::StartupError&)
  {
    return 1;  // already reported by the node, while its logging still worked
  }
  catch (const std::exception& e)
  {
    // rosconsole may no longer print once the plugin library is unloaded: write to stderr directly.
    std::cerr << "costmap_node: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
