#include "costmap_layers/ros/setpoint_applier.hpp"

#include "costmap_layers/ros/layer_reconfigure.hpp"

#include <ros/callback_queue.h>
#include <ros/connection.h>
#include <ros/service_manager.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "costmap_layers/core/config/input_error.hpp"

namespace costmap_layers_ros
{
using costmap_layers::ParamValue;
using costmap_layers::Setpoint;

namespace
{
/// The value of a named parameter in a Config, as a ParamValue (Null when absent).
ParamValue find(const dynamic_reconfigure::Config& c, const std::string& name)
{
  for (const auto& p : c.bools)
    if (p.name == name) return ParamValue::makeBool(p.value);
  for (const auto& p : c.ints)
    if (p.name == name) return ParamValue::makeInt(p.value);
  for (const auto& p : c.doubles)
    if (p.name == name) return ParamValue::makeDouble(p.value);
  for (const auto& p : c.strs)
    if (p.name == name) return ParamValue::makeString(p.value);
  return {};
}

bool sameValue(const ParamValue& a, const ParamValue& b)
{
  if (a.isNumber() && b.isNumber())
  {
    const double x = a.asDouble(), y = b.asDouble();
    return std::abs(x - y) <= 1e-9 * std::max({1.0, std::abs(x), std::abs(y)});
  }
  if (a.type() != b.type()) return false;
  if (a.type() == ParamValue::Type::Bool) return a.asBool() == b.asBool();
  if (a.type() == ParamValue::Type::String) return a.asString() == b.asString();
  return false;
}

/// now + seconds on the steady clock.
std::chrono::steady_clock::time_point after(std::chrono::steady_clock::time_point t, double seconds)
{
  return t + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
}

/// How many of a server's parameter names an error lists.
constexpr std::size_t kListed = 20;

std::string show(const Setpoint& s)
{
  return s.node + " " + s.parameter + " = " + s.value.toString();
}
}  // namespace

SetpointApplier::SetpointApplier(ros::NodeHandle nh, std::string key_prefix, double timeout,
                                 std::shared_ptr<ThrottledLog> log)
    : nh_(std::move(nh)), key_prefix_(std::move(key_prefix)), timeout_(timeout), log_(std::move(log))
{
  worker_ = std::thread([this] { run(); });
  watchdog_ = std::thread([this] { watchCalls(); });
}

SetpointApplier::~SetpointApplier()
{
  ros::ServiceServerLinkPtr link;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    link = std::move(link_);
    link_.reset();
  }
  wake_.notify_all();
  watch_wake_.notify_all();
  // Outside the lock: roscpp ends the worker's call and waits for it to return.
  if (link) link->getConnection()->drop(ros::Connection::Destructing);
  if (watchdog_.joinable()) watchdog_.join();
  if (worker_.joinable()) worker_.join();
}

void SetpointApplier::submit(std::vector<Setpoint> set, std::string label)
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    due_ = nodesOf(set);
    latest_ = std::move(set);
    latest_label_ = std::move(label);
  }
  wake_.notify_all();
}

std::vector<std::string> SetpointApplier::nodesOf(const std::vector<Setpoint>& set)
{
  std::vector<std::string> nodes;
  for (const auto& s : set)
    if (std::find(nodes.begin(), nodes.end(), s.node) == nodes.end()) nodes.push_back(s.node);
  return nodes;
}

std::string SetpointApplier::nextNode(const std::vector<std::string>& order, const std::vector<std::string>& due,
                                      const std::string& last)
{
  if (order.empty()) return "";
  const auto at = std::find(order.begin(), order.end(), last);
  const std::size_t first = at == order.end() ? 0 : static_cast<std::size_t>(at - order.begin()) + 1;
  for (std::size_t k = 0; k < order.size(); ++k)
  {
    const std::string& node = order[(first + k) % order.size()];
    if (std::find(due.begin(), due.end(), node) != due.end()) return node;
  }
  return "";
}

std::string SetpointApplier::keyOf(const Setpoint& s) const
{
  std::string node = s.node;
  while (!node.empty() && (node.front() == '/' || node.front() == '~'))
    node.erase(node.begin());
  return key_prefix_ + "/setpoint/" + node + "/" + s.parameter;
}

void SetpointApplier::fail(const Setpoint& s, const std::string& why)
{
  log_->log(costmap_layers::Severity::Error, keyOf(s), key_prefix_ + ": setting " + show(s) + " failed: " + why);
}

