#include "costmap_layers/ros/layer_reconfigure.hpp"

#include <dynamic_reconfigure/ConfigDescription.h>

#include <algorithm>
#include <cmath>

#include "costmap_layers/core/config/input_error.hpp"

namespace costmap_layers_ros
{
using costmap_layers::ParamSpec;
using costmap_layers::ParamValue;

namespace
{

double clampLimit(double v)
{
  return std::max(-1e9, std::min(1e9, v));
}

dynamic_reconfigure::GroupState defaultGroup()
{
  dynamic_reconfigure::GroupState g;
  g.name = "Default";
  g.state = true;
  g.id = 0;
  g.parent = 0;
  return g;
}

/// One typed parameter (BoolParameter, IntParameter, ...) appended to its list of a Config.
template <class Parameter, class Value>
void appendParameter(std::vector<Parameter>& list, const std::string& name, Value value)
{
  Parameter p;
  p.name = name;
  p.value = value;
  list.push_back(p);
}
}  // namespace

const char* reconfigureTypeName(ParamValue::Type t)
{
  switch (t)
  {
    case ParamValue::Type::Bool:
      return "bool";
    case ParamValue::Type::Int:
      return "int";
    case ParamValue::Type::Double:
      return "double";
    default:
      return "str";
  }
}

void addToConfig(dynamic_reconfigure::Config& config, const std::string& name, const ParamValue& value)
{
  switch (value.type())
  {
    case ParamValue::Type::Bool:
      appendParameter(config.bools, name, value.asBool());
      break;
    case ParamValue::Type::Int:
      appendParameter(config.ints, name, static_cast<int32_t>(value.asInt()));
      break;
    case ParamValue::Type::Double:
      appendParameter(config.doubles, name, value.asDouble());
      break;
    default:
      appendParameter(config.strs, name, value.asString());
      break;
  }
}

ReconfigureChange applyConfig(const ParamValue& current, const std::vector<ParamSpec>& specs,
                              const dynamic_reconfigure::Config& config)
{
  ReconfigureChange change;
  change.next = current.isMap() ? current : ParamValue::makeMap();
  ParamValue& next = change.next;
  auto known = [&specs](const std::string& name)
  { return std::any_of(specs.begin(), specs.end(), [&name](const ParamSpec& s) { return s.name == name; }); };
  // The names a caller sent that cannot change: the first few, each clipped, and how many in all.
  auto ignore = [&change](const std::string& name)
  {
    if (change.ignored_count++ < kReconfigureNamesShown) change.ignored += " " + costmap_layers::shownText(name);
  };
  for (const auto& p : config.bools)
    known(p.name) ? (void)next.set(p.name, ParamValue::makeBool(p.value)) : ignore(p.name);
  for (const auto& p : config.ints)
    known(p.name) ? (void)next.set(p.name, ParamValue::makeInt(p.value)) : ignore(p.name);
  for (const auto& p : config.doubles)
    known(p.name) ? (void)next.set(p.name, ParamValue::makeDouble(p.value)) : ignore(p.name);
  for (const auto& p : config.strs)
    known(p.name) ? (void)next.set(p.name, ParamValue::makeString(p.value)) : ignore(p.name);
  if (change.ignored_count > kReconfigureNamesShown)
    change.ignored += " (" + std::to_string(change.ignored_count) + " in all)";
  return change;
}

LayerReconfigure::LayerReconfigure(ros::NodeHandle layer_nh, std::shared_ptr<costmap_layers::Layer> layer,
                                   ParamValue params, RunLocked run_locked)
    : nh_(std::move(layer_nh)), layer_(std::move(layer)), params_(std::move(params)), run_locked_(std::move(run_locked))
{
  descriptions_ = nh_.advertise<dynamic_reconfigure::ConfigDescription>("parameter_descriptions", 1, true);
  updates_ = nh_.advertise<dynamic_reconfigure::Config>("parameter_updates", 1, true);
  const auto current = layer_->tunableParameters(params_);
  descriptions_.publish(describe(current, layer_->tunableParameters(ParamValue::makeMap())));
  updates_.publish(toConfig(current, false));
  service_ = nh_.advertiseService("set_parameters", &LayerReconfigure::onSet, this);
}

dynamic_reconfigure::Config LayerReconfigure::toConfig(const std::vector<ParamSpec>& specs, bool use_defaults,
                                                       int which)
{
  dynamic_reconfigure::Config c;
  for (const auto& s : specs)
  {
    const ParamValue& v = use_defaults ? s.default_value : s.value;
    // The value itself, or (which < 0 / > 0) the type's lower / upper bound as the description gives it.
    switch (s.type)
    {
      case ParamValue::Type::Bool:
        addToConfig(c, s.name, ParamValue::makeBool(which < 0 ? false : (which > 0 ? true : v.asBool())));
        break;
      case ParamValue::Type::Int:
        addToConfig(
            c, s.name,
            ParamValue::makeInt(which < 0 ? static_cast<int>(s.min)
                                          : (which > 0 ? static_cast<int>(s.max) : static_cast<int>(v.asInt()))));
        break;
      case ParamValue::Type::Double:
        addToConfig(
            c, s.name,
            ParamValue::makeDouble(which < 0 ? clampLimit(s.min) : (which > 0 ? clampLimit(s.max) : v.asDouble())));
        break;
      default:
        addToConfig(c, s.name, ParamValue::makeString(which != 0 ? std::string() : v.asString()));
        break;
    }
  }
  c.groups.push_back(defaultGroup());
  return c;
}

dynamic_reconfigure::ConfigDescription LayerReconfigure::describe(const std::vector<ParamSpec>& specs,
                                                                  const std::vector<ParamSpec>& defaults)
{
  dynamic_reconfigure::ConfigDescription d;
  dynamic_reconfigure::Group g;
  g.name = "Default";
  g.type = "";
  g.id = 0;
  g.parent = 0;
  for (const auto& s : specs)
  {
    dynamic_reconfigure::ParamDescription p;
    p.name = s.name;
    p.type = reconfigureTypeName(s.type);
    p.level = 0;
    p.description = s.choices.empty() ? s.name
                                      : s.name + " (one of: " +
                                            [&]
    {
      std::string list;
      for (const auto& c : s.choices)
        list += (list.empty() ? "" : ", ") + c;
      return list;
    }() + ")";
    p.edit_method = "";
    g.parameters.push_back(p);
  }
  d.groups.push_back(g);
  d.max = toConfig(specs, false, 1);
  d.min = toConfig(specs, false, -1);
  d.dflt = toConfig(defaults, true);
  return d;
}

bool LayerReconfigure::onSet(dynamic_reconfigure::Reconfigure::Request& req,
                             dynamic_reconfigure::Reconfigure::Response& res)
{
  std::lock_guard<std::mutex> lock(mutex_);
  ReconfigureChange change = applyConfig(params_, layer_->tunableParameters(params_), req.config);
  // One key for both lines: at most one error line per layer per second, whatever a caller floods.
  const std::string error_key = nh_.getNamespace() + "/set_parameters";
  if (change.ignored_count > 0)
    errors_.log(costmap_layers::Severity::Error, error_key,
                layer_->getName() + ": ignored parameters that cannot change at run time:" + change.ignored);
  try
  {
    run_locked_([&] { layer_->reconfigure(change.next); });
    params_ = change.next;
    ROS_INFO("%s: reconfigured", layer_->getName().c_str());
  }
  catch (const std::exception& e)
  {
    errors_.log(costmap_layers::Severity::Error, error_key,
                layer_->getName() + ": reconfiguration refused, keeping the previous parameters: " +
                    costmap_layers::shownText(e.what(), 400));
  }
  res.config = toConfig(layer_->tunableParameters(params_), false);
  updates_.publish(res.config);
  return true;
}
}  // namespace costmap_layers_ros
