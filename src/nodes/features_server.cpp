// rosrun costmap_layers features_server _yaml_filename:=speed_limits.yaml [_topic:=/features] [_frame_id:=map]
// Loads `limits: [{area_id: 1, max_speed: 0.5}, ...]` and publishes it latched as SpeedLimits.
#include <ros/ros.h>

#include <stdexcept>

#include "costmap_layers/SpeedLimits.h"
#include "costmap_layers/io/features_file.hpp"
#include "costmap_layers/ros/node_params.hpp"
#include "costmap_layers/ros/program_main.hpp"

namespace
{
int run()
{
  ros::NodeHandle nh, pnh("~");
  const std::string node = ros::this_node::getName();
  const costmap_layers_ros::NodeParams params(pnh);
  for (const auto& key : params.unknownKeys({"yaml_filename", "topic", "frame_id"}))
    ROS_WARN("%s: parameter %s%s is not one of yaml_filename, topic, frame_id: ignored [features_server/unknown]",
             node.c_str(), params.where().c_str(), key.c_str());
  const std::string yaml = params.getFile("yaml_filename");
  const std::string topic = params.getTopic("topic", "/features");
  const std::string frame = params.getFrameId("frame_id", "map");
  costmap_layers::SpeedLimits msg;
  costmap_layers::SpeedLimitsData data;
  try
  {
    data = costmap_layers::io::loadFeaturesFile(yaml);
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error("parameter " + params.where() + "yaml_filename: " + e.what());
  }
  // Published as written (each SpeedFilter drops a bad entry and keeps the rest, saying so); said here
  // too, where the file is.
  for (const auto& line : costmap_layers::io::featuresFileProblems(data))
  {
    if (line.rfind("error", 0) == 0)
      ROS_ERROR("features_server: %s: %s", yaml.c_str(), line.c_str());
    else
      ROS_WARN("features_server: %s: %s", yaml.c_str(), line.c_str());
  }
  for (const auto& entry : data.limits)
  {
    costmap_layers::SpeedLimit limit;
    limit.area_id = entry.area_id;
    limit.max_speed = entry.max_speed;
    msg.limits.push_back(limit);
  }
  msg.header.frame_id = frame;
  msg.header.stamp = ros::Time::now();
  ros::Publisher pub = nh.advertise<costmap_layers::SpeedLimits>(topic, 1, true);
  pub.publish(msg);
  ROS_INFO("features_server: publishing %zu speed limits from %s on %s", msg.limits.size(), yaml.c_str(),
           pub.getTopic().c_str());
  ros::spin();
  return 0;
}
}  // namespace

int main(int argc, char** argv)
{
  return costmap_layers_ros::runProgram(argc, argv, "features_server", [] { return run(); });
}
