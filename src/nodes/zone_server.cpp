// rosrun costmap_layers zone_server _yaml_filename:=zones.yaml [_topic:=/map_filter] [_markers:=true]
// Zones drawn as polygons and circles, served as a latched mask; edited through services and RViz's
// interactive markers, saved back to the file (include/costmap_layers/ros/zone_server.hpp).
#include <ros/ros.h>

#include "costmap_layers/ros/zone_server.hpp"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "zone_server");
  const std::string node = ros::this_node::getName();
  std::unique_ptr<costmap_layers_ros::ZoneServer> server;
  try
  {
    ros::NodeHandle nh, pnh("~");
    server =
        std::make_unique<costmap_layers_ros::ZoneServer>(nh, pnh, costmap_layers_ros::ZoneServer::readOptions(pnh));
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("%s: %s [%s/parameters]", node.c_str(), e.what(), node.c_str());
    return 1;
  }
  ros::spin();
  return 0;
}
