// Reading real move_base (costmap_2d) and Nav2 costmap configurations the way those stacks read them.
// One header for the callers that use several of the parts:
//   plugin_types.hpp       their plugin type names and the classes here that take their place
//   costmap2d_rules.hpp    costmap_2d's pre-Hydro parameters, copyParentParameters, searchParam, defaults
//   nav2_defaults.hpp      Nav2's costmap defaults where they differ from costmap_2d's
//   costmap_namespace.hpp  one costmap namespace made ready to build from (node and tool alike)
//   unknown_keys.hpp       parameters nobody read, with a likely typo or why they are ignored
// Rendering a ParamValue tree as YAML text is io's (io/param_yaml.hpp: paramToYaml), not the core's.
#pragma once

#include "costmap_layers/core/config/costmap2d_rules.hpp"
#include "costmap_layers/core/config/costmap_namespace.hpp"
#include "costmap_layers/core/config/nav2_defaults.hpp"
#include "costmap_layers/core/config/param_value.hpp"
#include "costmap_layers/core/config/plugin_types.hpp"
#include "costmap_layers/core/config/unknown_keys.hpp"
#include "costmap_layers/core/costmap/costmap_config.hpp"
