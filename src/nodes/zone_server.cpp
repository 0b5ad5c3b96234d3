// rosrun costmap_layers zone_server _yaml_filename:=zones.yaml [_topic:=/map_filter] [_markers:=true]
//   [_save_directory:=<folder ~save and ~load may name files in; default: the zone file's folder>]
//   [_publish_rate:=10 (Hz, the most masks published a second while handles are dragged)]
// Zones drawn as polygons and circles, served as a latched mask; edited through services and RViz's
// interactive markers, saved back to the file (include/costmap_layers/ros/zone_server.hpp).
#include <ros/ros.h>

#include "costmap_layers/ros/program_main.hpp"
#include "costmap_layers/ros/zone_server.hpp"

int main(int argc, char** argv)
{
  return costmap_layers_ros::runProgram(argc, argv, "zone_server",
                                        []
                                        {
                                          ros::NodeHandle nh, pnh("~");
                                          costmap_layers_ros::ZoneServer server(
                                              nh, pnh, costmap_layers_ros::ZoneServer::readOptions(pnh));
                                          ros::spin();
                                          return 0;
                                        });
}
