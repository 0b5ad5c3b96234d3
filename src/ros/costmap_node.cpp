#include "costmap_layers/ros/costmap_node.hpp"
#include "costmap_layers/ros/program_main.hpp"

#include <costmap_layers/ClearCostmapAroundPose.h>
#include <costmap_layers/ClearCostmapExceptRegion.h>
#include <costmap_layers/ClearEntireCostmap.h>
#include <costmap_layers/GetCosts.h>

#include <geometry_msgs/PolygonStamped.h>
#include <map_msgs/OccupancyGridUpdate.h>
#include <nav_msgs/OccupancyGrid.h>
#include <std_srvs/Empty.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include "costmap_layers/core/config/config_compat.hpp"
#include "costmap_layers/core/costmap/cost_query.hpp"
#include "costmap_layers/core/costmap/costmap_builder.hpp"
#include "costmap_layers/core/costmap/costmap_clearing.hpp"
#include "costmap_layers/core/costmap/layer.hpp"
#include "costmap_layers/core/costmap/layer_status.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/io/param_yaml.hpp"
#include "costmap_layers/ros/conversions.hpp"

namespace costmap_layers_ros
{
using costmap_layers::CellWindow;
using costmap_layers::ParamValue;

namespace
{
/// Seconds on the steady clock: the loop's pacing, its stall check and the publish schedule do not
/// follow steps of the system clock (CLOCK_REALTIME, which ros::WallTime reads).
double steadySeconds()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// A pose of a service request in the global frame, or why not. An empty frame_id means the global
/// frame (what a ROS 1 user typing `rosservice call` leaves). An all-zero quaternion (the unset
/// default) is yaw 0, as tf2::getYaw reads it; other orientations go through planarYaw, which names
/// the field and refuses a non-finite, zero-length or steeply tilted one.
struct PlacedPose
{
  double x = 0, y = 0, yaw = 0;
};
/// A length [m] in a log line: two decimals, as the services' lines have always printed it.
std::string metres(double v)
{
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::optional<PlacedPose> placePose(const tf2_ros::Buffer& tf, const std::string& global_frame, double tolerance,
                                    const geometry_msgs::PoseStamped& pose, const std::string& field,
                                    std::string& error)
{
  const auto& p = pose.pose.position;
  if (!std::isfinite(p.x) || !std::isfinite(p.y))
  {
    error = field + ".pose.position (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ") is not finite";
    return std::nullopt;
  }
  const auto& q = pose.pose.orientation;
  double yaw = 0.0;
  if (q.x != 0.0 || q.y != 0.0 || q.z != 0.0 || q.w != 0.0)
  {
    try
    {
      yaw = planarYaw(q, kMaxPoseTilt, field + ".pose.orientation");
    }
    catch (const std::invalid_argument& e)
    {
      error = e.what();
      return std::nullopt;
    }
  }
  const std::string& frame = pose.header.frame_id;
  if (frame.empty() || frame == global_frame) return PlacedPose{p.x, p.y, yaw};
  std::string tf_error;
  const auto t = lookupTransform2D(tf, global_frame, frame, tolerance, &tf_error);
  if (!t)
  {
    error = field + ".header.frame_id '" + frame.substr(0, 64) + "' cannot be transformed to " + global_frame + ": " +
            tf_error.substr(0, 200);
    return std::nullopt;
  }
  PlacedPose out;
  t->apply(p.x, p.y, out.x, out.y);
  out.yaw = yaw + t->yaw;
  return out;
}

constexpr const char* kNoClock =
    "/use_sim_time is true and no /clock has arrived: no update until it does (start the simulator, or "
    "rosbag play --clock)";
}  // namespace

ParamValue readNamespace(const ros::NodeHandle& nh)
{
  XmlRpc::XmlRpcValue value;
  if (!nh.getParam(nh.getNamespace(), value)) return ParamValue::makeMap();
  ParamValue tree = fromXmlRpc(value);
  return tree.isMap() ? tree : ParamValue::makeMap();
}

std::vector<costmap_layers::ParentNamespace> readParentNamespaces(const std::string& ns)
{
  std::vector<costmap_layers::ParentNamespace> parents;
  std::string at = ns;
  while (at != "/" && !at.empty())
  {
    at = ros::names::parentNamespace(at);
    costmap_layers::ParentNamespace parent{at, ParamValue::makeMap()};
    for (const auto& key : costmap_layers::searchedKeys())
    {
      XmlRpc::XmlRpcValue value;
      const std::string name = (at == "/" ? "" : at) + "/" + key;
      if (ros::param::has(name) && ros::param::get(name, value)) parent.values.set(key, fromXmlRpc(value));
    }
    parents.push_back(std::move(parent));
  }
  return parents;
}

CostmapNode::CostmapNode(ros::NodeHandle nh, ros::NodeHandle private_nh, std::string topic_ns)
    : nh_(nh),
      private_nh_(private_nh),
      topic_ns_(std::move(topic_ns)),
      log_(std::make_shared<ThrottledLog>()),
      tf_(ros::Duration(10.0)),
      tf_listener_(tf_, log_, private_nh.getNamespace())
{
  try
  {
    setUp();
  }
  catch (const std::exception& e)
  {
    // Logged here, while every member is alive: once the plugin loader is destroyed during unwinding,
    // rosconsole output from this process is no longer reliable.
    reportFatal(e.what());  // waits for rosout, so that the line reaches it too
    throw StartupError(e.what());
  }
}

void CostmapNode::setUp()
{
  const std::string ns = private_nh_.getNamespace();
  ParamValue raw = readNamespace(private_nh_);
  const std::string own_name = ns.substr(ns.rfind('/') + 1);
  // costmap_2d's conversions and look-ups; the tree that results is what everything below reads.
  params_ = std::make_unique<costmap_layers::CompatResult>(
      costmap_layers::prepareCostmapNamespace(std::move(raw), own_name, readParentNamespaces(ns)));
  for (const auto& w : params_->warnings)
    ROS_WARN("costmap %s: %s", ns.c_str(), w.c_str());
  for (const auto& n : params_->notes)
    ROS_INFO("costmap %s: %s", ns.c_str(), n.c_str());
  if (params_->converted_pre_hydro)
    ROS_INFO(
        "costmap %s: the same costmap as a plugin list (costmap_2d's form, read unchanged here); put it in "
        "the costmap's namespace in place of the pre-Hydro keys:\n%s",
        ns.c_str(), costmap_layers::io::paramToYaml(params_->plugin_list).c_str());
  const ParamValue& params = params_->params;

  // Every parameter look-up from here until the layers are initialised is noted, so that the keys
  // nobody asked for can be reported.
  costmap_layers::ParamReadLog read_log;
  config_ = costmap_layers::parseCostmapConfig(params);
  const costmap_layers::PluginLists lists = costmap_layers::parsePluginLists(params);

  costmap_ = std::make_unique<costmap_layers::LayeredCostmap>(config_.global_frame, config_.rolling_window,
                                                              config_.track_unknown_space);
  costmap_->resizeMap(config_.sizeInCellsX(), config_.sizeInCellsY(), config_.resolution, config_.origin_x,
                      config_.origin_y);
  std::vector<std::pair<costmap_layers::PluginSpec, std::shared_ptr<RosLayerContext>>> made;
  auto contexts = [&](const costmap_layers::PluginSpec& spec)
  {
    const ParamValue* sub = costmap_layers::pluginParams(params, spec.name);
    auto context = std::make_shared<RosLayerContext>(ros::NodeHandle(private_nh_, spec.name),
                                                     sub != nullptr ? *sub : ParamValue::makeMap(),
                                                     config_.global_frame, config_.transform_tolerance, tf_, log_);
    made.emplace_back(spec, context);
    return context;
  };
  costmap_layers::loadPlugins(
      *costmap_, lists, [this](const std::string& type) { return factory_.create(type); }, contexts);
  // The node owns every subscription and publication: each layer's ports, wired here, in the order the
  // layers were made (a container's plugins right after it), the order of the diagnostics' names.
  for (const auto& made_layer : made)
  {
    const costmap_layers::PluginSpec& spec = made_layer.first;
    const std::string ours = costmap_layers::resolvePluginType(spec.type);
    if (ours != spec.type)
      ROS_INFO("costmap: using plugin \"%s\" (%s, loaded as %s)", spec.name.c_str(), spec.type.c_str(), ours.c_str());
    else
      ROS_INFO("costmap: using plugin \"%s\" (%s)", spec.name.c_str(), spec.type.c_str());
    ports_.push_back(std::make_unique<LayerPorts>(nh_, ros::NodeHandle(private_nh_, spec.name),
                                                  *costmap_->findLayer(spec.name), config_.global_frame, tf_, log_,
                                                  topic_ns_));
  }

  // One warning per key that no parse asked for, in the costmap's namespace and in each layer's.
  std::vector<std::pair<costmap_layers::PluginSpec, const ParamValue*>> layer_params;
  std::vector<std::string> names;
  for (const auto& [spec, context] : made)
  {
    layer_params.emplace_back(spec, &context->params());
    names.push_back(spec.name);
  }
  for (const auto& line : costmap_layers::unusedParameterLines(*params_, read_log, layer_params, ns))
    ROS_WARN("costmap: %s", line.c_str());
  costmap_->setFootprint(config_.footprint.padded());
  const LayerReconfigure::RunLocked run_locked = [this](const std::function<void()>& fn)
  {
    std::lock_guard<std::mutex> lock(update_mutex_);
    fn();
    costmap_->requestFullUpdate();
  };
  for (const auto& [spec, context] : made)
    reconfigure_.push_back(std::make_unique<LayerReconfigure>(
        ros::NodeHandle(private_nh_, spec.name), costmap_->findLayer(spec.name), context->params(), run_locked));

  pacer_ = std::make_unique<costmap_layers::LoopPacer>(1.0 / config_.update_frequency);
  schedule_ =
      std::make_unique<costmap_layers::PublishSchedule>(config_.publish_frequency, config_.always_send_full_costmap);
  // Not latched: a latched grid would be the one of the last resize. Each new subscriber gets the
  // current grid from the connect callback instead, as costmap_2d's publisher does.
  costmap_pub_ = private_nh_.advertise<nav_msgs::OccupancyGrid>(
      "costmap", 1, [this](const ros::SingleSubscriberPublisher& sub) { sendCurrentGrid(sub); });
  update_pub_ = private_nh_.advertise<map_msgs::OccupancyGridUpdate>("costmap_updates", 1);
  footprint_pub_ = private_nh_.advertise<geometry_msgs::PolygonStamped>("footprint", 1);
  clear_srv_ = private_nh_.advertiseService<std_srvs::Empty::Request, std_srvs::Empty::Response>(
      "clear",
      [this](std_srvs::Empty::Request&, std_srvs::Empty::Response&)
      {
        std::lock_guard<std::mutex> lock(update_mutex_);
        const int n = costmap_layers::resetClearableLayers(*costmap_);
        log_->log(costmap_layers::Severity::Info, "clear/cleared",
                  "costmap: cleared " + std::to_string(n) + " clearable layer(s)");
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
          log_->log(costmap_layers::Severity::Error, "clear_around_robot",
                    "costmap: clear_around_robot refused: robot position (" + std::to_string(last_x_) + ", " +
                        std::to_string(last_y_) + ") or reset_distance " + std::to_string(config_.reset_distance) +
                        " not valid");
          return false;
        }
        log_->log(costmap_layers::Severity::Info, "clear_around_robot/cleared",
                  "costmap: cleared " + std::to_string(n) + " clearable layer(s) outside " +
                      metres(config_.reset_distance) + " m around the robot");
        return true;
      });
  advertiseNav2Services();
  setUpDiagnostics(names);
}

