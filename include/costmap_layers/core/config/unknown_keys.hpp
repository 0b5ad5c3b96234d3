// Parameters nobody read: found with a ParamReadLog after the costmap and its layers are set up, each
// described in one warning line with the nearest known name (a likely typo) or, for a key costmap_2d
// or Nav2 know, why this package ignores it.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "costmap_layers/core/config/costmap2d_rules.hpp"
#include "costmap_layers/core/config/param_value.hpp"
#include "costmap_layers/core/costmap/costmap_config.hpp"

namespace costmap_layers
{
/// Levenshtein distance.
std::size_t editDistance(const std::string& a, const std::string& b);
/// The candidate nearest to key when it is near enough to be a likely typo, else "".
std::string nearestName(const std::string& key, const std::vector<std::string>& candidates);

/// A key nobody asked for.
struct UnknownKey
{
  std::string path;             ///< relative to the namespace walked, e.g. "obstacle_layer/scan/topicc"
  std::string suggestion;       ///< the nearest known name, or ""
  std::string known_elsewhere;  ///< when costmap_2d or Nav2 know the key: why it is ignored here
  bool is_namespace = false;    ///< its value is a map (e.g. a layer namespace no plugin uses)
};

/// Walks ns: every key never asked while `log` recorded is reported; sub-maps that were read from are
/// walked too. `known` are names to take as asked at the top level; `skip` are top-level keys not to
/// look at (e.g. plugin namespaces walked separately). `scope` picks the table of keys costmap_2d or
/// Nav2 know: "costmap", "source", or a plugin class name such as "ObstacleLayer".
std::vector<UnknownKey> unknownKeys(const ParamValue& ns, const ParamReadLog& log, const std::string& scope,
                                    const std::vector<std::string>& known = {},
                                    const std::vector<std::string>& skip = {});

/// One warning line for an unknown key (`plugins` lists the costmap's plugin names, for namespaces), e.g.
/// "parameter 'inflaton_radius' in /move_base/global_costmap/inflation_layer is not used (did you mean
/// `inflation_radius`?)".
/// In a layer's namespace (layer_class set, e.g. "ObstacleLayer") a namespace key is one the layer does
/// not read, e.g. a misspelt observation source.
std::string describeUnknownKey(const UnknownKey& key, const std::string& ns_name,
                               const std::vector<std::string>& plugins = {}, const std::string& layer_class = "");

/// One warning line per parameter no parse asked for while `log` recorded (the costmap and its layers
/// set up): in the costmap's namespace (compat.params; its consumed keys are known) and in each layer's
/// (`layers`: each plugin with the parameter map its layer read). ns_name names the costmap's namespace.
std::vector<std::string> unusedParameterLines(const CompatResult& compat, const ParamReadLog& log,
                                              const std::vector<std::pair<PluginSpec, const ParamValue*>>& layers,
                                              const std::string& ns_name);
}  // namespace costmap_layers
