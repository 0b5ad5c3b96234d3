// rosrun costmap_layers costmap_node: a layered costmap configured by its private parameters.
//
// --move-base: run as one of move_base's costmaps (launch/move_base_costmaps.launch starts the node as
// <ns>/global_costmap): relative topic names (map, scan, ...) resolve against the namespace move_base
// itself runs in, the parent of <ns>, as costmap_2d's do inside move_base; without it they resolve
// against the node's own namespace.
#include <ros/names.h>
#include <ros/ros.h>

#include <cstring>
#include <iostream>

#include "costmap_layers/ros/costmap_node.hpp"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "costmap_node");
  try
  {
    bool move_base = false;
    for (int k = 1; k < argc; ++k)
      move_base = move_base || std::strcmp(argv[k], "--move-base") == 0;
    std::string topic_ns;
    if (move_base)
    {
      topic_ns = ros::names::parentNamespace(ros::this_node::getNamespace());
      ROS_INFO("costmap_node: run as a move_base costmap: relative topics resolve in %s, as inside move_base",
               topic_ns.c_str());
    }
    costmap_layers_ros::CostmapNode node(ros::NodeHandle(), ros::NodeHandle("~"), topic_ns);
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
