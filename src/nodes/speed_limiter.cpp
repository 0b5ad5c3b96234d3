// rosrun costmap_layers speed_limiter cmd_vel_in:=/move_base/cmd_vel cmd_vel:=/base/cmd_vel
// Sits between a planner and the base: every command on cmd_vel_in is republished on cmd_vel, scaled
// as a whole so that its linear speed stays within the latest /max_speed (0 = no limit; nothing is
// limited until a limit is known). When commands stop for ~command_timeout s, it publishes one zero
// command (~publish_zero_when_stale, default true) or simply falls silent.
#include <geometry_msgs/Twist.h>
#include <ros/ros.h>

#include <mutex>
#include <stdexcept>

#include "costmap_layers/MaxSpeed.h"
#include "costmap_layers/core/filters/speed_limiter.hpp"
#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/ros/node_params.hpp"
#include "costmap_layers/ros/program_main.hpp"

namespace
{
costmap_layers::Twist fromMsg(const geometry_msgs::Twist& m)
{
  return {m.linear.x, m.linear.y, m.linear.z, m.angular.x, m.angular.y, m.angular.z};
}

geometry_msgs::Twist toMsg(const costmap_layers::Twist& t)
{
  geometry_msgs::Twist m;
  m.linear.x = t.lx, m.linear.y = t.ly, m.linear.z = t.lz;
  m.angular.x = t.ax, m.angular.y = t.ay, m.angular.z = t.az;
  return m;
}

int run()
{
  ros::NodeHandle nh, pnh("~");
  const costmap_layers_ros::NodeParams params(pnh);
  for (const auto& key : params.unknownKeys({"command_timeout", "publish_zero_when_stale", "max_speed_topic"}))
    ROS_WARN(
        "speed_limiter: parameter %s%s is not one of command_timeout, publish_zero_when_stale, max_speed_topic: "
        "ignored",
        params.where().c_str(), key.c_str());
  costmap_layers::SpeedLimiterConfig cfg;
  // A string ('fast', 'no') is an error, not the default: a limiter running on a value nobody chose is
  // the silent kind of wrong.
  cfg.command_timeout =
      params.getDoubleIn("command_timeout", cfg.command_timeout, 0.0, costmap_layers::limits::kMaxDuration);
  if (!(cfg.command_timeout > 0.0))
    throw std::invalid_argument("parameter " + params.where() + "command_timeout must be more than 0 s (got 0)");
  cfg.publish_zero_when_stale = params.getBool("publish_zero_when_stale", cfg.publish_zero_when_stale);
  const std::string max_speed_topic = params.getTopic("max_speed_topic", "/max_speed");

  std::mutex mutex;
  double limit = 0.0;  // no limit until one is known
  // Staleness is decided by the core (a clock jump back restarts the timeout instead of keeping the last
  // command fresh until the clock is back at its time).
  costmap_layers::CommandWatchdog input_watch(cfg.command_timeout);
  ros::Publisher out = nh.advertise<geometry_msgs::Twist>("cmd_vel", 10);
  auto limits = nh.subscribe<costmap_layers::MaxSpeed>(
      max_speed_topic, 1,
      [&](const costmap_layers::MaxSpeed::ConstPtr& m)
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (const auto err = costmap_layers::checkMaxSpeed(m->max_speed))
        {
          ROS_ERROR_THROTTLE(5.0, "speed_limiter: dropped a MaxSpeed on %s: %s; keeping %.3f m/s",
                             max_speed_topic.c_str(), err->c_str(), limit);
          return;
        }
        limit = m->max_speed;
      });
  auto commands = nh.subscribe<geometry_msgs::Twist>(
      "cmd_vel_in", 10,
      [&](const geometry_msgs::Twist::ConstPtr& m)
      {
        const costmap_layers::Twist in = fromMsg(*m);
        if (const auto err = costmap_layers::checkTwist(in))
        {
          ROS_ERROR_THROTTLE(5.0, "speed_limiter: dropped a command on cmd_vel_in: %s", err->c_str());
          return;
        }
        std::lock_guard<std::mutex> lock(mutex);
        out.publish(toMsg(costmap_layers::limitTwist(in, limit)));
        input_watch.commandReceived(ros::Time::now().toNSec(), ros::SteadyTime::now().toNSec());
      });
  // A steady timer: a ROS-time timer never fires under /use_sim_time while /clock is absent or paused,
  // and the watchdog must still see commands stop then (CommandWatchdog times a clock that does not
  // move on the steady clock).
  using Event = costmap_layers::CommandWatchdog::Event;
  auto watchdog = nh.createSteadyTimer(
      ros::WallDuration(0.05),
      [&](const ros::SteadyTimerEvent&)
      {
        std::lock_guard<std::mutex> lock(mutex);
        const auto event = input_watch.check(ros::Time::now().toNSec(), ros::SteadyTime::now().toNSec());
        if (event == Event::ClockJumpedBack)
          ROS_WARN("speed_limiter: the clock jumped back: the %.2f s command timeout restarts now",
                   cfg.command_timeout);
        if (event != Event::WentStale && event != Event::WentStaleNoClock) return;
        if (cfg.publish_zero_when_stale) out.publish(geometry_msgs::Twist());
        ROS_WARN("speed_limiter: no command on cmd_vel_in for %.2f s%s: %s", cfg.command_timeout,
                 event == Event::WentStaleNoClock ? " of wall time (the ROS clock has not moved: /use_sim_time "
                                                    "without /clock, or a paused one)"
                                                  : "",
                 cfg.publish_zero_when_stale ? "published a zero command" : "stopped publishing");
      });
  ros::spin();
  return 0;
}
}  // namespace

int main(int argc, char** argv)
{
  return costmap_layers_ros::runProgram(argc, argv, "speed_limiter", [] { return run(); });
}
