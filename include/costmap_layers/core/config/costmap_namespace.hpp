// One costmap namespace, as a move_base, Nav2 or costmap_layers file leaves it on the parameter server,
// made ready to build from: the same steps in costmap_node and costmap_tool.
#pragma once

#include <string>
#include <vector>

#include "costmap_layers/core/config/costmap2d_rules.hpp"
#include "costmap_layers/core/config/param_value.hpp"

namespace costmap_layers
{
/// roslaunch loads a move_base file that nests everything under `global_costmap:` into the costmap's
/// own namespace as <ns>/global_costmap/global_costmap. When ns holds a map under the costmap's own
/// name (and no plugin of that name), its keys are merged over ns (they win, as a file loaded after
/// the common one does) and the nested key removed. @return true when it lifted.
bool liftOwnNamespace(ParamValue& ns, const std::string& own_name);

/// liftOwnNamespace() (noted); a Nav2 file's `ros__parameters:` level lifted too (warned about) and
/// Nav2's costmap defaults taken (applyNav2CostmapDefaults()); a plugin named "a/b" found nested as
/// a: {b: ...}; then applyCostmap2dRules(). A costmap with no plugin and no filter is warned about (it
/// would stay as it starts).
/// @param own_name  the last component of the costmap's namespace ("" for none)
CompatResult prepareCostmapNamespace(ParamValue ns, const std::string& own_name,
                                     const std::vector<ParentNamespace>& parents = {});

/// The namespaces around the one at `path` ("a/b/c") in a parameter tree, nearest first ("/a/b", "/a",
/// "/"), each with the searchedKeys() it holds: what a host reads from the parameter server.
std::vector<ParentNamespace> parentsInTree(const ParamValue& root, const std::string& path);
}  // namespace costmap_layers