void CostmapNode::advertiseNav2Services()
{
  get_cost_srv_ = private_nh_.advertiseService<costmap_layers::GetCosts::Request, costmap_layers::GetCosts::Response>(
      "get_cost",
      [this](costmap_layers::GetCosts::Request& req, costmap_layers::GetCosts::Response& res)
      {
        res.success = true;
        if (req.poses.size() > costmap_layers::kMaxCostQueryPoses)
        {
          log_->log(costmap_layers::Severity::Error, "get_cost/poses",
                    "costmap: get_cost refused: poses holds " + std::to_string(req.poses.size()) + " poses, at most " +
                        std::to_string(costmap_layers::kMaxCostQueryPoses));
          res.success = false;
          return true;
        }
        // Placed before the lock: tf look-ups need not hold up the update loop.
        std::vector<std::optional<PlacedPose>> placed(req.poses.size());
        std::size_t refused = 0;
        std::string first_error;
        for (std::size_t k = 0; k < req.poses.size(); ++k)
        {
          std::string error;
          placed[k] = placePose(tf_, config_.global_frame, config_.transform_tolerance, req.poses[k],
                                "poses[" + std::to_string(k) + "]", error);
          if (!placed[k] && refused++ == 0) first_error = error;
        }
        if (refused > 0)
          log_->log(costmap_layers::Severity::Error, "get_cost",
                    "costmap: get_cost: " + std::to_string(refused) + " pose(s) answered 255 (no information): " +
                        first_error + (refused > 1 ? " (and others)" : ""));
        std::lock_guard<std::mutex> lock(update_mutex_);
        const costmap_layers::Costmap2D& grid = costmap_->getCostmap();
        const costmap_layers::Footprint& footprint = costmap_->getFootprint();
        res.costs.reserve(placed.size());
        for (const auto& p : placed)
        {
          costmap_layers::CostAnswer a{costmap_layers::NO_INFORMATION, false};
          if (p)
            a = req.use_footprint ? costmap_layers::footprintCostAtPose(grid, p->x, p->y, p->yaw, footprint)
                                  : costmap_layers::pointCost(grid, p->x, p->y);
          res.costs.push_back(static_cast<float>(a.cost));
          res.success = res.success && a.ok;
        }
        return true;
      });
  clear_entirely_srv_ = private_nh_.advertiseService<costmap_layers::ClearEntireCostmap::Request,
                                                     costmap_layers::ClearEntireCostmap::Response>(
      "clear_entirely",
      [this](costmap_layers::ClearEntireCostmap::Request& req, costmap_layers::ClearEntireCostmap::Response& res)
      {
        std::lock_guard<std::mutex> lock(update_mutex_);
        std::string error;
        const int n = costmap_layers::clearEntirely(*costmap_, req.plugins, error);
        res.success = n >= 0;
        if (n < 0)
          log_->log(costmap_layers::Severity::Error, "clear_entirely",
                    "costmap: clear_entirely refused, nothing cleared: " + error);
        else
          log_->log(costmap_layers::Severity::Info, "clear_entirely/cleared",
                    "costmap: clear_entirely reset " + std::to_string(n) + " layer(s)");
        return true;
      });
  clear_except_srv_ = private_nh_.advertiseService<costmap_layers::ClearCostmapExceptRegion::Request,
                                                   costmap_layers::ClearCostmapExceptRegion::Response>(
      "clear_except_region",
      [this](costmap_layers::ClearCostmapExceptRegion::Request& req,
             costmap_layers::ClearCostmapExceptRegion::Response& res)
      {
        res.success = false;
        const auto robot = robotPose();  // the pose now, as Nav2 asks tf for it; logged when missing
        if (!robot)
        {
          log_->log(costmap_layers::Severity::Error, "clear_except_region",
                    "costmap: clear_except_region refused: no robot pose (" + config_.robot_base_frame + " in " +
                        config_.global_frame + ")");
          return true;
        }
        std::lock_guard<std::mutex> lock(update_mutex_);
        std::string error;
        const int n = costmap_layers::clearSquare(*costmap_, robot->x, robot->y, req.reset_distance,
                                                  costmap_layers::SquareClear::KeepSquare, req.plugins, error);
        res.success = n >= 0;
        if (n < 0)
          log_->log(costmap_layers::Severity::Error, "clear_except_region",
                    "costmap: clear_except_region refused, nothing cleared: " + error);
        else
          log_->log(costmap_layers::Severity::Info, "clear_except_region/cleared",
                    "costmap: cleared " + std::to_string(n) + " layer(s) outside " + metres(req.reset_distance) +
                        " m around the robot");
        return true;
      });
  clear_around_pose_srv_ = private_nh_.advertiseService<costmap_layers::ClearCostmapAroundPose::Request,
                                                        costmap_layers::ClearCostmapAroundPose::Response>(
      "clear_around_pose",
      [this](costmap_layers::ClearCostmapAroundPose::Request& req,
             costmap_layers::ClearCostmapAroundPose::Response& res)
      {
        res.success = false;
        std::string error;
        const auto p = placePose(tf_, config_.global_frame, config_.transform_tolerance, req.pose, "pose", error);
        if (!p)
        {
          log_->log(costmap_layers::Severity::Error, "clear_around_pose",
                    "costmap: clear_around_pose refused, nothing cleared: " + error);
          return true;
        }
        std::lock_guard<std::mutex> lock(update_mutex_);
        const int n = costmap_layers::clearSquare(*costmap_, p->x, p->y, req.reset_distance,
                                                  costmap_layers::SquareClear::ClearSquare, req.plugins, error);
        res.success = n >= 0;
        if (n < 0)
          log_->log(costmap_layers::Severity::Error, "clear_around_pose",
                    "costmap: clear_around_pose refused, nothing cleared: " + error);
        else
          log_->log(costmap_layers::Severity::Info, "clear_around_pose/cleared",
                    "costmap: cleared " + std::to_string(n) + " layer(s) within " + metres(req.reset_distance) +
                        " m around (" + metres(p->x) + ", " + metres(p->y) + ")");
        return true;
      });
}

