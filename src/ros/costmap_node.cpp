#include "costmap_layers/ros/costmap_node.hpp"

#include <geometry_msgs/PolygonStamped.h>
#include <map_msgs/OccupancyGridUpdate.h>
#include <nav_msgs/OccupancyGrid.h>
#include <std_srvs/Empty.h>

#include <algorithm>
#include <cmath>

#include "costmap_layers/core/costmap_builder.hpp"
#include "costmap_layers/core/costmap_clearing.hpp"
#include "costmap_layers/core/layer.hpp"
#include "costmap_layers/ros/conversions.hpp"

namespace costmap_layers_ros
{
using costmap_layers::CellWindow;
using costmap_layers::ParamValue;

ParamValue readNamespace(const ros::NodeHandle& nh)
{
  XmlRpc::XmlRpcValue value;
  if (!nh.getParam(nh.getNamespace(), value)) return ParamValue::makeMap();
  ParamValue tree = fromXmlRpc(value);
  return tree.isMap() ? tree : ParamValue::makeMap();
}

CostmapNode::CostmapNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh),
      private_nh_(private_nh),
      log_(std::make_shared<ThrottledLog>()),
      tf_(ros::Duration(10.0)),
      tf_listener_(tf_)
{
  try
  {
    setUp();
  }
  catch (const std::exception& e)
  {
    // Logged here, while every member is alive: once the plugin loader is destroyed during unwinding,
    // rosconsole output from this process is no longer reliable.
    ROS_FATAL("costmap_node: %s", e.what());
    throw StartupError(e.what());
  }
}

void CostmapNode::setUp()
{
  const ParamValue params = readNamespace(private_nh_);
  config_ = costmap_layers::parseCostmapConfig(params);
  if (config_.update_frequency <= 0.0)
    throw std::invalid_argument("costmap: parameter 'update_frequency' must be positive (got " +
                                std::to_string(config_.update_frequency) + ")");
  const costmap_layers::PluginLists lists = costmap_layers::parsePluginLists(params);

  costmap_ = std::make_unique<costmap_layers::LayeredCostmap>(config_.global_frame, config_.rolling_window,
                                                              config_.track_unknown_space);
  costmap_->resizeMap(config_.sizeInCellsX(), config_.sizeInCellsY(), config_.resolution, config_.origin_x,
                      config_.origin_y);
  auto contexts = [&](const costmap_layers::PluginSpec& spec)
  {
    const ParamValue* sub = params.find(spec.name);
    return std::make_shared<RosLayerContext>(nh_, ros::NodeHandle(private_nh_, spec.name),
                                             sub != nullptr ? *sub : ParamValue::makeMap(), config_.global_frame,
                                             config_.transform_tolerance, tf_, log_);
  };
  costmap_layers::loadPlugins(
      *costmap_, lists, [this](const std::string& type) { return factory_.create(type); }, contexts);
  for (const auto* list : {&lists.plugins, &lists.filters})
    for (const auto& spec : *list)
      ROS_INFO("costmap: using plugin \"%s\" (%s)", spec.name.c_str(), spec.type.c_str());
  costmap_->setFootprint(config_.footprint.padded());
  const LayerReconfigure::RunLocked run_locked = [this](const std::function<void()>& fn)
  {
    std::lock_guard<std::mutex> lock(update_mutex_);
    fn();
    costmap_->requestFullUpdate();
  };
  for (const auto* list : {&lists.plugins, &lists.filters})
    for (const auto& spec : *list)
    {
      const ParamValue* sub = params.find(spec.name);
      reconfigure_.push_back(
          std::make_unique<LayerReconfigure>(ros::NodeHandle(private_nh_, spec.name), costmap_->findLayer(spec.name),
                                             sub != nullptr ? *sub : ParamValue::makeMap(), run_locked));
    }

  costmap_pub_ = private_nh_.advertise<nav_msgs::OccupancyGrid>(
      "costmap", 1, [this](const ros::SingleSubscriberPublisher&) { new_subscriber_ = true; }, {}, {}, true);
  update_pub_ = private_nh_.advertise<map_msgs::OccupancyGridUpdate>("costmap_updates", 1);
  footprint_pub_ = private_nh_.advertise<geometry_msgs::PolygonStamped>("footprint", 1);
  clear_srv_ = private_nh_.advertiseService<std_srvs::Empty::Request, std_srvs::Empty::Response>(
      "clear",
      [this](std_srvs::Empty::Request&, std_srvs::Empty::Response&)
      {
        std::lock_guard<std::mutex> lock(update_mutex_);
        const int n = costmap_layers::resetClearableLayers(*costmap_);
        ROS_INFO("costmap: cleared %d clearable layer(s)", n);
        return true;
      });
  clear_around_srv_ = private_nh_.advertiseService<std_srvs::Empty::Request, std_srvs::Empty::Response>(
      "clear_around_robot",
      [this](std_srvs::Empty::Request&, std_srvs::Empty::Response&)
      {
        std::lock_guard<std::mutex> lock(update_mutex_);
        const int n = costmap_layers::clearClearableLayersAround(*costmap_, last_x_, last_y_, config_.reset_distance);
        if (n < 0)
        {
          ROS_ERROR("costmap: clear_around_robot refused: robot position (%f, %f) or reset_distance %f not valid",
                    last_x_, last_y_, config_.reset_distance);
          return false;
        }
        ROS_INFO("costmap: cleared %d clearable layer(s) outside %.2f m around the robot", n, config_.reset_distance);
        return true;
      });
}

