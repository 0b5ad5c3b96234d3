// rosrun costmap_layers mask_server _yaml_filename:=keepout.yaml _topic:=/map_filter [_frame_id:=map]
//     [_pixel_rule:=ros1|nav2] [_mode:=trinary|scale|raw|nav2_scale]
// Loads a map_server map file and publishes it latched as a nav_msgs/OccupancyGrid: what map_server
// does, for maps and masks. Nav2's filter_mask_server parameters (`topic_name`, `yaml_filename`,
// `frame_id`, from a Nav2 parameter file without its `ros__parameters:` level, loaded at the top level
// or with ns="<node name>") work as they are.
//
// Pixel rule (map_file.hpp has both): `mode: scale` in the YAML is read with ROS 1 map_server's rule
// (~pixel_rule: ros1) or Nav2's (~pixel_rule: nav2). The default is nav2 when the node is given Nav2's
// parameter name `topic_name` (a Nav2 mask), else ros1. trinary and raw are read with ROS 1's rule
// (Nav2's trinary differs only for a pixel exactly at a threshold). ~mode overrides the YAML's mode.
//
// Once loaded, the node logs what it publishes: size, resolution, origin, frame, mode, pixel rule and
// the count of each value (or a histogram), and warns when the values look like an image drawn for the
// other pixel rule. Log lines end with a stable key, "[mask_server/<key>]".
#include <nav_msgs/OccupancyGrid.h>
#include <ros/ros.h>

#include <cmath>
#include <stdexcept>

#include "costmap_layers/io/map_file.hpp"
#include "costmap_layers/io/mask_summary.hpp"
#include "costmap_layers/ros/node_params.hpp"
#include "costmap_layers/ros/program_main.hpp"

namespace io = costmap_layers::io;

namespace
{
int run()
{
  ros::NodeHandle nh, pnh("~");
  const std::string node = ros::this_node::getName();
  nav_msgs::OccupancyGrid msg;
  std::string yaml, topic, frame, rule;
  io::MapMode mode = io::MapMode::Trinary;
  {
    const costmap_layers_ros::NodeParams params(pnh);
    const std::string& at = params.where();
    if (params.nested())
      ROS_INFO("%s: reading the parameters under %s [mask_server/namespace]", node.c_str(), at.c_str());
    params.warnUseSimTime(node, "mask_server");
    for (const auto& key :
         params.unknownKeys({"yaml_filename", "topic", "topic_name", "frame_id", "mode", "pixel_rule"}))
      ROS_WARN(
          "%s: parameter %s%s is not one of yaml_filename, topic (or Nav2's topic_name), frame_id, mode, "
          "pixel_rule: ignored [mask_server/unknown]",
          node.c_str(), at.c_str(), key.c_str());
    yaml = params.getFile("yaml_filename");
    const bool nav2_form = params.has("topic_name");
    if (nav2_form && params.has("topic"))
      throw std::invalid_argument("parameters " + at + "topic (\"" + params.getString("topic", "") + "\") and " + at +
                                  "topic_name (\"" + params.getString("topic_name", "") +
                                  "\", Nav2's name) are both set: set one");
    // Nav2's map_server defaults to "map"; this node, serving masks, to /map_filter.
    topic = nav2_form ? params.getTopic("topic_name", "map") : params.getTopic("topic", "/map_filter");
    frame = params.getFrameId("frame_id", "map");
    rule = params.getString("pixel_rule", nav2_form ? "nav2" : "ros1");
    if (rule != "ros1" && rule != "nav2")
      throw std::invalid_argument("parameter " + at + "pixel_rule must be \"ros1\" or \"nav2\" (got \"" + rule + "\")");
    const std::string mode_name = params.getString("mode", "");  // overrides the file's mode when set

    io::MapFileInfo info;
    try
    {
      info = io::loadMapFileInfo(yaml);
    }
    catch (const std::exception& e)
    {
      throw std::runtime_error("parameter " + at + "yaml_filename: " + e.what());
    }
    mode = mode_name.empty() ? info.mode : io::parseMapMode(mode_name);
    if (rule == "nav2" && mode == io::MapMode::Scale) mode = io::MapMode::Nav2Scale;
    if (rule == "ros1" && mode == io::MapMode::Nav2Scale && params.has("pixel_rule"))
      throw std::invalid_argument("parameter " + at + "pixel_rule is \"ros1\" but the mode is nav2_scale (" +
                                  (mode_name.empty() ? "in " + yaml : at + "mode") + "): set one rule");
    const costmap_layers::OccupancyGridData grid = io::loadMapImage(info.image_path,
                                                                    [&]
                                                                    {
                                                                      io::MapFileInfo i = info;
                                                                      i.mode = mode;
                                                                      return i;
                                                                    }());
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

    const auto counts = io::countValues(grid);
    ROS_INFO(
        "%s: loaded %s: %ux%u cells at %g m/cell, origin (%g, %g, %g), frame %s, mode %s, pixel rule %s; "
        "values: %s [mask_server/loaded]",
        node.c_str(), yaml.c_str(), grid.width, grid.height, grid.resolution, grid.origin_x, grid.origin_y,
        grid.origin_yaw, frame.c_str(), io::mapModeName(mode), io::pixelRuleDescription(mode).c_str(),
        io::describeValues(counts).c_str());
    const std::string warning = io::pixelRuleWarning(counts, mode);
    if (!warning.empty()) ROS_WARN("%s: %s: %s [mask_server/pixel_rule]", node.c_str(), yaml.c_str(), warning.c_str());
  }
  ros::Publisher pub = nh.advertise<nav_msgs::OccupancyGrid>(topic, 1, true);
  pub.publish(msg);
  ROS_INFO("%s: publishing %s on %s [mask_server/published]", node.c_str(), yaml.c_str(), pub.getTopic().c_str());
  ros::spin();
  return 0;
}
}  // namespace

int main(int argc, char** argv)
{
  return costmap_layers_ros::runProgram(argc, argv, "mask_server", [] { return run(); });
}