void CostmapNode::setUpDiagnostics(const std::vector<std::string>& layer_names)
{
  diagnostics_ = std::make_unique<diagnostic_updater::Updater>(nh_, private_nh_);
  diagnostics_->setHardwareID(private_nh_.getNamespace());
  diagnostics_->add("costmap", [this](diagnostic_updater::DiagnosticStatusWrapper& stat) { costmapStatus(stat); });
  // ports_ was filled in plugin-list order, the same order as layer_names.
  for (std::size_t k = 0; k < layer_names.size(); ++k)
  {
    const std::string name = layer_names[k];
    diagnostics_->add("layer " + name, [this, name, k](diagnostic_updater::DiagnosticStatusWrapper& stat)
                      { layerStatus(name, k, stat); });
  }
  // A spinner thread, not the update loop, publishes them, once per ~diagnostic_period (default 1 s):
  // they keep coming while the loop waits for tf or /clock. Paced here on the steady clock (force_update):
  // Updater::update() waits for a deadline in ROS time, which a clock that goes back (rosbag play --loop, a system
  // clock set back) or never starts (no /clock) would leave silent.
  diagnostics_timer_ = private_nh_.createWallTimer(
      ros::WallDuration(0.1),
      [this](const ros::WallTimerEvent&)
      {
        std::lock_guard<std::mutex> lock(update_mutex_);
        const double now = steadySeconds();
        if (last_diagnostics_s_ >= 0.0 && now - last_diagnostics_s_ < diagnostics_->getPeriod()) return;
        last_diagnostics_s_ = now;
        diagnostics_->force_update();
      });
}