CostmapNode::~CostmapNode()
{
  // Layers first, while the plugin library that made them is still loaded.
  reconfigure_.clear();
  costmap_.reset();
}

std::optional<costmap_layers::Transform2D> CostmapNode::robotPose()
{
  std::string error;
  auto pose =
      lookupTransform2D(tf_, config_.global_frame, config_.robot_base_frame, config_.transform_tolerance, &error);
  if (!pose)
    log_->log(costmap_layers::Severity::Warn, "robot_pose",
              "costmap: cannot get the robot pose (" + config_.robot_base_frame + " in " + config_.global_frame +
                  "), skipping the update: " + error);
  return pose;
}

bool CostmapNode::updateOnce()
{
  const auto pose = robotPose();
  if (!pose) return false;
  std::lock_guard<std::mutex> lock(update_mutex_);
  costmap_->updateMap(pose->x, pose->y, pose->yaw);
  last_x_ = pose->x;
  last_y_ = pose->y;

  const CellWindow w = costmap_->getUpdatedBounds();
  if (!w.empty())
  {
    if (pending_.empty())
      pending_ = w;
    else
      pending_ = CellWindow{std::min(pending_.x0, w.x0), std::min(pending_.y0, w.y0), std::max(pending_.xn, w.xn),
                            std::max(pending_.yn, w.yn)};
  }

  geometry_msgs::PolygonStamped fp;
  fp.header.frame_id = config_.global_frame;
  fp.header.stamp = ros::Time::now();
  for (const auto& p : costmap_layers::transformFootprint(pose->x, pose->y, pose->yaw, costmap_->getFootprint()))
  {
    geometry_msgs::Point32 q;
    q.x = static_cast<float>(p.x());
    q.y = static_cast<float>(p.y());
    fp.polygon.points.push_back(q);
  }
  footprint_pub_.publish(fp);

  // Publish once a cycle ran, even if no layer had anything to draw yet: the grid is valid then.
  if (config_.publish_frequency > 0.0 &&
      (ros::WallTime::now() - last_publish_).toSec() >= 1.0 / config_.publish_frequency)
  {
    const auto& grid = costmap_->getCostmap();
    const bool geometry_changed = grid.getSizeInCellsX() != last_size_x_ || grid.getSizeInCellsY() != last_size_y_ ||
                                  grid.getOriginX() != last_origin_x_ || grid.getOriginY() != last_origin_y_ ||
                                  grid.getResolution() != last_resolution_;
    publish(!published_once_ || geometry_changed || config_.always_send_full_costmap ||
            new_subscriber_.exchange(false));
    last_publish_ = ros::WallTime::now();
  }
  return true;
}

void CostmapNode::publish(bool full)
{
  const auto& grid = costmap_->getCostmap();
  const ros::Time now = ros::Time::now();
  if (full)
  {
    nav_msgs::OccupancyGrid msg;
    toOccupancyGrid(grid, config_.global_frame, now, msg);
    costmap_pub_.publish(msg);
    last_size_x_ = grid.getSizeInCellsX();
    last_size_y_ = grid.getSizeInCellsY();
    last_origin_x_ = grid.getOriginX();
    last_origin_y_ = grid.getOriginY();
    last_resolution_ = grid.getResolution();
    published_once_ = true;
  }
  else if (!pending_.empty())
  {
    map_msgs::OccupancyGridUpdate msg;
    toOccupancyGridUpdate(grid, pending_, config_.global_frame, now, msg);
    update_pub_.publish(msg);
  }
  pending_ = CellWindow{};
}

void CostmapNode::run()
{
  // As costmap_2d does: wait for the robot's transform before the first update, saying so.
  while (ros::ok() &&
         !tf_.canTransform(config_.global_frame, config_.robot_base_frame, ros::Time(0), ros::Duration(0.1)))
    log_->log(costmap_layers::Severity::Info, "waiting_for_tf",
              "costmap: waiting for the transform " + config_.robot_base_frame + " -> " + config_.global_frame);
  const double period = 1.0 / config_.update_frequency;
  ros::WallTime next = ros::WallTime::now();
  while (ros::ok())
  {
    const ros::WallTime start = ros::WallTime::now();
    updateOnce();
    const double took = (ros::WallTime::now() - start).toSec();
    if (took > period)
      log_->log(costmap_layers::Severity::Warn, "rate",
                "costmap: the update loop missed its desired rate of " + std::to_string(config_.update_frequency) +
                    " Hz: the cycle took " + std::to_string(took) + " s, " + std::to_string(took - period) +
                    " s longer than its period");
    next += ros::WallDuration(period);
    const ros::WallTime now = ros::WallTime::now();
    if (next < now)
      next = now;  // late: start the next cycle at once instead of bursting to catch up
    else
      (next - now).sleep();
  }
}
}  // namespace costmap_layers_ros
