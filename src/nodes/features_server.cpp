// rosrun costmap_layers features_server _yaml_filename:=speed_limits.yaml [_topic:=/features] [_frame_id:=map]
// Loads `limits: [{area_id: 1, max_speed: 0.5}, ...]` and publishes it latched as SpeedLimits.
#include <ros/ros.h>

#include "costmap_layers/SpeedLimits.h"
#include "costmap_layers/io/features_file.hpp"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "features_server");
  ros::NodeHandle nh, pnh("~");
  const std::string yaml = pnh.param<std::string>("yaml_filename", "");
  const std::string topic = pnh.param<std::string>("topic", "/features");
  const std::string frame = pnh.param<std::string>("frame_id", "map");
  if (yaml.empty())
  {
    ROS_FATAL("features_server: parameter ~yaml_filename is not set");
    return 1;
  }
  costmap_layers::SpeedLimits msg;
  try
  {
    const costmap_layers::SpeedLimitsData data = costmap_layers::io::loadFeaturesFile(yaml);
    // Published as written (each SpeedFilter drops a bad entry and keeps the rest, saying so); said
    // here too, where the file is.
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
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("features_server: %s", e.what());
    return 1;
  }
  msg.header.frame_id = frame;
  msg.header.stamp = ros::Time::now();
  ros::Publisher pub = nh.advertise<costmap_layers::SpeedLimits>(topic, 1, true);
  pub.publish(msg);
  ROS_INFO("features_server: publishing %zu speed limits from %s on %s", msg.limits.size(), yaml.c_str(),
           topic.c_str());
  ros::spin();
  return 0;
}
