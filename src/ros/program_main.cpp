#include "costmap_layers/ros/program_main.hpp"

#include <ros/ros.h>
#include <ros/topic_manager.h>

#include <cstdio>
#include <exception>

namespace costmap_layers_ros
{
namespace
{
/// The program's own name (runProgram's default node name): the stable key of its start-up errors,
/// whatever __name:= the node runs under, as the other keys of the programs are.
std::string g_program;

std::size_t rosoutSubscribers()
{
  return ros::TopicManager::instance()->getNumSubscribers("/rosout");
}
}  // namespace

int reportFatal(const std::string& what)
{
  const std::string node = ros::this_node::getName();
  const std::string key = g_program.empty() ? node : g_program;
  if (!ros::isStarted() || ros::isShuttingDown())
  {
    // rosconsole prints nothing once roscpp is down: stderr directly, so that the line is never lost.
    std::fprintf(stderr, "[FATAL] %s: %s [%s/startup]\n", node.c_str(), what.c_str(), key.c_str());
    return 1;
  }
  // rosout connects to a new node's /rosout a few milliseconds after the node registers; a bounded wait
  // (a node run without rosout, e.g. roscore's rosout killed, still exits after 2 s).
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(2.0);
  while (rosoutSubscribers() == 0 && ros::WallTime::now() < give_up)
    ros::WallDuration(0.01).sleep();
  ROS_FATAL("%s: %s [%s/startup]", node.c_str(), what.c_str(), key.c_str());
  // The rosout appender publishes from its own thread and the link writes from roscpp's: shutting down
  // at once can drop the line that was just queued.
  if (rosoutSubscribers() > 0) ros::WallDuration(0.3).sleep();
  return 1;
}

int runProgram(int argc, char** argv, const std::string& default_name, const std::function<int()>& body,
               uint32_t init_options)
{
  int code = 1;
  g_program = default_name;
  try
  {
    ros::init(argc, argv, default_name, init_options);  // throws for a __name:= roscpp refuses
    ros::start();
    code = body();
  }
  catch (const std::exception& e)
  {
    code = reportFatal(e.what());
  }
  ros::shutdown();
  return code;
}
}  // namespace costmap_layers_ros