dynamic_reconfigure::Config SetpointApplier::request(const std::vector<Setpoint>& setpoints)
{
  dynamic_reconfigure::Config c;
  for (const auto& s : setpoints)
    addToConfig(c, s.parameter, s.value);
  return c;
}

std::string SetpointApplier::checkAgainst(const Setpoint& s, const dynamic_reconfigure::ConfigDescription& d)
{
  const dynamic_reconfigure::ParamDescription* found = nullptr;
  std::string names;
  std::size_t count = 0;
  for (const auto& g : d.groups)
    for (const auto& p : g.parameters)
    {
      if (count++ < kListed) names += (names.empty() ? "" : ", ") + costmap_layers::shownText(p.name);
      if (p.name == s.parameter) found = &p;
    }
  if (count > kListed) names += " and " + std::to_string(count - kListed) + " more";
  if (!found) return "the server has no parameter '" + s.parameter + "' (it has: " + names + ")";
  const std::string want = reconfigureTypeName(s.value.type());
  if (found->type != want)
    return "the server's '" + s.parameter + "' is of type " + costmap_layers::shownText(found->type) +
           ", the value is of type " + want + (found->type == "double" && want == "int" ? " (write 1.0, not 1)" : "");
  if (s.value.isNumber())
  {
    const ParamValue lo = find(d.min, s.parameter), hi = find(d.max, s.parameter);
    const double v = s.value.asDouble();
    if (lo.isNumber() && hi.isNumber() && (v < lo.asDouble() || v > hi.asDouble()))
    {
      std::ostringstream o;
      o << "out of the server's range [" << lo.asDouble() << ", " << hi.asDouble() << "]: not sent";
      return o.str();
    }
  }
  return "";
}

std::string SetpointApplier::checkAnswer(const Setpoint& s, const dynamic_reconfigure::Config& answer)
{
  const ParamValue got = find(answer, s.parameter);
  if (got.isNull()) return "the server's answer has no parameter '" + s.parameter + "' (unknown to it)";
  if (!sameValue(got, s.value)) return "the server refused it and holds " + costmap_layers::shownText(got.toString());
  return "";
}

bool SetpointApplier::stopping()
{
  std::lock_guard<std::mutex> lock(mutex_);
  return stop_;
}

void SetpointApplier::run()
{
  for (;;)
  {
    std::string node, label;
    std::vector<Setpoint> mine;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stop_ || !due_.empty(); });
      if (stop_) return;
      node = nextNode(nodesOf(latest_), due_, last_node_);
      due_.erase(std::remove(due_.begin(), due_.end(), node), due_.end());
      last_node_ = node;
      for (const auto& s : latest_)
        if (s.node == node) mine.push_back(s);
      label = latest_label_;
    }
    if (!mine.empty()) applyNode(node, mine, label);
  }
}

dynamic_reconfigure::ConfigDescriptionConstPtr SetpointApplier::waitForDescription(const std::string& topic)
{
  // ros::topic::waitForMessage, on a queue of its own, in short slices so that a stop ends the wait.
  ros::CallbackQueue queue;
  ros::NodeHandle nh(nh_);
  nh.setCallbackQueue(&queue);
  dynamic_reconfigure::ConfigDescriptionConstPtr got;
  const ros::Subscriber sub = nh.subscribe<dynamic_reconfigure::ConfigDescription>(
      topic, 1, [&got](const dynamic_reconfigure::ConfigDescriptionConstPtr& m) { got = m; });
  const auto deadline = after(std::chrono::steady_clock::now(), timeout_);
  while (!got && ros::ok() && !stopping() && std::chrono::steady_clock::now() < deadline)
    queue.callAvailable(ros::WallDuration(0.05));
  return got;
}

bool SetpointApplier::waitForService(const std::string& service)
{
  const auto deadline = after(std::chrono::steady_clock::now(), timeout_);
  for (;;)
  {
    if (!ros::ok() || stopping()) return false;
    if (ros::service::exists(service, false)) return true;
    std::unique_lock<std::mutex> lock(mutex_);
    const auto next = std::min(deadline, std::chrono::steady_clock::now() + std::chrono::milliseconds(100));
    wake_.wait_until(lock, next, [this] { return stop_; });
    if (std::chrono::steady_clock::now() >= deadline) return false;
  }
}

