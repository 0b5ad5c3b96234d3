#include "costmap_layers/core/filters/zone_parameter_filter.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/core/config/param_reader.hpp"

namespace costmap_layers
{
namespace
{
/// Names a node or a parameter may have: ROS graph names ('/' separated, '~' only at the start).
bool isGraphName(const std::string& s, bool allow_slash)
{
  if (s.empty() || s.size() > 256) return false;
  for (std::size_t k = 0; k < s.size(); ++k)
  {
    const char c = s[k];
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || (allow_slash && c == '/') ||
                    (allow_slash && c == '~' && k == 0);
    if (!ok) return false;
  }
  return true;
}

/// Names of lists the filter reads, each a list of strings.
std::vector<std::string> nameList(const ParamReader& params, const std::string& name)
{
  const ParamValue* v = params.raw(name);
  std::vector<std::string> out;
  if (!v) return out;
  if (!v->isList()) params.fail(name, "must be a list of names (got " + v->toString() + ")");
  for (const auto& item : v->asList())
  {
    if (item.type() != ParamValue::Type::String || item.asString().empty())
      params.fail(name, "must be a list of non-empty names (got " + v->toString() + ")");
    if (std::find(out.begin(), out.end(), item.asString()) != out.end())
      params.fail(name, "names '" + item.asString() + "' twice");
    out.push_back(item.asString());
  }
  return out;
}

/// One setpoint namespace {node, parameter, value}.
Setpoint parseSetpoint(const ParamReader& owner, const std::string& path, const ParamValue* v)
{
  if (!v || !v->isMap())
    owner.fail(path, "must be a map {node: ..., parameter: ..., value: ...} (got " +
                         (v ? v->toString() : std::string("nothing")) + ")");
  for (const auto& [key, value] : v->entries())
    if (key != "node" && key != "parameter" && key != "value")
      owner.fail(path + "/" + key, "is not one of node, parameter, value");
  Setpoint s;
  const ParamValue* node = v->find("node");
  const ParamValue* parameter = v->find("parameter");
  const ParamValue* value = v->find("value");
  if (!node || node->type() != ParamValue::Type::String || !isGraphName(node->asString(), true))
    owner.fail(path + "/node", "must be the node's name, e.g. \"/move_base/DWAPlannerROS\" (got " +
                                   (node ? node->toString() : std::string("nothing")) + ")");
  if (!parameter || parameter->type() != ParamValue::Type::String || !isGraphName(parameter->asString(), false))
    owner.fail(path + "/parameter", "must be a parameter name, e.g. \"max_vel_x\" (got " +
                                        (parameter ? parameter->toString() : std::string("nothing")) + ")");
  if (!value) owner.fail(path + "/value", "must be set (a bool, an integer, a number or a string)");
  const ParamValue::Type t = value->type();
  if (t != ParamValue::Type::Bool && t != ParamValue::Type::Int && t != ParamValue::Type::Double &&
      t != ParamValue::Type::String)
    owner.fail(path + "/value", "must be a bool, an integer, a number or a string (got " + value->toString() + ")");
  if (t == ParamValue::Type::Double && !std::isfinite(value->asDouble()))
    owner.fail(path + "/value", "must be finite (got " + value->toString() + ")");
  if (t == ParamValue::Type::Int && (value->asInt() < INT32_MIN || value->asInt() > INT32_MAX))
    owner.fail(path + "/value", "must fit dynamic_reconfigure's int32 (got " + value->toString() + ")");
  s.node = node->asString();
  s.parameter = parameter->asString();
  s.value = *value;
  return s;
}

bool sameTarget(const Setpoint& a, const Setpoint& b)
{
  return a.node == b.node && a.parameter == b.parameter;
}

std::string target(const Setpoint& s)
{
  return s.node + " " + s.parameter;
}
}  // namespace

ZoneParameterConfig parseZoneParameterConfig(const ParamReader& params)
{
  ZoneParameterConfig c;
  c.state_event_topic = params.getTopic("state_event_topic", c.state_event_topic, true);
  if (c.state_event_topic.empty()) params.fail("state_event_topic", "must not be empty");
  c.setpoint_timeout = params.getDouble("setpoint_timeout", c.setpoint_timeout, 1e-3, limits::kMaxDuration);

  params.declare("nominal_defaults", "<name>: {node, parameter, value}, ...", "none");
  params.declare("states", "state names; each a namespace <state>: {id, setpoints, <setpoint>: {...}}", "none");
  // nominal_defaults: a map of name -> {node, parameter, value}.
  if (const ParamValue* nominal = params.raw("nominal_defaults"))
  {
    if (!nominal->isMap())
      params.fail("nominal_defaults", "must be a map of <name>: {node, parameter, value} (got " + nominal->toString() +
                                          "; Nav2's list of names plus a namespace of the same name cannot be "
                                          "written in ROS 1)");
    for (const auto& [name, entry] : nominal->entries())
    {
      Setpoint s = parseSetpoint(params, "nominal_defaults/" + name, &entry);
      for (const auto& other : c.nominal_defaults)
        if (sameTarget(other, s)) params.fail("nominal_defaults/" + name, "sets " + target(s) + " a second time");
      c.nominal_defaults.push_back(std::move(s));
    }
  }

  for (const std::string& name : nameList(params, "states"))
  {
    static const std::vector<std::string> reserved = {"enabled",
                                                      "mask_topic",
                                                      "filter_info_topic",
                                                      "state_event_topic",
                                                      "setpoint_timeout",
                                                      "states",
                                                      "nominal_defaults",
                                                      "plugin",
                                                      "type",
                                                      "name"};
    if (std::find(reserved.begin(), reserved.end(), name) != reserved.end())
      params.fail("states", "names a state '" + name + "', which is a parameter of the filter: choose another name");
    const ParamValue* ns = params.raw(name);
    if (!ns || !ns->isMap())
      params.fail(name, "must be the namespace of state '" + name + "' with id and setpoints (got " +
                            (ns ? ns->toString() : std::string("nothing")) + ")");
    const ParamReader state(*ns, params.owner() + "/" + name);
    ZoneState z;
    z.name = name;
    if (!state.has("id")) state.fail("id", "must be set: the mask value (1..100) of this state");
    z.id = state.getInt("id", 0, 1, 100);
    for (const auto& other : c.states)
      if (other.id == z.id)
        state.fail("id", "is " + std::to_string(z.id) + ", the id of state '" + other.name + "' too");
    const std::vector<std::string> setpoints = nameList(state, "setpoints");
    for (const auto& [key, value] : ns->entries())
      if (key != "id" && key != "setpoints" && std::find(setpoints.begin(), setpoints.end(), key) == setpoints.end())
        state.fail(key, "is neither id, setpoints nor one of the setpoints it lists");
    for (const std::string& sp : setpoints)
    {
      Setpoint s = parseSetpoint(state, sp, state.raw(sp));
      for (const auto& other : z.setpoints)
        if (sameTarget(other, s)) state.fail(sp, "sets " + target(s) + " a second time in this state");
      const auto nominal = std::find_if(c.nominal_defaults.begin(), c.nominal_defaults.end(),
                                        [&](const Setpoint& n) { return sameTarget(n, s); });
      if (nominal == c.nominal_defaults.end())
        state.fail(sp, "sets " + target(s) +
                           " but nominal_defaults has no value for it: leaving the zone could not restore it "
                           "(add an entry to nominal_defaults)");
      if (nominal->value.type() != s.value.type())
        state.fail(sp + "/value", "is " + s.value.toString() + " (" + ParamValue::typeName(s.value.type()) +
                                      ") but its nominal default is " + nominal->value.toString() + " (" +
                                      ParamValue::typeName(nominal->value.type()) +
                                      "): write both the same way (1.0, not 1, for a floating-point parameter)");
      z.setpoints.push_back(std::move(s));
    }
    c.states.push_back(std::move(z));
  }
  return c;
}

std::vector<Setpoint> zoneSetpoints(const ZoneParameterConfig& config, int id)
{
  std::vector<Setpoint> out = config.nominal_defaults;
  const auto state =
      std::find_if(config.states.begin(), config.states.end(), [id](const ZoneState& s) { return s.id == id; });
  if (id == 0 || state == config.states.end()) return out;
  for (const Setpoint& s : state->setpoints)
    for (Setpoint& o : out)
      if (sameTarget(o, s)) o.value = s.value;
  return out;
}

int zoneStateFor(std::optional<int> value, int current, const ZoneParameterConfig& config, bool* unknown)
{
  if (unknown) *unknown = false;
  if (!value || *value == 0) return 0;
  if (*value == -1) return current;
  const int v = *value;
  if (v >= 1 && v <= 100)
    for (const auto& s : config.states)
      if (s.id == v) return v;
  if (unknown) *unknown = true;
  return 0;
}

std::string zoneStateName(const ZoneParameterConfig& config, int id)
{
  if (id == 0) return "nominal";
  for (const auto& s : config.states)
    if (s.id == id) return s.name;
  return "";
}

void ZoneParameterFilter::onInitializeFilter(const ParamReader& params)
{
  config_ = parseZoneParameterConfig(params);
  addOutput(OutputPort{OutputKind::ZoneState, config_.state_event_topic});
  addOutput(OutputPort{OutputKind::Setpoints, name_ + "/setpoints", config_.setpoint_timeout});
}

void ZoneParameterFilter::onFilterInfo(const FilterInfoData& info)
{
  if (info.base != filter_info::kBaseDefault || info.multiplier != filter_info::kMultiplierDefault)
    context_->report(Severity::Warn, "filter_info/base",
                     name_ + ": the filter info has base " + std::to_string(info.base) + " and multiplier " +
                         std::to_string(info.multiplier) +
                         ": a zone parameter filter reads the mask value itself as the state id and ignores both "
                         "(Nav2 expects 0 and 1)");
}

void ZoneParameterFilter::processPose(const OccupancyGridData& mask, const Transform2D& to_mask, double robot_x,
                                      double robot_y, double robot_yaw)
{
  (void)robot_yaw;
  if (warned_for_mask_ != activeMask())
  {
    warned_for_mask_ = activeMask();
    warned_values_.reset();
  }
  const std::optional<int8_t> cell = maskValueAt(mask, to_mask, robot_x, robot_y);
  const std::optional<int> value = cell ? std::optional<int>(*cell) : std::nullopt;
  bool unknown = false;
  const int next = zoneStateFor(value, state_.value_or(0), config_, &unknown);
  if (unknown)
  {
    const std::size_t bit = static_cast<std::size_t>(static_cast<uint8_t>(*cell));
    if (!warned_values_.test(bit))
    {
      warned_values_.set(bit);
      context_->report(Severity::Error, "mask/state",
                       name_ + ": the robot is on mask value " + std::to_string(*value) +
                           ", which no state has as its id (declare a state with that id in 'states'); "
                           "treating it as outside every zone: the nominal defaults");
    }
  }
  enter(next);
}

void ZoneParameterFilter::enter(int id)
{
  if (state_ && *state_ == id) return;
  state_ = id;
  OutputEvent set;
  set.kind = OutputKind::Setpoints;
  set.topic = name_ + "/setpoints";
  set.setpoints = zoneSetpoints(config_, id);
  set.label = zoneStateName(config_, id);
  set.value = id;
  emit(set);
  emit(OutputKind::ZoneState, config_.state_event_topic, id);
}

LayerStatus ZoneParameterFilter::status() const
{
  LayerStatus s = CostmapFilter::status();
  s.add("state", state_ ? std::to_string(*state_) + " (" + zoneStateName(config_, *state_) + ")" : "none yet");
  return s;
}
}  // namespace costmap_layers
