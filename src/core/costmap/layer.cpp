#include "costmap_layers/core/costmap/layer.hpp"

#include <algorithm>
#include <stdexcept>

#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/config/param_reader.hpp"

namespace costmap_layers
{
void Layer::initialize(LayeredCostmap* parent, const std::string& name, std::shared_ptr<LayerContext> context)
{
  layered_costmap_ = parent;
  name_ = name;
  context_ = std::move(context);
  enabled_ = ParamReader(context_->params(), name_).getBool("enabled", true);
  onInitialize();
  initialized_ = true;
}

void Layer::setEnabled(bool on)
{
  if (enabled_.exchange(on) == on) return;
  enabled_flipped_ = true;
  onEnabledChanged(on);
}

void Layer::reconfigure(const ParamValue& params)
{
  const bool on = ParamReader(params, name_).getBool("enabled", true);
  onReconfigure(params);
  setEnabled(on);
}

std::vector<ParamSpec> Layer::tunableParameters(const ParamValue& params) const
{
  std::vector<ParamSpec> specs =
      recordParameters(params, name_, [](const ParamReader& r) { r.getBool("enabled", true); });
  for (auto& spec : tunableLayerParameters(params))
    specs.push_back(std::move(spec));
  return specs;
}

void Layer::setOutputListener(OutputListener listener)
{
  std::lock_guard<std::mutex> lock(output_mutex_);
  listener_ = std::move(listener);
  if (listener_)
    for (const auto& e : latest_)
      listener_(e);
}

void Layer::setOutputWanted(const std::string& topic, bool wanted)
{
  std::lock_guard<std::mutex> lock(wanted_mutex_);
  const auto it = std::find(wanted_.begin(), wanted_.end(), topic);
  if (wanted && it == wanted_.end())
    wanted_.push_back(topic);
  else if (!wanted && it != wanted_.end())
    wanted_.erase(it);
  wanted_count_ = wanted_.size();
}

bool Layer::outputWanted(const std::string& topic) const
{
  if (wanted_count_.load() == 0) return false;
  std::lock_guard<std::mutex> lock(wanted_mutex_);
  return std::find(wanted_.begin(), wanted_.end(), topic) != wanted_.end();
}

void Layer::setInputListener(InputListener listener)
{
  std::lock_guard<std::mutex> lock(input_mutex_);
  input_listener_ = std::move(listener);
  if (input_listener_)
    for (const auto& [index, port] : replaced_)
      input_listener_(index, port);
}

void Layer::replaceInput(std::size_t index, InputPort port)
{
  if (index >= inputs_.size() || port.kind != inputs_[index].kind)
    throw std::logic_error(name_ + ": replaceInput() of an input that was not declared with that kind");
  std::lock_guard<std::mutex> lock(input_mutex_);
  auto it = std::find_if(replaced_.begin(), replaced_.end(), [&](const auto& r) { return r.first == index; });
  if (it == replaced_.end())
    it = replaced_.insert(replaced_.end(), {index, std::move(port)});
  else
    it->second = std::move(port);
  if (input_listener_) input_listener_(index, it->second);
}

void Layer::emit(OutputKind kind, const std::string& topic, double value)
{
  OutputEvent event;
  event.kind = kind;
  event.topic = topic;
  event.value = value;
  emit(event);
}

void Layer::emit(const OutputEvent& event)
{
  std::lock_guard<std::mutex> lock(output_mutex_);
  const OutputKind kind = event.kind;
  const std::string& topic = event.topic;
  // An on-demand output is not latched: a listener set later gets the next one, not an old snapshot.
  const bool on_demand = std::any_of(outputs_.begin(), outputs_.end(), [&](const OutputPort& p)
                                     { return p.on_demand && p.kind == kind && p.topic == topic; });
  if (!on_demand)
  {
    auto it = std::find_if(latest_.begin(), latest_.end(),
                           [&](const OutputEvent& e) { return e.kind == kind && e.topic == topic; });
    if (it == latest_.end())
      latest_.push_back(event);
    else
      *it = event;
  }
  if (listener_) listener_(event);
}

const char* inputKindName(InputKind kind)
{
  switch (kind)
  {
    case InputKind::Map:
      return "map";
    case InputKind::Mask:
      return "mask";
    case InputKind::MapUpdates:
      return "map updates";
    case InputKind::SpeedLimits:
      return "speed limits";
    case InputKind::LaserScan:
      return "laser scans";
    case InputKind::PointCloud2:
      return "point clouds";
    case InputKind::PointCloud:
      return "point clouds (sensor_msgs/PointCloud)";
    case InputKind::Range:
      return "ranges";
    case InputKind::FilterInfo:
      return "filter info";
    case InputKind::Path:
      return "path";
    case InputKind::Odometry:
      return "odometry";
  }
  return "?";
}

LayerStatus Layer::status() const
{
  LayerStatus s;
  s.add("enabled", enabled() ? "true" : "false");
  s.add("current", current_ ? "true" : "false");
  for (const auto& in : inputs_)
    s.add(std::string("input ") + inputKindName(in.kind), in.topic);
  if (!enabled())
    s.message = "disabled";
  else if (!current_)
    s.raise(StatusLevel::Warn, "not current: its inputs are out of date");
  else
    s.message = "current";
  return s;
}

const std::vector<Eigen::Vector2d>& Layer::getFootprint() const
{
  static const std::vector<Eigen::Vector2d> empty;
  return layered_costmap_ != nullptr ? layered_costmap_->getFootprint() : empty;
}
}  // namespace costmap_layers
