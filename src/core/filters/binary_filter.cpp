#include "costmap_layers/core/filters/binary_filter.hpp"

#include <sstream>
#include <stdexcept>

#include "costmap_layers/core/config/param_reader.hpp"

namespace costmap_layers
{
BinaryFilterConfig parseBinaryFilterConfig(const ParamReader& params)
{
  BinaryFilterConfig c;
  // Read without recording (the base reads it): it cannot change at run time.
  const ParamValue* info_topic = params.raw("filter_info_topic");
  c.filter_info = info_topic && info_topic->type() == ParamValue::Type::String && !info_topic->asString().empty();
  if (c.filter_info)
    for (const char* held : {"base", "multiplier"})
      if (params.has(held))
        params.fail(held, std::string("is set together with 'filter_info_topic' (") + info_topic->toString() +
                              "): the filter info (costmap_filter_info_server, type 3) gives base and multiplier; "
                              "remove '" +
                              held + "', or configure the filter with mask_topic instead");
  c.binary_state_topic = params.getTopic("binary_state_topic", c.binary_state_topic, true);
  if (c.binary_state_topic.empty()) params.fail("binary_state_topic", "is empty: name the topic of the state");
  c.default_state = params.getBool("default_state", c.default_state);
  c.flip_threshold = params.getDouble("flip_threshold", c.flip_threshold);
  if (!c.filter_info)
  {
    c.base = params.getDouble("base", c.base);
    c.multiplier = params.getDouble("multiplier", c.multiplier);
  }
  return c;
}

bool binaryState(int v, double base, double multiplier, double flip_threshold, bool default_state)
{
  return base + multiplier * v > flip_threshold ? !default_state : default_state;
}

void BinaryFilter::onInitializeFilter(const ParamReader& params)
{
  config_ = parseBinaryFilterConfig(params);
  addOutput(OutputPort{OutputKind::BinaryState, config_.binary_state_topic});
  // The initial state, published at start (latched), as Nav2 does.
  state_ = config_.default_state;
  OutputEvent e;
  e.kind = OutputKind::BinaryState;
  e.topic = config_.binary_state_topic;
  e.state = state_;
  emit(e);
}

void BinaryFilter::onReconfigure(const ParamValue& params)
{
  const BinaryFilterConfig next = parseBinaryFilterConfig(ParamReader(params, name_));  // validates first
  if (next.binary_state_topic != config_.binary_state_topic || next.filter_info != config_.filter_info)
    throw std::invalid_argument(name_ + ": binary_state_topic and filter_info_topic cannot change at run time");
  config_ = next;  // the state is evaluated again at the next update
}

std::vector<ParamSpec> BinaryFilter::tunableLayerParameters(const ParamValue& params) const
{
  std::vector<ParamSpec> tunable;
  for (auto& p : recordParameters(params, name_, [](const ParamReader& r) { parseBinaryFilterConfig(r); }))
    if (p.name != "binary_state_topic") tunable.push_back(std::move(p));
  return tunable;
}

void BinaryFilter::processPose(const OccupancyGridData& mask, const Transform2D& to_mask, double robot_x,
                               double robot_y, double)
{
  const std::optional<int8_t> v = maskValueAt(mask, to_mask, robot_x, robot_y);
  if (!v)
  {
    if (state_ != config_.default_state) setState(config_.default_state, "the robot is outside the mask");
    return;
  }
  if (*v == -1) return;  // unknown: keep the state (Nav2)
  if (*v < -1 || *v > 100)
  {
    const std::size_t bit = static_cast<uint8_t>(*v);
    if (!warned_values_.test(bit))
    {
      warned_values_.set(bit);
      context_->report(Severity::Warn, "mask/value",
                       name_ + ": the mask holds the value " + std::to_string(*v) +
                           " (outside -1..100, invalid in an OccupancyGrid); the state is default_state (" +
                           (config_.default_state ? "true" : "false") + ") there");
    }
    if (state_ != config_.default_state) setState(config_.default_state, "invalid mask value");
    return;
  }
  const FilterInfoData* info = activeInfo().get();
  const double base = info ? info->base : config_.base;
  const double multiplier = info ? info->multiplier : config_.multiplier;
  const bool next = binaryState(*v, base, multiplier, config_.flip_threshold, config_.default_state);
  if (next == state_) return;
  std::ostringstream why;
  why << "mask value " << static_cast<int>(*v) << ": " << base << " + " << multiplier << " * " << static_cast<int>(*v)
      << " = " << base + multiplier * *v << ", flip_threshold " << config_.flip_threshold;
  setState(next, why.str());
}

void BinaryFilter::setState(bool state, const std::string& why)
{
  if (state == state_) return;
  state_ = state;
  OutputEvent e;
  e.kind = OutputKind::BinaryState;
  e.topic = config_.binary_state_topic;
  e.state = state;
  emit(e);
  context_->report(
      Severity::Info, "binary_state",
      name_ + ": state " + (state ? "true" : "false") + " on " + config_.binary_state_topic + " (" + why + ")");
}
}  // namespace costmap_layers
