// rosrun costmap_layers costmap_node: a layered costmap configured by its private parameters.
//
// --move-base: run as one of move_base's costmaps (launch/move_base_costmaps.launch starts the node as
// <ns>/global_costmap): relative topic names (map, scan, ...) resolve against the namespace move_base
// itself runs in, the parent of <ns>, as costmap_2d's do inside move_base; without it they resolve
// against the node's own namespace.
#include <ros/names.h>
#include <ros/ros.h>

#include <cstring>

#include "costmap_layers/ros/costmap_node.hpp"
#include "costmap_layers/ros/program_main.hpp"

int main(int argc, char** argv)
{
  return costmap_layers_ros::runProgram(argc, argv, "costmap_node",
                                        [&]
                                        {
                                          bool move_base = false;
                                          for (int k = 1; k < argc; ++k)
                                            move_base = move_base || std::strcmp(argv[k], "--move-base") == 0;
                                          std::string topic_ns;
                                          if (move_base)
                                          {
                                            topic_ns = ros::names::parentNamespace(ros::this_node::getNamespace());
                                            ROS_INFO(
                                                "costmap_node: run as a move_base costmap: relative topics resolve "
                                                "in %s, as inside move_base",
                                                topic_ns.c_str());
                                          }
                                          try
                                          {
                                            costmap_layers_ros::CostmapNode node(ros::NodeHandle(),
                                                                                 ros::NodeHandle("~"), topic_ns);
                                            ros::AsyncSpinner spinner(2);  // callbacks while run() updates
                                            spinner.start();
                                            try
                                            {
                                              node.run();
                                            }
                                            catch (const std::exception& e)
                                            {
                                              // Said while the plugins are loaded: rosconsole is not
                                              // reliable once their libraries are unloaded.
                                              return costmap_layers_ros::reportFatal(e.what());
                                            }
                                          }
                                          catch (const costmap_layers_ros::StartupError&)
                                          {
                                            return 1;  // reported by the node while its logging still worked
                                          }
                                          return 0;
                                        });
}
