#include "costmap_layers/ros/setpoint_applier.hpp"

#include "costmap_layers/ros/layer_reconfigure.hpp"

#include <dynamic_reconfigure/Reconfigure.h>
#include <ros/topic.h>

#include <algorithm>
#include <cmath>
#include <sstream>

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

std::string show(const Setpoint& s)
{
  return s.node + " " + s.parameter + " = " + s.value.toString();
}
}  // namespace

SetpointApplier::SetpointApplier(ros::NodeHandle nh, std::string key_prefix, double timeout,
                                 std::shared_ptr<ThrottledLog> log)
    : nh_(std::move(nh)), key_prefix_(std::move(key_prefix)), timeout_(timeout), log_(std::move(log))
{
  watchdog_ = nh_.createSteadyTimer(ros::WallDuration(std::min(1.0, timeout_ / 2.0)), &SetpointApplier::watch, this);
  worker_ = std::thread([this] { run(); });
}

SetpointApplier::~SetpointApplier()
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  watchdog_.stop();
  if (worker_.joinable()) worker_.join();
}

void SetpointApplier::submit(std::vector<Setpoint> set, std::string label)
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_.emplace(std::move(set), std::move(label));
  }
  wake_.notify_all();
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
    switch (s.value.type())
    {
      case ParamValue::Type::Bool:
      {
        dynamic_reconfigure::BoolParameter p;
        p.name = s.parameter;
        p.value = s.value.asBool();
        c.bools.push_back(p);
        break;
      }
      case ParamValue::Type::Int:
      {
        dynamic_reconfigure::IntParameter p;
        p.name = s.parameter;
        p.value = static_cast<int32_t>(s.value.asInt());
        c.ints.push_back(p);
        break;
      }
      case ParamValue::Type::Double:
      {
        dynamic_reconfigure::DoubleParameter p;
        p.name = s.parameter;
        p.value = s.value.asDouble();
        c.doubles.push_back(p);
        break;
      }
      default:
      {
        dynamic_reconfigure::StrParameter p;
        p.name = s.parameter;
        p.value = s.value.asString();
        c.strs.push_back(p);
        break;
      }
    }
  return c;
}

std::string SetpointApplier::checkAgainst(const Setpoint& s, const dynamic_reconfigure::ConfigDescription& d)
{
  const dynamic_reconfigure::ParamDescription* found = nullptr;
  std::string names;
  for (const auto& g : d.groups)
    for (const auto& p : g.parameters)
    {
      names += (names.empty() ? "" : ", ") + p.name;
      if (p.name == s.parameter) found = &p;
    }
  if (!found) return "the server has no parameter '" + s.parameter + "' (it has: " + names + ")";
  const std::string want = reconfigureTypeName(s.value.type());
  if (found->type != want)
    return "the server's '" + s.parameter + "' is of type " + found->type + ", the value is of type " + want +
           (found->type == "double" && want == "int" ? " (write 1.0, not 1)" : "");
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
  if (!sameValue(got, s.value)) return "the server refused it and holds " + got.toString();
  return "";
}

void SetpointApplier::run()
{
  for (;;)
  {
    std::pair<std::vector<Setpoint>, std::string> job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stop_ || pending_.has_value(); });
      if (stop_) return;
      job = std::move(*pending_);
      pending_.reset();
    }
    // Node by node, in the order the set first names them.
    std::vector<std::string> nodes;
    for (const auto& s : job.first)
      if (std::find(nodes.begin(), nodes.end(), s.node) == nodes.end()) nodes.push_back(s.node);
    for (const auto& node : nodes)
    {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (stop_) return;
      }
      std::vector<Setpoint> mine;
      for (const auto& s : job.first)
        if (s.node == node) mine.push_back(s);
      applyNode(node, mine, job.second);
    }
  }
}

void SetpointApplier::applyNode(const std::string& node, const std::vector<Setpoint>& setpoints,
                                const std::string& label)
{
  if (!ros::ok()) return;
  const std::string resolved = nh_.resolveName(node);
  const std::string service = resolved + "/set_parameters";
  const ros::Duration timeout(timeout_);
  // 1. The description: what the server declares.
  std::vector<Setpoint> to_send;
  const auto description = ros::topic::waitForMessage<dynamic_reconfigure::ConfigDescription>(
      resolved + "/parameter_descriptions", nh_, timeout);
  if (!description)
  {
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
  if (!ros::service::waitForService(service, timeout))
  {
    for (const auto& s : to_send)
      fail(s, "the service " + service + " did not appear within " + std::to_string(timeout_) + " s");
    return;
  }
  dynamic_reconfigure::Reconfigure srv;
  srv.request.config = request(to_send);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    calling_ = to_send;
    calling_service_ = service;
    call_started_ = std::chrono::steady_clock::now();
    call_reported_ = false;
  }
  const bool answered = ros::service::call(service, srv);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    calling_.clear();
  }
  if (!answered)
  {
    for (const auto& s : to_send)
      fail(s, "the call to " + service + " failed");
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

void SetpointApplier::watch(const ros::SteadyTimerEvent&)
{
  std::vector<Setpoint> late;
  std::string service;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (calling_.empty() || call_reported_) return;
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - call_started_).count();
    if (waited <= timeout_) return;
    call_reported_ = true;
    late = calling_;
    service = calling_service_;
  }
  for (const auto& s : late)
    fail(s, "no answer from " + service + " within " + std::to_string(timeout_) + " s (still waiting)");
}
}  // namespace costmap_layers_ros
