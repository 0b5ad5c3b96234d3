// rosrun costmap_layers costmap_snapshot _topic:=/costmap_node/costmap _output:=costmap.png
// Waits for an OccupancyGrid (applying OccupancyGridUpdates that follow it), writes it as a PNG with a
// legend after ~wait seconds of updates, and exits. Used by the demo and the tests.
#include <map_msgs/OccupancyGridUpdate.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/ros.h>

#include <cstdint>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "costmap_layers/core/filters/costmap_filter.hpp"
#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/io/png_writer.hpp"
#include "costmap_layers/ros/conversions.hpp"
#include "costmap_layers/ros/node_params.hpp"
#include "costmap_layers/ros/program_main.hpp"

namespace
{
int run()
{
  ros::NodeHandle nh, pnh("~");
  const costmap_layers_ros::NodeParams params(pnh);
  for (const auto& key : params.unknownKeys({"topic", "output", "wait", "timeout"}))
    ROS_WARN("costmap_snapshot: parameter %s%s is not one of topic, output, wait, timeout: ignored",
             params.where().c_str(), key.c_str());
  const std::string topic = params.getTopic("topic", "/costmap_node/costmap");
  const std::string output = params.getString("output", "costmap.png");
  if (output.empty()) throw std::invalid_argument("parameter " + params.where() + "output is empty (a PNG file name)");
  // Both in wall time: under /use_sim_time a stopped or absent /clock must not hang the tool. NaN and
  // infinities are refused (either would make a wait endless).
  const double wait = params.getDoubleIn("wait", 0.0, 0.0,
                                         costmap_layers::limits::kMaxDuration);  // [s] of updates after the first grid
  const double timeout =
      params.getDoubleIn("timeout", 30.0, 0.0, costmap_layers::limits::kMaxDuration);  // [s] for the first grid

  std::mutex mutex;
  nav_msgs::OccupancyGrid grid;
  bool have_grid = false;
  ros::SteadyTime first;
  auto sub = nh.subscribe<nav_msgs::OccupancyGrid>(
      topic, 1,
      [&](const nav_msgs::OccupancyGrid::ConstPtr& msg)
      {
        // Sizes checked before any cell is touched.
        std::string error;
        try
        {
          error = costmap_layers::validateGrid(costmap_layers_ros::fromMsg(*msg)).message;
        }
        catch (const std::exception& e)
        {
          error = e.what();
        }
        if (!error.empty())
        {
          ROS_ERROR_THROTTLE(5.0, "costmap_snapshot: grid on %s dropped: %s", topic.c_str(), error.c_str());
          return;
        }
        std::lock_guard<std::mutex> lock(mutex);
        grid = *msg;
        if (!have_grid) first = ros::SteadyTime::now();
        have_grid = true;
      });
  auto updates = nh.subscribe<map_msgs::OccupancyGridUpdate>(
      topic + "_updates", 10,
      [&](const map_msgs::OccupancyGridUpdate::ConstPtr& u)
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (!have_grid) return;
        const std::string error = costmap_layers::validateGridUpdate(u->x, u->y, u->width, u->height, u->data.size(),
                                                                     grid.info.width, grid.info.height)
                                      .message;
        if (!error.empty())
        {
          ROS_ERROR_THROTTLE(5.0, "costmap_snapshot: update on %s_updates dropped: %s", topic.c_str(), error.c_str());
          return;
        }
        for (uint32_t j = 0; j < u->height; ++j)
          std::copy_n(u->data.begin() + static_cast<std::size_t>(j) * u->width, u->width,
                      grid.data.begin() + (static_cast<std::size_t>(u->y) + j) * grid.info.width + u->x);
      });

  const ros::SteadyTime start = ros::SteadyTime::now();
  ros::WallRate rate(20);
  while (ros::ok())
  {
    ros::spinOnce();
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (have_grid && (ros::SteadyTime::now() - first).toSec() >= wait)
      {
        try
        {
          costmap_layers::io::writeOccupancyPng(output, grid.data.data(), grid.info.width, grid.info.height);
        }
        catch (const std::exception& e)
        {
          ROS_ERROR("costmap_snapshot: %s", e.what());
          return 1;
        }
        ROS_INFO("costmap_snapshot: wrote %ux%u costmap from %s to %s", grid.info.width, grid.info.height,
                 topic.c_str(), output.c_str());
        return 0;
      }
    }
    bool waiting_for_first;
    {
      std::lock_guard<std::mutex> lock(mutex);
      waiting_for_first = !have_grid;
    }
    if (waiting_for_first && (ros::SteadyTime::now() - start).toSec() > timeout)
    {
      ROS_ERROR("costmap_snapshot: no costmap on %s within %.1f s", topic.c_str(), timeout);
      return 1;
    }
    rate.sleep();
  }
  return 1;
}
}  // namespace

int main(int argc, char** argv)
{
  return costmap_layers_ros::runProgram(argc, argv, "costmap_snapshot", [] { return run(); });
}
