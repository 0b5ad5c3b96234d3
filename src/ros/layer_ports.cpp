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
#include <tf2/exceptions.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <mutex>
#include <type_traits>

#include "costmap_layers/CostmapFilterInfo.h"
#include "costmap_layers/MaxSpeed.h"
#include "costmap_layers/Nav2SpeedLimit.h"
#include "costmap_layers/SpeedLimits.h"
#include "costmap_layers/core/filters/costmap_filter.hpp"
#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/ros/conversions.hpp"
#include "costmap_layers/ros/tf_verdict.hpp"

namespace costmap_layers_ros
{
using costmap_layers::InputKind;
using costmap_layers::Severity;

TfVerdict tfVerdict(tf2::BufferCore& tf, const std::string& target, const std::string& frame, const ros::Time& stamp,
                    const ros::Time& now, double max_ahead)
{
  if (frame.empty()) return TfVerdict::NoFrame;
  if (secondsBetween(stamp, now) > max_ahead) return TfVerdict::Future;
  try
  {
    if (tf.canTransform(target, frame, stamp)) return TfVerdict::Ready;
  }
  catch (const std::exception&)
  {
    // tf2 computes with ROS time, which throws beyond 32-bit seconds (a stamp decades before now)
    return TfVerdict::BadStamp;
  }
  try
  {
    // The newest transform tf has between the frames; the reading is beyond hope when even the
    // oldest one tf still keeps is newer than it.
    const ros::Time latest = tf.lookupTransform(target, frame, ros::Time(0)).header.stamp;
    if (!latest.isZero() && secondsBetween(latest, stamp) > tf.getCacheLength().toSec()) return TfVerdict::TooOld;
  }
  catch (const std::exception&)
  {
    // frames not connected (yet): wait
  }
  return TfVerdict::Wait;
}

TfVerdict gateVerdict(tf2::BufferCore& tf, const std::string& target, const std::string& frame,
                      const std::string& sensor_frame, const ros::Time& stamp, const ros::Time& now, double max_ahead)
{
  const TfVerdict v = tfVerdict(tf, target, frame, stamp, now, max_ahead);
  if (v != TfVerdict::Ready || sensor_frame.empty() || sensor_frame == frame) return v;
  return tfVerdict(tf, target, sensor_frame, stamp, now, max_ahead);
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
        ROS_INFO("%s: now reading %s%s [%s/input]", ns.c_str(), next.getTopic().c_str(), more.c_str(), ns.c_str());
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
  }
  if (!publishers_.empty() || setpoints_)
    layer.setOutputListener([this](const costmap_layers::OutputEvent& e) { publish(e); });
  // A filter's one switch, as a service: the same flag as its `enabled` parameter. Under this
  // package's name `toggle` and under Nav2's `toggle_filter` (a Nav2 CostmapFilter's service, with its
  // answers "Enabled" / "Disabled"), one handler.
  if (auto* filter = dynamic_cast<costmap_layers::CostmapFilter*>(&layer))
  {
    const auto toggle = [filter](std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res)
    {
      filter->setEnabled(req.data);
      res.success = true;
      res.message = req.data ? "Enabled" : "Disabled";
      return true;
    };
    for (const char* name : {"toggle", "toggle_filter"})
      toggles_.push_back(
          private_nh_.advertiseService<std_srvs::SetBool::Request, std_srvs::SetBool::Response>(name, toggle));
  }
}

std::string LayerPorts::resolveTopic(const std::string& topic) const
{
  if (topic_ns_.empty() || topic.empty() || topic[0] == '/' || topic[0] == '~') return topic;
  return ros::names::append(topic_ns_, topic);
}

void LayerPorts::Receipts::note()
{
  count.fetch_add(1);
  // Arrival on the steady clock: the age shown is real time since the message came, also under
  // /use_sim_time or after a clock jump (ROS time behind the last arrival would read 0 s for as long).
  last.store(ros::SteadyTime::now().toSec());
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
    const uint64_t n = r->count.load();
    char text[96];
    if (n == 0)
      std::snprintf(text, sizeof(text), "nothing yet");
    else
      std::snprintf(text, sizeof(text), "%llu message(s), last %.2f s ago", static_cast<unsigned long long>(n),
                    std::max(0.0, now - r->last.load()));
    out.emplace_back("received on " + public_nh_.resolveName(topic), text);
  }
  return out;
}