void CostmapNode::costmapStatus(diagnostic_updater::DiagnosticStatusWrapper& stat)
{
  using diagnostic_msgs::DiagnosticStatus;
  const double period = 1.0 / config_.update_frequency;
  const auto& grid = costmap_->getCostmap();
  stat.add("global_frame", config_.global_frame);
  stat.add("robot_base_frame", config_.robot_base_frame);
  stat.add("rolling_window", config_.rolling_window ? "true" : "false");
  stat.addf("size [cells]", "%u x %u", grid.getSizeInCellsX(), grid.getSizeInCellsY());
  stat.add("resolution [m]", grid.getResolution());
  stat.add("cycles", cycles_);
  stat.add("update period [s]", period);
  stat.add("last cycle [s]", last_cycle_s_);
  stat.add("longest cycle since last report [s]", worst_cycle_s_);
  const double now = steadySeconds();
  stat.add("last cycle ended",
           cycles_ == 0 ? std::string("never") : costmap_layers::describeAge(pacer_->sinceLastCycle(now)));
  std::string not_current;
  for (const auto* list : {&costmap_->getPlugins(), &costmap_->getFilters()})
    for (const auto& layer : *list)
      if (layer->enabled() && !layer->isCurrent()) not_current += (not_current.empty() ? "" : ", ") + layer->getName();
  stat.add("layers not current", not_current.empty() ? std::string("none") : not_current);

  stat.summary(DiagnosticStatus::OK, "updating");
  if (waiting_for_clock_)
    stat.mergeSummary(DiagnosticStatus::ERROR, kNoClock);
  else if (const double stalled = pacer_->stalledFor(now); stalled > 0.0)
    stat.mergeSummaryf(DiagnosticStatus::ERROR, "no update cycle for %.1f s (the update period is %.3f s)", stalled,
                       period);
  if (!pose_error_.empty())
    stat.mergeSummary(DiagnosticStatus::ERROR, "no robot pose (" + config_.robot_base_frame + " in " +
                                                   config_.global_frame + "): " + pose_error_);
  else if (cycles_ == 0)
    stat.mergeSummary(DiagnosticStatus::WARN, "waiting for the transform " + config_.robot_base_frame + " -> " +
                                                  config_.global_frame + " before the first update");
  if (cycles_ > 0 && worst_cycle_s_ > period)
    stat.mergeSummaryf(DiagnosticStatus::WARN, "an update took %.3f s, longer than the period %.3f s", worst_cycle_s_,
                       period);
  if (!not_current.empty()) stat.mergeSummary(DiagnosticStatus::WARN, "not current: " + not_current);
  worst_cycle_s_ = last_cycle_s_;
}