bool SetpointApplier::call(const std::string& service, const std::vector<Setpoint>& to_send,
                           dynamic_reconfigure::Reconfigure& srv, bool* abandoned)
{
  *abandoned = false;
  // ServiceClient::call, except that the link is kept where the watchdog and the destructor can drop
  // it: a roscpp call has no timeout of its own, and a server that never answers would hold the worker.
  const std::string md5 = ros::service_traits::md5sum<dynamic_reconfigure::Reconfigure>();
  const ros::ServiceServerLinkPtr link =
      ros::ServiceManager::instance()->createServiceServerLink(service, false, md5, md5, ros::M_string());
  if (!link) return false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stop_)
    {
      link->getConnection()->drop(ros::Connection::Destructing);  // roscpp keeps the link till it drops
      return false;
    }
    calling_ = to_send;
    calling_service_ = service;
    call_started_ = std::chrono::steady_clock::now();
    link_ = link;
  }
  watch_wake_.notify_all();
  const ros::SerializedMessage request = ros::serialization::serializeMessage(srv.request);
  ros::SerializedMessage response;
  const bool answered = link->call(request, response);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    *abandoned = link_ != link;  // the watchdog (or the destructor) took the link and dropped it
    calling_.clear();
    link_.reset();
  }
  if (!answered) return false;
  try
  {
    ros::serialization::deserializeMessage(response, srv.response);
  }
  catch (const std::exception&)
  {
    return false;
  }
  return true;
}

void SetpointApplier::applyNode(const std::string& node, const std::vector<Setpoint>& setpoints,
                                const std::string& label)
{
  if (!ros::ok()) return;
  const std::string resolved = nh_.resolveName(node);
  const std::string service = resolved + "/set_parameters";
  // 1. The description: what the server declares.
  std::vector<Setpoint> to_send;
  const auto description = waitForDescription(resolved + "/parameter_descriptions");
  if (!description)
  {
    if (stopping()) return;
    for (const auto& s : setpoints)
      fail(s, "no dynamic_reconfigure server at " + resolved + " (nothing on " + resolved +
                  "/parameter_descriptions within " + std::to_string(timeout_) + " s)");
    return;
  }
  for (const auto& s : setpoints)
  {
    const std::string why = checkAgainst(s, *description);
    if (why.empty())
      to_send.push_back(s);
    else
      fail(s, why);
  }
  if (to_send.empty()) return;
  // 2. The call.
  if (!waitForService(service))
  {
    if (stopping()) return;
    for (const auto& s : to_send)
      fail(s, "the service " + service + " did not appear within " + std::to_string(timeout_) + " s");
    return;
  }
  dynamic_reconfigure::Reconfigure srv;
  srv.request.config = request(to_send);
  bool abandoned = false;
  if (!call(service, to_send, srv, &abandoned))
  {
    // A call the watchdog dropped is reported there; a stop is no failure of the server.
    if (abandoned || stopping()) return;
    for (const auto& s : to_send)
      fail(s, "the call to " + service + " failed (no answer, the server went away, or its answer was malformed)");
    return;
  }
  // 3. What the server holds now.
  std::string applied;
  for (const auto& s : to_send)
  {
    const std::string why = checkAnswer(s, srv.response.config);
    if (why.empty())
      applied += (applied.empty() ? "" : ", ") + s.parameter + " = " + s.value.toString();
    else
      fail(s, why);
  }
  if (!applied.empty())
    ROS_INFO("%s: state %s: %s now has %s [%s/setpoints]", key_prefix_.c_str(), label.c_str(), resolved.c_str(),
             applied.c_str(), key_prefix_.c_str());
}

void SetpointApplier::watchCalls()
{
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_)
  {
    if (!link_)
    {
      watch_wake_.wait(lock);
      continue;
    }
    const auto deadline = after(call_started_, timeout_);
    if (std::chrono::steady_clock::now() < deadline)
    {
      watch_wake_.wait_until(lock, deadline);
      continue;
    }
    const ros::ServiceServerLinkPtr link = std::move(link_);
    link_.reset();
    const std::vector<Setpoint> late = calling_;
    const std::string service = calling_service_;
    lock.unlock();
    for (const auto& s : late)
      fail(s, "no answer from " + service + " within " + std::to_string(timeout_) +
                  " s: the call is abandoned, the value is sent again with the next set");
    // Outside the lock: roscpp ends the worker's call and waits for it to return.
    link->getConnection()->drop(ros::Connection::Destructing);
    lock.lock();
  }
}
}  // namespace costmap_layers_ros
