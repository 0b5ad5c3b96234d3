// The parameter reference, generated from the code that reads the parameters: each plugin is created
// and initialised with its defaults while a ParamSpecLog records what its parse functions read (name,
// type, default, range, choices), and its declared input and output ports give the topics and message
// types it uses. `costmap_tool --describe-params [--markdown]` prints it; docs/parameters.md is that
// output, and a test fails when the two differ, so the reference cannot drift from the code.
#pragma once

#include <string>
#include <vector>

namespace costmap_layers_ros
{
class PluginFactory;

struct ParamRow
{
  std::string name;  ///< relative to the plugin's namespace; "<source>/..." for an observation source's
  std::string type;  ///< bool, int, double, string, topic, frame id, or what a whole value holds
  std::string default_text;
  std::string range;  ///< "[min, max]", ">= min", "one of ...", or ""
};

struct PortRow
{
  bool output = false;
  std::string kind;     ///< what the port carries ("map", "filter mask", ...)
  std::string topic;    ///< with the defaults; "" for a port connected later (by a filter info)
  std::string message;  ///< ROS message type; "" for setpoints (no topic)
};

struct PluginReference
{
  std::string type;
  std::string description;
  std::vector<ParamRow> params;
  std::vector<PortRow> ports;
  std::vector<std::string> services;  ///< in the plugin's namespace
};

struct ParamReference
{
  std::vector<ParamRow> costmap;  ///< the costmap's own parameters (costmap_node's ~, move_base's costmaps)
  std::vector<PluginReference> plugins;
};

/// Creates every plugin type the factory declares, with its defaults, and records what it reads.
/// Throws std::runtime_error naming a type that does not initialise with its defaults.
ParamReference describeParameters(PluginFactory& factory);

/// The reference as Markdown (docs/parameters.md) or as plain text for a terminal.
std::string referenceMarkdown(const ParamReference& reference);
std::string referenceText(const ParamReference& reference);
}  // namespace costmap_layers_ros