void CostmapNode::layerStatus(const std::string& name, std::size_t ports_index,
                              diagnostic_updater::DiagnosticStatusWrapper& stat)
{
  const auto layer = costmap_->findLayer(name);
  if (!layer)
  {
    stat.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "no layer " + name);
    return;
  }
  const costmap_layers::LayerStatus s = layer->status();
  stat.summary(static_cast<unsigned char>(s.level), s.message);
  for (const auto& [key, value] : s.values)
    stat.add(key, value);
  if (ports_index < ports_.size())
    for (const auto& [key, value] : ports_[ports_index]->receipts())
      stat.add(key, value);
}

CostmapNode::~CostmapNode()
{
  // Subscriptions first (their callbacks reach into the layers), then the layers, while the plugin
  // library that made them is still loaded. The diagnostics timer reads both: stopped before.
  diagnostics_timer_.stop();
  ports_.clear();
  reconfigure_.clear();
  costmap_.reset();
}

std::optional<costmap_layers::Transform2D> CostmapNode::robotPose()
{
  std::string error;
  auto pose =
      lookupTransform2D(tf_, config_.global_frame, config_.robot_base_frame, config_.transform_tolerance, &error);
  {
    std::lock_guard<std::mutex> lock(update_mutex_);
    pose_error_ = pose ? std::string() : (error.empty() ? std::string("no transform") : error);
  }
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
  const double start = steadySeconds();
  costmap_->updateMap(pose->x, pose->y, pose->yaw);
  last_x_ = pose->x;
  last_y_ = pose->y;

  schedule_->noteCycle(costmap_->getCostmap(), costmap_->getUpdatedBounds());
  cycled_once_ = true;

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
  if (schedule_->due(steadySeconds())) publish();
  const double end = steadySeconds();
  pacer_->noteCycleEnd(end);
  last_cycle_s_ = end - start;
  worst_cycle_s_ = std::max(worst_cycle_s_, last_cycle_s_);
  ++cycles_;
  return true;
}