LayerPorts::~LayerPorts()
{
  layer_.setInputListener({});
  if (!publishers_.empty() || setpoints_) layer_.setOutputListener({});
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

ros::Subscriber LayerPorts::subscribe(const costmap_layers::InputPort& in)
{
  if (in.topic.empty()) return {};  // not connected yet: the layer replaces the port later
  switch (in.kind)
  {
    case InputKind::Map:
    case InputKind::Mask:
      return subscribeGrid(in.topic, in.on_grid);
    case InputKind::MapUpdates:
      return subscribeGridUpdates(in.topic, in.on_update);
    case InputKind::SpeedLimits:
      return subscribeSpeedLimits(in.topic, in.on_limits);
    case InputKind::FilterInfo:
      return subscribeFilterInfo(in.topic, in.on_info);
    case InputKind::Path:
      return subscribeTyped<nav_msgs::Path>(in.topic, "a path", in.on_path, 1);
    case InputKind::Odometry:
      return subscribeTyped<nav_msgs::Odometry>(in.topic, "odometry", in.on_odom, 10);
    default:
      return {};  // sensors go through subscribeSensor()
  }
}

ros::Subscriber LayerPorts::subscribeGrid(const std::string& topic, costmap_layers::GridCallback cb)
{
  const std::string owner = private_nh_.getNamespace();
  auto receipts = receiptsFor(topic);
  return (public_nh_.subscribe<nav_msgs::OccupancyGrid>(
      resolveTopic(topic), 1,
      [cb, owner, topic, receipts, log = log_](const nav_msgs::OccupancyGrid::ConstPtr& msg)
      {
        receipts->note();
        try
        {
          std::string note;
          auto grid = std::make_shared<const costmap_layers::OccupancyGridData>(fromMsg(*msg, &note));
          if (!note.empty())
            log->log(Severity::Warn, owner + topic + "/info.origin.orientation",
                     owner + ": grid on " + topic + ": " + note);
          cb(grid);
        }
        catch (const std::exception& e)
        {
          log->log(Severity::Error, owner + topic, owner + ": dropped a grid on " + topic + ": " + e.what());
        }
      }));
}

ros::Subscriber LayerPorts::subscribeGridUpdates(const std::string& topic, costmap_layers::GridUpdateCallback cb)
{
  const std::string owner = private_nh_.getNamespace();
  auto receipts = receiptsFor(topic);
  return (public_nh_.subscribe<map_msgs::OccupancyGridUpdate>(
      resolveTopic(topic), 10,
      [cb, owner, topic, receipts, log = log_](const map_msgs::OccupancyGridUpdate::ConstPtr& msg)
      {
        receipts->note();
        try
        {
          cb(std::make_shared<const costmap_layers::OccupancyGridUpdateData>(fromMsg(*msg)));
        }
        catch (const std::exception& e)
        {
          log->log(Severity::Error, owner + topic, owner + ": dropped a map update on " + topic + ": " + e.what());
        }
      }));
}

ros::Subscriber LayerPorts::subscribeFilterInfo(const std::string& topic, costmap_layers::FilterInfoCallback cb)
{
  const std::string owner = private_nh_.getNamespace();
  auto receipts = receiptsFor(topic);
  // Several infos may be latched on one topic (one per info server): keep them all.
  return public_nh_.subscribe<costmap_layers::CostmapFilterInfo>(
      resolveTopic(topic), 10,
      [cb, owner, topic, receipts, log = log_](const costmap_layers::CostmapFilterInfo::ConstPtr& msg)
      {
        receipts->note();
        try
        {
          cb(std::make_shared<const costmap_layers::FilterInfoData>(fromMsg(*msg)));
        }
        catch (const std::exception& e)
        {
          log->log(Severity::Error, owner + topic, owner + ": dropped a filter info on " + topic + ": " + e.what());
        }
      });
}

ros::Subscriber LayerPorts::subscribeSpeedLimits(const std::string& topic, costmap_layers::SpeedLimitsCallback cb)
{
  const std::string owner = private_nh_.getNamespace();
  auto receipts = receiptsFor(topic);
  return (public_nh_.subscribe<costmap_layers::SpeedLimits>(
      resolveTopic(topic), 1,
      [cb, owner, topic, receipts, log = log_](const costmap_layers::SpeedLimits::ConstPtr& msg)
      {
        receipts->note();
        try
        {
          cb(std::make_shared<const costmap_layers::SpeedLimitsData>(fromMsg(*msg)));
        }
        catch (const std::exception& e)
        {
          log->log(Severity::Error, owner + topic, owner + ": dropped speed limits on " + topic + ": " + e.what());
        }
      }));
}

template <class Msg, class Callback>
ros::Subscriber LayerPorts::subscribeTyped(const std::string& topic, const std::string& what, Callback cb,
                                           uint32_t queue)
{
  const std::string owner = private_nh_.getNamespace();
  auto receipts = receiptsFor(topic);
  return public_nh_.subscribe<Msg>(resolveTopic(topic), queue,
                                   [cb, owner, topic, what, receipts, log = log_](const typename Msg::ConstPtr& msg)
                                   {
                                     receipts->note();
                                     try
                                     {
                                       using Data = typename std::decay_t<decltype(fromMsg(*msg))>;
                                       cb(std::make_shared<const Data>(fromMsg(*msg)));
                                     }
                                     catch (const std::exception& e)
                                     {
                                       log->log(Severity::Error, owner + topic,
                                                owner + ": dropped " + what + " on " + topic + ": " + e.what());
                                     }
                                   });
}

namespace
{
/// Holds each reading until tf can place it, then hands it on in arrival order; the readings tf will
/// never place are handed to the failure callback. This replaces tf2_ros::MessageFilter, whose
/// addTransformableRequest() in Debian's tf2 (0.7.6) reads tf's frame table without tf's lock, a race
/// with the tf listener adding frames that TSan reports (fixed upstream in 0.7.10, ros/geometry2#539).
/// Only tf2's public, locked calls are used here: canTransform(), lookupTransform(), getCacheLength().
template <class Msg>
class TfGate : public std::enable_shared_from_this<TfGate<Msg>>
{
public:
  using Ptr = typename Msg::ConstPtr;
  static constexpr std::size_t kQueue = 10;     ///< readings that may wait for tf at once
  static constexpr double kRetryPeriod = 0.02;  ///< [s] how often waiting readings are retried
  /// [s] how far a reading's stamp may lie ahead of now (see kGateMaxAhead). tf's canTransform() is true
  /// at any stamp between a frame and itself, so without this a reading from the future would pass (and,
  /// buffered, look fresh until the clock caught up with it).
  static constexpr double kMaxAhead = kGateMaxAhead;

  static std::shared_ptr<TfGate> create(ros::NodeHandle& nh, const std::string& topic, tf2_ros::Buffer& tf,
                                        std::string target, std::string sensor_frame,
                                        std::function<void(const Ptr&)> ready,
                                        std::function<void(const Ptr&, TfVerdict)> failed,
                                        std::shared_ptr<LayerPorts::Receipts> receipts)
  {
    std::shared_ptr<TfGate> gate(
        new TfGate(tf, std::move(target), std::move(sensor_frame), std::move(ready), std::move(failed)));
    std::weak_ptr<TfGate> weak = gate;  // callbacks still in flight after destruction do nothing
    gate->subscriber_ = nh.subscribe<Msg>(topic, 5,
                                          [weak, receipts](const Ptr& msg)
                                          {
                                            receipts->note();
                                            if (auto g = weak.lock()) g->arrive(msg);
                                          });
    gate->timer_ = nh.createWallTimer(ros::WallDuration(kRetryPeriod),
                                      [weak](const ros::WallTimerEvent&)
                                      {
                                        if (auto g = weak.lock()) g->arrive(nullptr);
                                      });
    return gate;
  }

private:
  TfGate(tf2_ros::Buffer& tf, std::string target, std::string sensor_frame, std::function<void(const Ptr&)> ready,
         std::function<void(const Ptr&, TfVerdict)> failed)
      : tf_(tf),
        target_(std::move(target)),
        sensor_frame_(std::move(sensor_frame)),
        ready_(std::move(ready)),
        failed_(std::move(failed))
  {
  }

  TfVerdict check(const Msg& msg) const
  {
    return gateVerdict(tf_, target_, msg.header.frame_id, sensor_frame_, msg.header.stamp, ros::Time::now(), kMaxAhead);
  }

  /// Queues msg (when not null) and hands on, in order, every waiting reading tf can now place. One
  /// lock for queue and delivery: the layer sees one input's readings one at a time and in order.
  void arrive(const Ptr& msg)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (msg) waiting_.push_back(msg);
    std::deque<Ptr> still;
    for (const Ptr& m : waiting_)
    {
      // Nothing a reading carries may escape into roscpp's spinner thread (that would end the node):
      // a reading the rule or its callbacks throw on is dropped as one tf cannot place.
      try
      {
        const TfVerdict v = check(*m);
        if (v == TfVerdict::Ready)
          ready_(m);
        else if (v == TfVerdict::Wait)
          still.push_back(m);
        else
          failed_(m, v);
      }
      catch (const std::exception&)
      {
        try
        {
          failed_(m, TfVerdict::BadStamp);
        }
        catch (const std::exception&)
        {
          // dropped; the report itself failed (out of memory)
        }
      }
    }
    while (still.size() > kQueue)
    {
      failed_(still.front(), TfVerdict::PushedOut);
      still.pop_front();
    }
    waiting_.swap(still);
  }

  tf2_ros::Buffer& tf_;
  const std::string target_;
  const std::string sensor_frame_;  ///< the readings' origin frame when not their own (may be empty)
  const std::function<void(const Ptr&)> ready_;
  const std::function<void(const Ptr&, TfVerdict)> failed_;
  std::mutex mutex_;
  std::deque<Ptr> waiting_;
  ros::Subscriber subscriber_;
  ros::WallTimer timer_;
};
}  // namespace

