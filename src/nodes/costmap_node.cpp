// rosrun costmap_layers costmap_node: a layered costmap configured by its private parameters.
#include <ros/ros.h>

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
  catch (const std::exception& e)
  {
    ROS_FATAL("costmap_node: %s", e.what());
    return 1;
  }
  return 0;
}
