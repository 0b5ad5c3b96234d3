// rosrun costmap_layers costmap_snapshot _topic:=/costmap_node/costmap _output:=costmap.png
// Waits for an OccupancyGrid (applying OccupancyGridUpdates that follow it), writes it as a PNG with a
// legend after ~wait seconds of updates, and exits. Used by the demo and the tests.
#include <map_msgs/OccupancyGridUpdate.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/ros.h>

#include <cstdint>
#include <mutex>
#include <utility>

#include "costmap_layers/core/filters/costmap_filter.hpp"
#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/io/png_writer.hpp"
#include "costmap_layers/ros/conversions.hpp"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "costmap_snapshot");
  ros::NodeHandle nh, pnh("~");
  const std::string topic = pnh.param<std::string>("topic", "/costmap_node/costmap");
  const std::string output = pnh.param<std::string>("output", "costmap.png");
  // Both in wall time: under /use_sim_time a stopped or absent /clock must not hang the tool.
  const double wait = pnh.param("wait", 0.0);         // [s] to keep applying updates after the first grid
  const double timeout = pnh.param("timeout", 30.0);  // [s] to wait for the first grid (not after it)
  // NaN would make both waits endless (every comparison with it is false).
  for (const auto& [name, value] : {std::pair<const char*, double>{"wait", wait}, {"timeout", timeout}})
  {
    if (!(value >= 0.0 && value <= costmap_layers::limits::kMaxDuration))
    {
      ROS_FATAL("costmap_snapshot: parameter ~%s must be in [0, %g] s (got %g)", name,
                costmap_layers::limits::kMaxDuration, value);
      return 1;
    }
  }

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