template <class Msg, class Reading>
void LayerPorts::subscribeSensor(const std::string& topic, const std::string& sensor_frame,
                                 costmap_layers::SensorCallback<Reading> cb)
{
  const std::string owner = private_nh_.getNamespace();
  const std::string global = global_frame_;
  tf2_ros::Buffer& tf = tf_;
  auto log = log_;
  auto ready = [=, &tf](const typename Msg::ConstPtr& msg)
  {
    try
    {
      costmap_layers::SensorPose pose;
      const std::string& frame = msg->header.frame_id;
      pose.to_global = fromMsg(tf.lookupTransform(global, frame, msg->header.stamp).transform);
      const std::string origin_frame = sensor_frame.empty() ? frame : sensor_frame;
      // The gate let it through once tf could place both frames at the stamp: no waiting here.
      const auto origin = tf.lookupTransform(global, origin_frame, msg->header.stamp);
      pose.origin_x = origin.transform.translation.x;
      pose.origin_y = origin.transform.translation.y;
      pose.origin_z = origin.transform.translation.z;
      cb(std::make_shared<const Reading>(fromMsg(*msg)), pose);
    }
    catch (const std::exception& e)
    {
      log->log(Severity::Warn, owner + topic + "/tf",
               owner + ": dropped a reading on " + topic + " (frame " +
                   costmap_layers::shownText(msg->header.frame_id) + "): " + costmap_layers::shownText(e.what(), 400));
    }
  };
  auto failed = [=](const typename Msg::ConstPtr& msg, TfVerdict verdict)
  {
    // Each reason is its own throttled report, so that a stale stamp does not hide a wrong frame.
    std::string key = owner + topic + "/tf/", why;
    const ros::Time stamp = msg->header.stamp;
    const double behind = secondsBetween(ros::Time::now(), stamp);
    char when[96];
    std::snprintf(when, sizeof(when), "header.stamp %.3f s (%.3f s %s now)", stamp.toSec(), std::fabs(behind),
                  behind >= 0.0 ? "before" : "after");
    switch (verdict)
    {
      case TfVerdict::NoFrame:
        key += "frame_id";
        why = "header.frame_id is empty";
        break;
      case TfVerdict::TooOld:
        key += "stamp";
        why = std::string(when) + " is older than every transform tf keeps";
        break;
      case TfVerdict::BadStamp:
        key += "stamp";
        why = std::string(when) + " is beyond what tf can compute with";
        break;
      case TfVerdict::Future:
        key += "future";
        why = std::string(when) + " is more than " + costmap_layers::valueText(TfGate<Msg>::kMaxAhead) +
              " s ahead of the clock (a wrong sensor clock, or the clock jumped back)";
        break;
      default:
        key += "wait";
        why = std::string("no transform at ") + when + " arrived while " + std::to_string(TfGate<Msg>::kQueue) +
              " newer readings waited";
        break;
    }
    log->log(Severity::Warn, key,
             owner + ": dropped a reading on " + topic + ": cannot transform frame '" +
                 costmap_layers::shownText(msg->header.frame_id) + "'" +
                 (sensor_frame.empty() ? std::string() : " (sensor_frame '" + sensor_frame + "')") + " into '" +
                 global + "': " + why);
  };
  sensor_inputs_.push_back(TfGate<Msg>::create(public_nh_, resolveTopic(topic), tf_, global_frame_, sensor_frame, ready,
                                               failed, receiptsFor(topic)));
}
}  // namespace costmap_layers_ros
