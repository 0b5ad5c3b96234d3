// Fuzzes the params YAML: io::parseParamsYaml on arbitrary text, then what costmap_tool and the node
// read from it: parseCostmapConfig (footprint as a string or a list, robot_radius, padding, sizes),
// parsePluginLists (ROS 1, Nav2 Foxy and Galactic forms, filters), every plugin's own parse through
// its initialize(), loadPlugins with the core layer types, and one update cycle when the grid is small.
// Input: the YAML text itself (a plain text corpus: test/fuzz/corpus/params/*.yaml). The costmap's
// namespace is the document's first map-valued key when there is one, else the document.
// Invariants: only std::invalid_argument / std::runtime_error escape the parsers; an accepted
// costmap config has a finite positive resolution, sizes of at least one cell and a padded footprint
// of at least 3 finite vertices; the plugin lists hold no duplicate names.
#include <cmath>
#include <cstdint>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>

#include "costmap_layers/core/costmap/costmap_builder.hpp"
#include "costmap_layers/core/costmap/costmap_config.hpp"
#include "costmap_layers/core/layers/gradient_layer.hpp"
#include "costmap_layers/core/layers/inflation_layer.hpp"
#include "costmap_layers/core/filters/keepout_filter.hpp"
#include "costmap_layers/core/filters/lanes_filter.hpp"
#include "costmap_layers/core/layers/range_sensor_layer.hpp"
#include "costmap_layers/core/filters/speed_filter.hpp"
#include "costmap_layers/core/layers/static_layer.hpp"
#include "costmap_layers/core/layers/voxel_layer.hpp"
#include "costmap_layers/io/param_yaml.hpp"
#include "fuzz_common.hpp"

using namespace costmap_layers;
using namespace costmap_layers_fuzz;

namespace
{
/// The core layer types by the class name at the end of a pluginlib type ("costmap_layers/X" or
/// "costmap_layers::X"); unknown types throw as PluginFactory does.
std::shared_ptr<Layer> createLayer(const std::string& type)
{
  const std::size_t cut = type.find_last_of("/:");
  const std::string name = cut == std::string::npos ? type : type.substr(cut + 1);
  if (name == "GradientLayer") return std::make_shared<GradientLayer>();
  if (name == "InflationLayer") return std::make_shared<InflationLayer>();
  if (name == "StaticLayer") return std::make_shared<StaticLayer>();
  if (name == "ObstacleLayer") return std::make_shared<ObstacleLayer>();
  if (name == "VoxelLayer") return std::make_shared<VoxelLayer>();
  if (name == "RangeSensorLayer") return std::make_shared<RangeSensorLayer>();
  if (name == "KeepoutFilter") return std::make_shared<KeepoutFilter>();
  if (name == "LanesFilter") return std::make_shared<LanesFilter>();
  if (name == "SpeedFilter") return std::make_shared<SpeedFilter>();
  throw std::runtime_error("unknown plugin type " + type);
}

void run(const std::string& text)
{
  const ParamValue root = io::parseParamsYaml(text, "fuzz.yaml");
  const ParamValue* ns = &root;
  for (const auto& [key, value] : root.entries())
    if (value.isMap())
    {
      ns = &value;
      break;
    }
  // The plugin lists before the config, so that a bad config does not hide them from the fuzzer.
  PluginLists lists;
  bool lists_ok = true;
  try
  {
    lists = parsePluginLists(*ns);
    std::set<std::string> names;
    for (const auto* l : {&lists.plugins, &lists.filters})
      for (const auto& spec : *l)
      {
        FUZZ_CHECK(names.insert(spec.name).second, "plugin names are unique");
        FUZZ_CHECK(!spec.type.empty(), "every plugin has a type");
      }
  }
  catch (const std::invalid_argument&)
  {
    lists_ok = false;
  }
  const CostmapConfig config = parseCostmapConfig(*ns);
  FUZZ_CHECK(std::isfinite(config.resolution) && config.resolution > 0, "resolution finite and > 0");
  FUZZ_CHECK(config.sizeInCellsX() >= 1 && config.sizeInCellsY() >= 1, "at least one cell a side");
  const Footprint footprint = config.footprint.padded();
  FUZZ_CHECK(footprint.size() >= 3, "a footprint has at least 3 vertices");
  for (const auto& v : footprint)
    FUZZ_CHECK(std::isfinite(v.x()) && std::isfinite(v.y()), "finite footprint");
  if (!lists_ok) return;

  LayeredCostmap lc(config.global_frame, config.rolling_window, config.track_unknown_space);
  const bool small = static_cast<uint64_t>(config.sizeInCellsX()) * config.sizeInCellsY() <= (1u << 16);
  if (small)
    lc.resizeMap(config.sizeInCellsX(), config.sizeInCellsY(), config.resolution, config.origin_x, config.origin_y);
  else
    lc.resizeMap(16, 16, config.resolution, config.origin_x, config.origin_y);
  loadPlugins(lc, lists, createLayer,
              [&](const PluginSpec& spec)
              {
                const ParamValue* sub = ns->find(spec.name);
                return std::make_shared<FuzzContext>(sub ? *sub : ParamValue::makeMap(), config.global_frame);
              });
  lc.setFootprint(footprint);
  lc.updateMap(config.origin_x, config.origin_y, 0.0);
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  if (size > 8192) return 0;
  try
  {
    run(std::string(reinterpret_cast<const char*>(data), size));
  }
  catch (const std::invalid_argument&)
  {
  }
  catch (const std::runtime_error&)
  {
  }
  return 0;
}
