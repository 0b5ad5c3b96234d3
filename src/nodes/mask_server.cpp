// rosrun costmap_layers mask_server _yaml_filename:=keepout.yaml _topic:=/map_filter [_frame_id:=map]
// Loads a map_server map file (trinary, scale, raw, or nav2_scale for masks authored with Nav2's rule)
// and publishes it latched as a nav_msgs/OccupancyGrid: what map_server does, for maps and masks.
#include <nav_msgs/OccupancyGrid.h>
#include <ros/ros.h>

#include <cmath>
#include <stdexcept>

#include "costmap_layers/io/map_file.hpp"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "mask_server");
  ros::NodeHandle nh, pnh("~");
  const std::string yaml = pnh.param<std::string>("yaml_filename", "");
  const std::string topic = pnh.param<std::string>("topic", "/map_filter");
  const std::string frame = pnh.param<std::string>("frame_id", "map");
  const std::string mode = pnh.param<std::string>("mode", "");  // overrides the file's mode when set
  if (yaml.empty())
  {
    ROS_FATAL("mask_server: parameter ~yaml_filename is not set");
    return 1;
  }
  nav_msgs::OccupancyGrid msg;
  try
  {
    std::optional<costmap_layers::io::MapMode> override_mode;
    if (!mode.empty()) override_mode = costmap_layers::io::parseMapMode(mode);
    const costmap_layers::OccupancyGridData grid = costmap_layers::io::loadMapFile(yaml, override_mode);
    msg.header.frame_id = frame;
    msg.header.stamp = ros::Time::now();
    msg.info.map_load_time = msg.header.stamp;
    // The loader keeps resolution in [kMinResolution, kMaxResolution], both normal float32 numbers;
    // checked again on the float the message carries, which must never be 0 or inf.
    msg.info.resolution = static_cast<float>(grid.resolution);
    if (!(msg.info.resolution > 0.0f) || !std::isfinite(msg.info.resolution))
      throw std::runtime_error(yaml + ": resolution " + std::to_string(grid.resolution) +
                               " is not representable as a float32 > 0");
    msg.info.width = grid.width;
    msg.info.height = grid.height;
    msg.info.origin.position.x = grid.origin_x;
    msg.info.origin.position.y = grid.origin_y;
    msg.info.origin.orientation.z = std::sin(grid.origin_yaw / 2.0);
    msg.info.origin.orientation.w = std::cos(grid.origin_yaw / 2.0);
    msg.data.assign(grid.data.begin(), grid.data.end());
  }
  catch (const std::exception& e)
  {
    ROS_FATAL("mask_server: %s", e.what());
    return 1;
  }
  ros::Publisher pub = nh.advertise<nav_msgs::OccupancyGrid>(topic, 1, true);
  pub.publish(msg);
  ROS_INFO("mask_server: publishing %s (%ux%u at %.3f m) on %s in frame %s", yaml.c_str(), msg.info.width,
           msg.info.height, msg.info.resolution, topic.c_str(), frame.c_str());
  ros::spin();
  return 0;
}
