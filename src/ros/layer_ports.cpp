#include "costmap_layers/ros/layer_ports.hpp"

#include <map_msgs/OccupancyGridUpdate.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/names.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/Range.h>
#include <std_msgs/Bool.h>
#include <std_msgs/UInt8.h>
#include <std_srvs/SetBool.h>

#include <atomic>
#include <deque>
#include <mutex>

#include "costmap_layers/CostmapFilterInfo.h"
#include "costmap_layers/MaxSpeed.h"
#include "costmap_layers/Nav2SpeedLimit.h"
#include "costmap_layers/SpeedLimits.h"
#include "costmap_layers/core/filters/costmap_filter.hpp"
#include "costmap_layers/ros/inline_callback_queue.hpp"
#include "costmap_layers/ros/port_dispatch.hpp"
#include "costmap_layers/ros/tf_gate.hpp"
#include "costmap_layers/ros/voxel_output.hpp"

namespace costmap_layers_ros
{
using costmap_layers::InputKind;
using costmap_layers::OutputKind;

std::string portMessageType(InputKind kind)
{
  switch (kind)
  {
    case InputKind::Map:
    case InputKind::Mask:
      return ros::message_traits::datatype<nav_msgs::OccupancyGrid>();
    case InputKind::MapUpdates:
      return ros::message_traits::datatype<map_msgs::OccupancyGridUpdate>();
    case InputKind::SpeedLimits:
      return ros::message_traits::datatype<costmap_layers::SpeedLimits>();
    case InputKind::FilterInfo:
      return ros::message_traits::datatype<costmap_layers::CostmapFilterInfo>();
    case InputKind::Path:
      return ros::message_traits::datatype<nav_msgs::Path>();
    case InputKind::Odometry:
      return ros::message_traits::datatype<nav_msgs::Odometry>();
    case InputKind::LaserScan:
      return ros::message_traits::datatype<sensor_msgs::LaserScan>();
    case InputKind::PointCloud2:
      return ros::message_traits::datatype<sensor_msgs::PointCloud2>();
    case InputKind::PointCloud:
      return ros::message_traits::datatype<sensor_msgs::PointCloud>();
    case InputKind::Range:
      return ros::message_traits::datatype<sensor_msgs::Range>();
  }
  return "";
}

std::string portMessageType(OutputKind kind)
{
  switch (kind)
  {
    case OutputKind::MaxSpeed:
      return ros::message_traits::datatype<costmap_layers::MaxSpeed>();
    case OutputKind::SpeedLimit:
      return ros::message_traits::datatype<costmap_layers::Nav2SpeedLimit>();
    case OutputKind::ZoneState:
      return ros::message_traits::datatype<std_msgs::UInt8>();
    case OutputKind::BinaryState:
      return ros::message_traits::datatype<std_msgs::Bool>();
    case OutputKind::Setpoints:
      return "";
    case OutputKind::VoxelGrid:
      return ros::message_traits::datatype<costmap_layers::VoxelMap>();
    case OutputKind::VoxelMarkers:
      return ros::message_traits::datatype<visualization_msgs::Marker>();
    case OutputKind::VoxelCloud:
      return ros::message_traits::datatype<sensor_msgs::PointCloud2>();
  }
  return "";
}

std::vector<std::string> layerServices(const costmap_layers::Layer& layer)
{
  // A filter's one switch, under this package's name and under Nav2's (a Nav2 CostmapFilter's
  // `toggle_filter`, with its answers "Enabled" / "Disabled").
  if (dynamic_cast<const costmap_layers::CostmapFilter*>(&layer) != nullptr) return {"toggle", "toggle_filter"};
  return {};
}

LayerPorts::LayerPorts(ros::NodeHandle public_nh, ros::NodeHandle private_nh, costmap_layers::Layer& layer,
                       std::string global_frame, tf2_ros::Buffer& tf, std::shared_ptr<ThrottledLog> log,
                       std::string topic_ns)
    : public_nh_(std::move(public_nh)),
      private_nh_(std::move(private_nh)),
      layer_(layer),
      topic_ns_(std::move(topic_ns)),
      global_frame_(std::move(global_frame)),
      tf_(tf),
      log_(std::move(log))
{
  port_subscribers_.resize(layer.inputs().size());
  port_topics_.resize(layer.inputs().size());
  for (std::size_t i = 0; i < layer.inputs().size(); ++i)
  {
    const costmap_layers::InputPort& in = layer.inputs()[i];
    port_topics_[i] = resolveTopic(in.topic);
    switch (in.kind)
    {
      case InputKind::Map:
      case InputKind::Mask:
      case InputKind::MapUpdates:
      case InputKind::SpeedLimits:
      case InputKind::FilterInfo:
      case InputKind::Path:
      case InputKind::Odometry:
        port_subscribers_[i] = subscribe(in);
        break;
      case InputKind::LaserScan:
        subscribeSensor<sensor_msgs::LaserScan>(in.topic, in.sensor_frame, in.on_scan);
        break;
      case InputKind::PointCloud2:
        subscribeSensor<sensor_msgs::PointCloud2>(in.topic, in.sensor_frame, in.on_cloud);
        break;
      case InputKind::PointCloud:
        subscribeSensor<sensor_msgs::PointCloud>(in.topic, in.sensor_frame, in.on_cloud);
        break;
      case InputKind::Range:
        subscribeSensor<sensor_msgs::Range>(in.topic, "", in.on_range);
        break;
    }
  }
  // A port the layer replaces at run time (a filter whose filter info named the mask topic): the new
  // subscription starts (when it cannot, the old one stays), then the old one ends (roscpp waits for a
  // delivery in progress). Replacements of one layer arrive one at a time and in order
  // (Layer::setInputListener()). The receipts of a topic that only a replaced port read go with it, so
  // that a sender naming ever new topics cannot grow them.
  const std::size_t fixed_receipts = receipts_.size();
  layer.setInputListener(
      [this, fixed_receipts](std::size_t index, const costmap_layers::InputPort& port)
      {
        std::lock_guard<std::mutex> lock(ports_mutex_);
        if (index >= port_subscribers_.size()) return;
        ros::Subscriber next = subscribe(port);
        const std::string old_topic = port_topics_[index];
        port_subscribers_[index].shutdown();
        port_subscribers_[index] = next;
        port_topics_[index] = resolveTopic(port.topic);
        bool still_read = false;
        for (const std::string& t : port_topics_)
          still_read = still_read || t == old_topic;
        if (!still_read)
        {
          std::lock_guard<std::mutex> receipts_lock(receipts_mutex_);
          for (std::size_t k = fixed_receipts; k < receipts_.size(); ++k)
            if (receipts_[k].first == old_topic)
            {
              receipts_.erase(receipts_.begin() + static_cast<std::ptrdiff_t>(k));
              break;
            }
        }
        // A filter's deactivate() ends a subscription with an empty topic; one that had none yet
        // (a filter info that named no mask topic) changes nothing worth a line.
        if (port.topic.empty() && old_topic.empty()) return;
        // Each move is logged (each one matters), ending with the layer's stable key; a sender moving
        // the topic over and over gets kMovesLogged lines per kMovePeriod and then a count.
        constexpr std::size_t kMovesLogged = 10;
        constexpr double kMovePeriod = 10.0;                // [s]
        const double now = ros::SteadyTime::now().toSec();  // a step of the system clock must not silence it
        while (!move_log_times_.empty() && !(now - move_log_times_.front() < kMovePeriod))
          move_log_times_.pop_front();
        if (move_log_times_.size() >= kMovesLogged)
        {
          ++moves_unlogged_;
          return;
        }
        move_log_times_.push_back(now);
        const std::string& ns = private_nh_.getNamespace();
        std::string more;
        if (moves_unlogged_ > 0) more = " (and " + std::to_string(moves_unlogged_) + " moves before, not logged)";
        moves_unlogged_ = 0;
        const std::string what = port.topic.empty() ? "stopped reading " + old_topic : "now reading " + next.getTopic();
        ROS_INFO("%s: %s%s [%s/input]", ns.c_str(), what.c_str(), more.c_str(), ns.c_str());
      });
  for (const costmap_layers::OutputPort& out : layer.outputs())
  {
    const std::string topic = resolveTopic(out.topic);
    if (out.kind == costmap_layers::OutputKind::MaxSpeed)
      publishers_[{out.kind, out.topic}] = public_nh_.advertise<costmap_layers::MaxSpeed>(topic, 1, true);
    else if (out.kind == costmap_layers::OutputKind::SpeedLimit)
      publishers_[{out.kind, out.topic}] = public_nh_.advertise<costmap_layers::Nav2SpeedLimit>(topic, 1, true);
    else if (out.kind == costmap_layers::OutputKind::ZoneState)
      publishers_[{out.kind, out.topic}] = public_nh_.advertise<std_msgs::UInt8>(topic, 1, true);
    else if (out.kind == costmap_layers::OutputKind::Setpoints && !setpoints_)
      setpoints_ = std::make_unique<SetpointApplier>(public_nh_, private_nh_.getNamespace(), out.timeout, log_);
    else if (out.kind == costmap_layers::OutputKind::BinaryState)
      publishers_[{out.kind, out.topic}] = public_nh_.advertise<std_msgs::Bool>(topic, 1, true);
    else if (out.on_demand)
      publishers_[{out.kind, out.topic}] = advertiseOnDemand(out);
  }
  if (!publishers_.empty() || setpoints_)
    layer.setOutputListener([this](const costmap_layers::OutputEvent& e) { publish(e); });
  // A filter's one switch, as a service: the same flag as its `enabled` parameter; one handler for
  // every name layerServices() gives.
  if (auto* filter = dynamic_cast<costmap_layers::CostmapFilter*>(&layer))
  {
    const auto toggle = [filter](std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res)
    {
      filter->setEnabled(req.data);
      res.success = true;
      res.message = req.data ? "Enabled" : "Disabled";
      return true;
    };
    for (const std::string& name : layerServices(layer))
      toggles_.push_back(
          private_nh_.advertiseService<std_srvs::SetBool::Request, std_srvs::SetBool::Response>(name, toggle));
  }
}

ros::Publisher LayerPorts::advertiseOnDemand(const costmap_layers::OutputPort& out)
{
  // The layer builds the output only while someone subscribes: connections are counted as roscpp
  // reports them (on its callback threads; not after this object is gone: tracked by alive_).
  auto readers = std::make_shared<std::atomic<int>>(0);
  costmap_layers::Layer* layer = &layer_;
  const std::string key = out.topic;
  const auto connect = [readers, layer, key](const ros::SingleSubscriberPublisher&)
  { layer->setOutputWanted(key, ++*readers > 0); };
  const auto disconnect = [readers, layer, key](const ros::SingleSubscriberPublisher&)
  { layer->setOutputWanted(key, --*readers > 0); };
  ros::NodeHandle& nh = out.layer_namespace ? private_nh_ : public_nh_;
  const std::string topic = out.layer_namespace ? out.topic : resolveTopic(out.topic);
  ros::AdvertiseOptions options;
  if (out.kind == costmap_layers::OutputKind::VoxelGrid)
    options.init<costmap_layers::VoxelMap>(topic, 1, connect, disconnect);
  else if (out.kind == costmap_layers::OutputKind::VoxelMarkers)
    options.init<visualization_msgs::Marker>(topic, 1, connect, disconnect);
  else
    options.init<sensor_msgs::PointCloud2>(topic, 1, connect, disconnect);
  options.tracked_object = alive_;
  return nh.advertise(options);
}

std::string LayerPorts::resolveTopic(const std::string& topic) const
{
  if (topic_ns_.empty() || topic.empty() || topic[0] == '/' || topic[0] == '~') return topic;
  return ros::names::append(topic_ns_, topic);
}

std::shared_ptr<LayerPorts::Receipts> LayerPorts::receiptsFor(const std::string& topic)
{
  const std::string resolved = resolveTopic(topic);
  std::lock_guard<std::mutex> lock(receipts_mutex_);
  for (const auto& [t, r] : receipts_)
    if (t == resolved) return r;
  receipts_.emplace_back(resolved, std::make_shared<Receipts>());
  return receipts_.back().second;
}

std::vector<std::pair<std::string, std::string>> LayerPorts::receipts() const
{
  std::vector<std::pair<std::string, std::string>> out;
  const double now = ros::SteadyTime::now().toSec();
  std::lock_guard<std::mutex> lock(receipts_mutex_);
  for (const auto& [topic, r] : receipts_)
  {
    out.emplace_back("received on " + public_nh_.resolveName(topic), receiptText(r->count.load(), r->last.load(), now));
  }
  return out;
}

LayerPorts::~LayerPorts()
{
  layer_.setInputListener({});
  if (!publishers_.empty() || setpoints_) layer_.setOutputListener({});
  for (const costmap_layers::OutputPort& out : layer_.outputs())
    if (out.on_demand) layer_.setOutputWanted(out.topic, false);
}

void LayerPorts::publish(const costmap_layers::OutputEvent& e)
{
  if (e.kind == costmap_layers::OutputKind::Setpoints)
  {
    // Handed to the worker: the update thread never waits for another node.
    if (setpoints_) setpoints_->submit(e.setpoints, e.label);
    return;
  }
  const auto it = publishers_.find({e.kind, e.topic});
  if (it == publishers_.end()) return;
  if (e.voxels)
  {
    publishVoxels(e, it->second);
    return;
  }
  if (e.kind == costmap_layers::OutputKind::ZoneState)
  {
    std_msgs::UInt8 msg;
    msg.data = static_cast<uint8_t>(e.value);
    it->second.publish(msg);
    return;
  }
  if (e.kind == costmap_layers::OutputKind::BinaryState)
  {
    std_msgs::Bool msg;
    msg.data = e.state;
    it->second.publish(msg);
    return;
  }
  if (e.kind == costmap_layers::OutputKind::SpeedLimit)
  {
    costmap_layers::Nav2SpeedLimit msg;
    msg.header.frame_id = global_frame_;
    msg.header.stamp = ros::Time::now();
    msg.percentage = e.percentage;
    msg.speed_limit = e.value;
    it->second.publish(msg);
    return;
  }
  costmap_layers::MaxSpeed msg;
  msg.header.frame_id = global_frame_;
  msg.header.stamp = ros::Time::now();
  msg.max_speed = e.value;
  it->second.publish(msg);
}

void LayerPorts::publishVoxels(const costmap_layers::OutputEvent& e, ros::Publisher& pub)
{
  if (pub.getNumSubscribers() == 0) return;  // the last reader left since the layer asked
  const ros::Time stamp = ros::Time::now();
  std::size_t left_out = 0;
  if (e.kind == costmap_layers::OutputKind::VoxelGrid)
    pub.publish(toVoxelGridMsg(*e.voxels, global_frame_, stamp));
  else if (e.kind == costmap_layers::OutputKind::VoxelMarkers)
  {
    visualization_msgs::Marker marker;
    left_out = toVoxelMarker(*e.voxels, global_frame_, stamp, layer_.getName(), marker);
    pub.publish(marker);
  }
  else if (e.kind == costmap_layers::OutputKind::VoxelCloud)
  {
    sensor_msgs::PointCloud2 cloud;
    left_out = toVoxelCloud(*e.voxels, global_frame_, stamp, cloud);
    pub.publish(cloud);
  }
  if (left_out > 0)
    log_->log(costmap_layers::Severity::Warn, private_nh_.getNamespace() + "/" + e.topic,
              private_nh_.resolveName(e.topic) + ": " + std::to_string(left_out) + " marked voxels left out: at most " +
                  std::to_string(costmap_layers::kMaxVoxelPoints) + " are drawn (voxel_grid carries them all)");
}

ros::Subscriber LayerPorts::subscribe(const costmap_layers::InputPort& in)
{
  if (in.topic.empty()) return {};  // not connected yet: the layer replaces the port later
  switch (in.kind)
  {
    case InputKind::Map:
    case InputKind::Mask:
      return subscribePort<nav_msgs::OccupancyGrid>(in.topic, 1, in.on_grid);
    case InputKind::MapUpdates:
      return subscribePort<map_msgs::OccupancyGridUpdate>(in.topic, 10, in.on_update);
    case InputKind::SpeedLimits:
      return subscribePort<costmap_layers::SpeedLimits>(in.topic, 1, in.on_limits);
    case InputKind::FilterInfo:
      // Several infos may be latched on one topic (one per info server): keep them all.
      return subscribePort<costmap_layers::CostmapFilterInfo>(in.topic, 10, in.on_info);
    case InputKind::Path:
      return subscribePort<nav_msgs::Path>(in.topic, 1, in.on_path);
    case InputKind::Odometry:
      return subscribePort<nav_msgs::Odometry>(in.topic, 10, in.on_odom);
    default:
      return {};  // sensors go through subscribeSensor()
  }
}

template <class Msg, class Callback>
ros::Subscriber LayerPorts::subscribePort(const std::string& topic, uint32_t queue, Callback cb)
{
  const PortSource source{private_nh_.getNamespace(), topic, log_};
  auto receipts = receiptsFor(topic);
  return public_nh_.subscribe<Msg>(resolveTopic(topic), queue,
                                   [cb, source, receipts](const typename Msg::ConstPtr& msg)
                                   {
                                     receipts->note();
                                     dispatch(*msg, cb, source);
                                   });
}

namespace
{
/// A tf gate fed by a subscription whose messages go straight from roscpp's network thread into the
/// gate (InlineCallbackQueue), and retried whenever tf changes. Declared in this order so that the
/// subscription ends before its queue, and both and the wake before the gate; callbacks still in flight
/// hold the gate through their own reference, and those that come after it is gone do nothing.
template <class Msg>
struct SubscribedGate
{
  std::shared_ptr<TfGate<Msg>> gate;
  std::unique_ptr<TfChangeWake> wake;
  std::unique_ptr<InlineCallbackQueue> queue;
  ros::Subscriber subscriber;
};
}  // namespace

template <class Msg, class Reading>
void LayerPorts::subscribeSensor(const std::string& topic, const std::string& sensor_frame,
                                 costmap_layers::SensorCallback<Reading> cb)
{
  const PortSource source{private_nh_.getNamespace(), topic, log_};
  const std::string global = global_frame_;
  tf2::BufferCore& tf = tf_;
  auto ready = [=, &tf](const typename Msg::ConstPtr& msg)
  { dispatchReading(msg, tf, global, sensor_frame, cb, source); };
  auto failed = [=](const typename Msg::ConstPtr& msg, TfVerdict verdict)
  {
    reportDroppedReading(msg->header.frame_id, msg->header.stamp, verdict, ros::Time::now(), global, sensor_frame,
                         source);
  };
  auto in = std::make_shared<SubscribedGate<Msg>>();
  in->gate = std::make_shared<TfGate<Msg>>(tf_, global_frame_, sensor_frame, ready, failed);
  std::weak_ptr<TfGate<Msg>> weak = in->gate;
  // Readings that wait for tf are retried in the thread that brings the transform (the tf listener's callback),
  // at once and with no timer.
  in->wake = std::make_unique<TfChangeWake>(tf_,
                                            [weak]
                                            {
                                              const auto g = weak.lock();
                                              if (g) g->arrive(nullptr);
                                            });
  auto receipts = receiptsFor(topic);
  const std::shared_ptr<ThrottledLog> log = log_;
  const std::string key = source.owner + topic + "/callback", what = source.owner + ": on " + topic + ": ";
  in->queue = std::make_unique<InlineCallbackQueue>(
      [log, key, what](const std::string& problem) { log->log(costmap_layers::Severity::Error, key, what + problem); });
  ros::SubscribeOptions options;
  options.template init<Msg>(resolveTopic(topic), 5,
                             [weak, receipts](const typename Msg::ConstPtr& msg)
                             {
                               receipts->note();
                               if (const auto g = weak.lock()) g->arrive(msg);
                             });
  options.callback_queue = in->queue.get();
  options.allow_concurrent_callbacks = true;  // the gate has a lock of its own; see InlineCallbackQueue
  in->subscriber = public_nh_.subscribe(options);
  sensor_inputs_.push_back(in);
}
}  // namespace costmap_layers_ros