void CostmapNode::publish()
{
  const auto& grid = costmap_->getCostmap();
  const costmap_layers::PublishDecision d = schedule_->take(grid, false);
  const ros::Time now = ros::Time::now();
  if (d.full)
  {
    nav_msgs::OccupancyGrid msg;
    toOccupancyGrid(grid, config_.global_frame, now, msg);
    costmap_pub_.publish(msg);
  }
  else if (!d.window.empty())
  {
    map_msgs::OccupancyGridUpdate msg;
    if (toOccupancyGridUpdate(grid, d.window, config_.global_frame, now, msg)) update_pub_.publish(msg);
  }
}

void CostmapNode::sendCurrentGrid(const ros::SingleSubscriberPublisher& subscriber)
{
  std::lock_guard<std::mutex> lock(update_mutex_);
  // Before the first cycle the grid holds nothing yet: the first scheduled publish sends it.
  if (!cycled_once_) return;
  nav_msgs::OccupancyGrid msg;
  toOccupancyGrid(costmap_->getCostmap(), config_.global_frame, ros::Time::now(), msg);
  subscriber.publish(msg);
}

bool CostmapNode::clockMissing()
{
  // costmap_2d's loop (ros::Rate in ROS time) does not run before the first /clock; this one runs on the
  // steady clock, so it must not cycle either: every stamped reading would be "ahead of the clock" and
  // dropped, and the costmap would go out with the static map alone, looking healthy.
  const bool missing = ros::Time::isSimTime() && ros::Time::now().isZero();
  {
    std::lock_guard<std::mutex> lock(update_mutex_);
    waiting_for_clock_ = missing;
  }
  if (missing) log_->log(costmap_layers::Severity::Warn, "clock", std::string("costmap: ") + kNoClock);
  return missing;
}

