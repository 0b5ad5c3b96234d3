#include "costmap_layers/tool/param_reference.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/costmap/costmap_builder.hpp"
#include "costmap_layers/core/costmap/costmap_config.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/ros/layer_ports.hpp"
#include "costmap_layers/ros/plugin_factory.hpp"

namespace costmap_layers_ros
{
using namespace costmap_layers;

namespace
{
/// The name the sample observation source has: the one source an obstacle or voxel layer is given so
/// that a source's parameters are read too. Shown as "<source>".
const char* kSampleSource = "scan";

/// A context that has no tf (one frame) and keeps what is reported: a plugin that complains about its
/// defaults is a fault of the reference, said by describeParameters().
class DescribeContext : public LayerContext
{
public:
  explicit DescribeContext(ParamValue params) : params_(std::move(params)) {}
  const ParamValue& params() const override { return params_; }
  const std::string& globalFrame() const override { return frame_; }
  double transformTolerance() const override { return 0.3; }
  std::optional<Transform2D> lookupTransform(const std::string& target, const std::string& source,
                                             std::string* error) override
  {
    if (target == source) return Transform2D{};
    if (error) *error = "no tf here";
    return std::nullopt;
  }
  uint64_t nowNs() const override { return 0; }
  void report(Severity, const std::string&, const std::string&) override {}

private:
  ParamValue params_;
  std::string frame_ = "map";
};

/// Parameters a plugin needs beyond its defaults for all of its parse functions to run: an obstacle or
/// voxel layer reads a source's parameters only for a source it is given.
ParamValue sampleParams(const std::string& type)
{
  ParamValue p = ParamValue::makeMap();
  if (type == "costmap_layers/ObstacleLayer" || type == "costmap_layers/VoxelLayer")
    p.set("observation_sources", ParamValue::makeString(kSampleSource));
  // Its voxel outputs exist only when asked for: describe them.
  if (type == "costmap_layers/VoxelLayer") p.set("publish_voxel_map", ParamValue::makeBool(true));
  // A container needs a plugin to start: an inflation layer (no inputs), described under its own type.
  if (type == "costmap_layers/PluginContainerLayer")
  {
    p.set("plugins", ParamValue::makeList({ParamValue::makeString("inflation")}));
    p.set("inflation", ParamValue::makeMap()).set("plugin", ParamValue::makeString("costmap_layers/InflationLayer"));
  }
  return p;
}

bool isLowest(double v)
{
  return v <= std::numeric_limits<double>::lowest() || v <= -1e300;
}
bool isHighest(double v)
{
  return v >= std::numeric_limits<double>::max() || v >= 1e300;
}

std::string rangeText(const ParamSpec& s)
{
  if (!s.choices.empty())
  {
    std::string out = "one of ";
    for (std::size_t i = 0; i < s.choices.size(); ++i)
      out += (i ? ", " : "") + s.choices[i];
    return out;
  }
  if (s.type == ParamValue::Type::Int)
  {
    const bool lo = s.min > static_cast<double>(std::numeric_limits<int>::min());
    const bool hi = s.max < static_cast<double>(std::numeric_limits<int>::max());
    if (lo && hi) return "[" + valueText(s.min) + ", " + valueText(s.max) + "]";
    if (lo) return ">= " + valueText(s.min);
    if (hi) return "<= " + valueText(s.max);
    return "";
  }
  if (s.type == ParamValue::Type::Double)
  {
    const bool lo = !isLowest(s.min), hi = !isHighest(s.max);
    if (lo && hi) return "[" + valueText(s.min) + ", " + valueText(s.max) + "]";
    if (lo) return ">= " + valueText(s.min);
    if (hi) return "<= " + valueText(s.max);
    return "finite";
  }
  return "";
}

std::string typeText(const ParamSpec& s)
{
  switch (s.type)
  {
    case ParamValue::Type::Bool:
      return "bool";
    case ParamValue::Type::Int:
      return "int";
    case ParamValue::Type::Double:
      return "double";
    case ParamValue::Type::String:
      return s.role.empty() ? "string" : s.role;
    default:
      return s.role;  // declared: what the whole value holds
  }
}

std::string defaultText(const ParamSpec& s, bool in_source)
{
  const ParamValue& d = s.default_value;
  switch (d.type())
  {
    case ParamValue::Type::Bool:
      return d.asBool() ? "true" : "false";
    case ParamValue::Type::Int:
      return std::to_string(d.asInt());
    case ParamValue::Type::Double:
      return valueText(d.asDouble());
    case ParamValue::Type::String:
      if (s.type == ParamValue::Type::Null) return d.asString();  // declare(): a sentence
      if (in_source && d.asString() == kSampleSource) return "the source's name";
      return "\"" + d.asString() + "\"";
    default:
      return "";
  }
}

/// The log's entries as rows: names relative to `owner` (a source's sub-namespace as "<source>/"), each
/// name once (a parameter two parse functions read is the same parameter).
std::vector<ParamRow> rowsOf(const std::vector<ParamSpecLog::Entry>& entries, const std::string& owner)
{
  std::vector<ParamRow> rows;
  std::set<std::string> seen;
  const std::string source_owner = owner + "/" + kSampleSource;
  for (const auto& e : entries)
  {
    std::string name;
    bool in_source = false;
    if (e.owner == owner)
      name = e.spec.name;
    else if (e.owner == source_owner)
    {
      name = "<source>/" + e.spec.name;
      in_source = true;
    }
    else
      continue;  // another reader (a sub-namespace the defaults do not reach)
    if (!seen.insert(name).second) continue;
    rows.push_back({name, typeText(e.spec), defaultText(e.spec, in_source), rangeText(e.spec)});
  }
  return rows;
}

std::string shortType(const std::string& type)
{
  const auto slash = type.find('/');
  return slash == std::string::npos ? type : type.substr(slash + 1);
}

std::string cell(const std::string& text)
{
  // A '|' would end the Markdown table cell.
  std::string out;
  for (char c : text)
    out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out.empty() ? std::string("") : out;
}

std::string code(const std::string& text)
{
  return text.empty() ? "" : "`" + text + "`";
}

/// An input with no topic is connected by the filter info; an output with none publishes on no topic.
std::string portTopic(const PortRow& port, bool markdown)
{
  if (port.topic.empty()) return port.output ? "(no topic)" : "(the filter info's mask topic)";
  if (port.topic == "<source>/topic") return markdown ? "each source's `topic`" : "each source's topic";
  return markdown ? code(port.topic) : port.topic;
}

const char* outputKindName(OutputKind kind)
{
  switch (kind)
  {
    case OutputKind::MaxSpeed:
      return "speed limit in force";
    case OutputKind::SpeedLimit:
      return "speed limit (Nav2's message)";
    case OutputKind::ZoneState:
      return "zone state id";
    case OutputKind::Setpoints:
      return "parameters of other nodes (dynamic_reconfigure)";
    case OutputKind::BinaryState:
      return "binary state";
    case OutputKind::VoxelGrid:
      return "voxel grid (while subscribed)";
    case OutputKind::VoxelMarkers:
      return "marked voxels as cubes (while subscribed)";
    case OutputKind::VoxelCloud:
      return "marked voxels' centres (while subscribed)";
  }
  return "";
}
}  // namespace

ParamReference describeParameters(PluginFactory& factory)
{
  ParamReference ref;
  {
    ParamSpecLog log;
    const ParamValue none = ParamValue::makeMap();
    parseCostmapConfig(none);
    parsePluginLists(none);
    ref.costmap = rowsOf(log.entries(), "costmap");
  }
  std::vector<std::string> types = factory.availableTypes();
  std::sort(types.begin(), types.end());
  for (const std::string& type : types)
  {
    PluginReference plugin;
    plugin.type = type;
    plugin.description = factory.description(type);
    const std::string name = shortType(type);
    LayeredCostmap costmap("map", false, false);
    costmap.resizeMap(10, 10, 0.1, 0.0, 0.0);
    PluginLists lists;
    lists.plugins.push_back({name, type});
    ParamSpecLog log;
    try
    {
      loadPlugins(
          costmap, lists, [&factory](const std::string& t) { return factory.create(t); },
          [&type](const PluginSpec&) { return std::make_shared<DescribeContext>(sampleParams(type)); });
    }
    catch (const std::exception& e)
    {
      throw std::runtime_error("the reference cannot describe " + type +
                               ": it does not start on its defaults: " + e.what());
    }
    plugin.params = rowsOf(log.entries(), name);
    const auto layer = costmap.findLayer(name);
    for (const InputPort& in : layer->inputs())
      plugin.ports.push_back({false, inputKindName(in.kind), in.topic == kSampleSource ? "<source>/topic" : in.topic,
                              portMessageType(in.kind)});
    for (const OutputPort& out : layer->outputs())
      plugin.ports.push_back({true, outputKindName(out.kind),
                              out.kind == OutputKind::Setpoints ? ""
                              : out.layer_namespace           ? "~<name>/" + out.topic
                                                              : out.topic,
                              portMessageType(out.kind)});
    plugin.services = layerServices(*layer);
    ref.plugins.push_back(std::move(plugin));
  }
  return ref;
}

std::string referenceMarkdown(const ParamReference& ref)
{
  std::ostringstream md;
  md << "# Parameter reference\n\n"
        "Generated from the code by `costmap_tool --describe-params --markdown` (run "
        "`scripts/dev/make_reference.sh` after changing a parse function): every parameter each plugin reads, "
        "with its type, default and accepted range, and the topics and services it uses. A test fails when this "
        "file differs from what the code declares. What the parameters mean is in each plugin's page and in "
        "the [README](../README.md).\n\n"
        "Every plugin also has `enabled` and a dynamic_reconfigure server `~<name>/set_parameters` for the "
        "parameters marked tunable there. Topics are given with their defaults; a relative topic resolves in "
        "the costmap node's namespace (in move_base: move_base's).\n\n";
  md << "## The costmap\n\ncostmap_node's private namespace (move_base: `global_costmap/`, `local_costmap/`).\n\n";
  md << "| parameter | type | default | range |\n|---|---|---|---|\n";
  for (const auto& r : ref.costmap)
    md << "| " << code(r.name) << " | " << cell(r.type) << " | " << cell(r.default_text) << " | " << cell(r.range)
       << " |\n";
  for (const auto& p : ref.plugins)
  {
    md << "\n## " << p.type << "\n\n" << p.description << "\n\n";
    md << "| parameter | type | default | range |\n|---|---|---|---|\n";
    for (const auto& r : p.params)
      md << "| " << code(r.name) << " | " << cell(r.type) << " | " << cell(r.default_text) << " | " << cell(r.range)
         << " |\n";
    if (!p.ports.empty())
    {
      md << "\n| direction | carries | topic (default) | message |\n|---|---|---|---|\n";
      for (const auto& port : p.ports)
        md << "| " << (port.output ? "publishes" : "subscribes") << " | " << cell(port.kind) << " | "
           << portTopic(port, true) << " | " << code(port.message) << " |\n";
    }
    if (!p.services.empty())
    {
      md << "\nServices:";
      for (std::size_t i = 0; i < p.services.size(); ++i)
        md << (i ? "," : "") << " `~<name>/" << p.services[i] << "` (std_srvs/SetBool)";
      md << "\n";
    }
  }
  return md.str();
}

std::string referenceText(const ParamReference& ref)
{
  std::ostringstream out;
  auto rows = [&out](const std::vector<ParamRow>& list)
  {
    for (const auto& r : list)
    {
      out << "  " << r.name << " (" << r.type << ")";
      if (!r.default_text.empty()) out << " default " << r.default_text;
      if (!r.range.empty()) out << ", " << r.range;
      out << "\n";
    }
  };
  out << "costmap:\n";
  rows(ref.costmap);
  for (const auto& p : ref.plugins)
  {
    out << "\n" << p.type << ": " << p.description << "\n";
    rows(p.params);
    for (const auto& port : p.ports)
      out << "  " << (port.output ? "publishes " : "subscribes ") << port.kind << " on " << portTopic(port, false)
          << (port.message.empty() ? std::string() : " (" + port.message + ")") << "\n";
    for (const auto& s : p.services)
      out << "  service ~<name>/" << s << " (std_srvs/SetBool)\n";
  }
  return out.str();
}
}  // namespace costmap_layers_ros