void CostmapNode::sleepWhileOk(double seconds)
{
  // In slices, so that a shutdown does not wait for a long period.
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                            std::chrono::duration<double>(seconds));
  while (ros::ok())
  {
    const auto now = std::chrono::steady_clock::now();
    if (now >= until) return;
    std::this_thread::sleep_for(
        std::min<std::chrono::steady_clock::duration>(until - now, std::chrono::milliseconds(100)));
  }
}

void CostmapNode::run()
{
  while (ros::ok() && clockMissing())
    sleepWhileOk(0.1);
  // As costmap_2d does: wait for the robot's transform before the first update, saying so.
  while (ros::ok() &&
         !tf_.canTransform(config_.global_frame, config_.robot_base_frame, ros::Time(0), ros::Duration(0.1)))
    log_->log(costmap_layers::Severity::Info, "waiting_for_tf",
              "costmap: waiting for the transform " + config_.robot_base_frame + " -> " + config_.global_frame);
  const double period = 1.0 / config_.update_frequency;
  pacer_->start(steadySeconds());
  while (ros::ok())
  {
    const double start = steadySeconds();
    if (!clockMissing()) updateOnce();
    const double took = steadySeconds() - start;
    if (took > period)
      log_->log(costmap_layers::Severity::Warn, "rate",
                "costmap: the update loop missed its desired rate of " + std::to_string(config_.update_frequency) +
                    " Hz: the cycle took " + std::to_string(took) + " s, " + std::to_string(took - period) +
                    " s longer than its period");
    sleepWhileOk(pacer_->waitAfterCycle(steadySeconds()));
  }
}
}  // namespace costmap_layers_ros
