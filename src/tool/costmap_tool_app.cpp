#include "costmap_layers/tool/costmap_tool_app.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "costmap_layers/core/config/config_compat.hpp"
#include "costmap_layers/core/costmap/cost_query.hpp"
#include "costmap_layers/core/costmap/costmap_builder.hpp"
#include "costmap_layers/core/costmap/costmap_config.hpp"
#include "costmap_layers/core/costmap/layer.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/io/features_file.hpp"
#include "costmap_layers/io/map_file.hpp"
#include "costmap_layers/io/param_yaml.hpp"
#include "costmap_layers/io/png_writer.hpp"
#include "costmap_layers/io/zone_file.hpp"
#include "costmap_layers/ros/plugin_factory.hpp"
#include "costmap_layers/tool/param_reference.hpp"
#include "costmap_layers/tool/run_timing.hpp"

namespace costmap_layers_ros
{
using namespace costmap_layers;

namespace
{
const char* kDescription =
    "costmap_tool: the offline twin of costmap_node. Builds the costmap the params YAML describes, feeds it\n"
    "the map file (and masks and speed-limit files) where the node gets topics, runs an update at --pose\n"
    "and prints one JSON line: width, height, resolution, origin_x, origin_y, update_ms_median,\n"
    "update_ms_min, repeats, max_speed (and costs, costs_success with --cost). On a rolling_window costmap\n"
    "the result is the window of the configured width/height centred on --pose, as costmap_node publishes\n"
    "it. Each option may be given once, except --mask, --features, --filter-info, --plan (once per plugin name),\n"
    "--label and --cost.\n"
    "costmap_tool --describe-params [--markdown] prints every parameter, topic and service of every plugin\n"
    "(docs/parameters.md is that output).";

struct ToolArgs
{
  std::string map, params, ns, out_raw, out_png;
  std::vector<std::pair<std::string, std::string>> masks, features, infos, plans;
  bool has_pose = false;
  double x = 0, y = 0, yaw = 0;
  int repeat = 0;
  unsigned zoom = 1;
  struct Label
  {
    double x = 0, y = 0;  // in the global frame [m]
    std::string text;
  };
  std::vector<Label> labels;
  struct CostPose
  {
    double x = 0, y = 0, yaw = 0;  // in the global frame [m, m, rad]
  };
  std::vector<CostPose> costs;  // --cost, answered as costmap_node's ~get_cost
  bool cost_footprint = false;
};

struct UsageError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

std::pair<std::string, std::string> splitAssignment(const std::string& flag, const std::string& value)
{
  const auto eq = value.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == value.size())
    throw UsageError(flag + " expects PLUGIN_NAME=FILE (got \"" + value + "\")");
  return {value.substr(0, eq), value.substr(eq + 1)};
}

/// PLUGIN_NAME=FILE assignments of a repeatable flag; one plugin named twice is an error.
std::vector<std::pair<std::string, std::string>> assignments(const std::string& flag,
                                                             const std::vector<std::string>& values)
{
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& v : values)
  {
    auto a = splitAssignment(flag, v);
    for (const auto& [name, file] : out)
      if (name == a.first)
        throw UsageError(flag + " names plugin '" + name + "' twice (\"" + file + "\" and \"" + a.second +
                         "\"): give one file per plugin");
    out.push_back(std::move(a));
  }
  return out;
}

int parseRepeat(const std::string& v)
{
  std::size_t used = 0;
  long n = -1;
  try
  {
    n = std::stol(v, &used);
  }
  catch (const std::exception&)
  {
  }
  if (used != v.size() || n < 1 || n > 100000)
    throw UsageError("--repeat expects a count in 1..100000 (got \"" + v + "\")");
  return static_cast<int>(n);
}

void parsePose(const std::string& v, ToolArgs& a)
{
  double p[3];
  std::istringstream in(v);
  char c1 = 0, c2 = 0;
  // NaN fails every comparison below, so it is refused with the infinities.
  if (!(in >> p[0] >> c1 >> p[1] >> c2 >> p[2]) || c1 != ',' || c2 != ',' || !in.eof() ||
      !(std::fabs(p[0]) <= limits::kMaxCoordinate) || !(std::fabs(p[1]) <= limits::kMaxCoordinate) ||
      !(std::fabs(p[2]) <= limits::kMaxYaw))
  {
    std::ostringstream msg;
    msg << "--pose expects X,Y,YAW as three finite numbers, |X| and |Y| at most " << limits::kMaxCoordinate
        << " m and |YAW| at most " << limits::kMaxYaw << " rad (got \"" << v << "\")";
    throw UsageError(msg.str());
  }
  a.has_pose = true;
  a.x = p[0];
  a.y = p[1];
  a.yaw = p[2];
}

unsigned parseZoom(const std::string& v)
{
  std::size_t used = 0;
  long n = -1;
  try
  {
    n = std::stol(v, &used);
  }
  catch (const std::exception&)
  {
  }
  if (used != v.size() || n < 1 || n > static_cast<long>(io::kMaxPngZoom))
    throw UsageError("--zoom expects a whole number in 1.." + std::to_string(io::kMaxPngZoom) + " (got \"" + v + "\")");
  return static_cast<unsigned>(n);
}

/// X,Y,TEXT: the text is everything after the second comma (it may hold commas); what it may hold and
/// where it may go is checked by the PNG writer, which knows the font and the grid.
ToolArgs::Label parseLabel(const std::string& v)
{
  const auto c1 = v.find(',');
  const auto c2 = c1 == std::string::npos ? std::string::npos : v.find(',', c1 + 1);
  ToolArgs::Label l;
  bool ok = c2 != std::string::npos && c2 + 1 < v.size();
  for (int k = 0; ok && k < 2; ++k)
  {
    const std::string num = k == 0 ? v.substr(0, c1) : v.substr(c1 + 1, c2 - c1 - 1);
    std::istringstream in(num);
    double d = 0;
    ok = static_cast<bool>(in >> d) && in.eof() && std::fabs(d) <= limits::kMaxCoordinate;  // NaN fails too
    (k == 0 ? l.x : l.y) = d;
  }
  if (!ok)
  {
    std::ostringstream msg;
    msg << "--label expects X,Y,TEXT: two finite numbers, |X| and |Y| at most " << limits::kMaxCoordinate
        << " m, then the text (got \"" << v.substr(0, 80) << (v.size() > 80 ? "..." : "") << "\")";
    throw UsageError(msg.str());
  }
  l.text = v.substr(c2 + 1);
  return l;
}

/// X,Y or X,Y,YAW: finite, within the limits every coordinate is held to.
ToolArgs::CostPose parseCostPose(const std::string& v)
{
  double p[3] = {0, 0, 0};
  std::istringstream in(v);
  char c1 = 0, c2 = 0;
  bool ok = static_cast<bool>(in >> p[0] >> c1 >> p[1]) && c1 == ',';
  if (ok && !in.eof()) ok = static_cast<bool>(in >> c2 >> p[2]) && c2 == ',' && in.eof();
  // NaN fails every comparison below, so it is refused with the infinities.
  if (!ok || !(std::fabs(p[0]) <= limits::kMaxCoordinate) || !(std::fabs(p[1]) <= limits::kMaxCoordinate) ||
      !(std::fabs(p[2]) <= limits::kMaxYaw))
  {
    std::ostringstream msg;
    msg << "--cost expects X,Y or X,Y,YAW as finite numbers, |X| and |Y| at most " << limits::kMaxCoordinate
        << " m and |YAW| at most " << limits::kMaxYaw << " rad (got \"" << v.substr(0, 80)
        << (v.size() > 80 ? "..." : "") << "\")";
    throw UsageError(msg.str());
  }
  return {p[0], p[1], p[2]};
}

/// The command line. Each single-valued option may appear once (CLI11's Throw policy: a second one is
/// an error naming the option); --mask and --features repeat, once per plugin name.
class ToolCommandLine
{
public:
  ToolCommandLine() : app_(kDescription, "costmap_tool")
  {
    app_.add_option("--map", map_, "map_server map YAML: the map every map input receives")
        ->required()
        ->type_name("MAP.yaml");
    app_.add_option("--params", params_, "costmap parameters YAML (costmap_node's)")
        ->required()
        ->type_name("PARAMS.yaml");
    app_.add_option("--namespace", ns_, "the costmap's key path inside PARAMS.yaml, e.g. local_costmap/costmap")
        ->type_name("NS");
    app_.add_option("--mask", masks_, "a filter mask for the named filter (repeatable)")
        ->allow_extra_args(false)
        ->type_name("PLUGIN_NAME=MASK.yaml");  // a map file, or a zone file (zone_server's shapes)
    app_.add_option("--features", features_, "speed limits for the named SpeedFilter (repeatable)")
        ->allow_extra_args(false)
        ->type_name("PLUGIN_NAME=FEATURES.yaml");
    app_.add_option("--filter-info", infos_,
                    "the filter info of a filter configured Nav2's way (filter_info_topic), repeatable")
        ->allow_extra_args(false)
        ->type_name("PLUGIN_NAME=TYPE,BASE,MULTIPLIER");
    app_.add_option("--plan", plans_, "a planned path for the named plugin's plan input, global frame (repeatable)")
        ->allow_extra_args(false)
        ->type_name("PLUGIN_NAME=X1,Y1,X2,Y2[,...]");
    app_.add_option("--pose", pose_, "robot pose in the global frame [m, m, rad]; default: the map's centre, yaw 0")
        ->type_name("X,Y,YAW");
    app_.add_option("--repeat", repeat_, "time N full updates (after one warm-up) and report median and min")
        ->type_name("N");
    app_.add_option("--out-raw", out_raw_, "write the costs, one byte per cell, row 0 first")->type_name("FILE");
    app_.add_option("--out-png", out_png_, "write the costs as a PNG picture")->type_name("FILE");
    app_.add_option("--zoom", zoom_, "--out-png: draw each cell as N x N pixels (1..8)")->type_name("N");
    app_.add_option("--label", labels_, "--out-png: write TEXT centred on (X, Y) [m, global frame] (repeatable)")
        ->allow_extra_args(false)
        ->type_name("X,Y,TEXT");
    app_.add_option("--cost", costs_, "add the cost at (X, Y) [m, global frame] to the output's costs (repeatable)")
        ->allow_extra_args(false)
        ->type_name("X,Y[,YAW]");
    app_.add_flag("--cost-footprint", cost_footprint_,
                  "--cost: the highest cost on the footprint's outline placed at X,Y,YAW (Nav2's use_footprint)");
    app_.allow_extras(true);  // reported below as unknown options, in the tool's own words
  }

  std::string usage() const { return app_.help(); }

  /// Throws UsageError; CLI::CallForHelp for -h / --help.
  ToolArgs parse(const std::vector<std::string>& args)
  {
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
    try
    {
      app_.parse(reversed);
    }
    catch (const CLI::CallForHelp&)
    {
      throw;
    }
    catch (const CLI::ArgumentMismatch& e)
    {
      std::string what = e.what();
      if (what.find("At Most") != std::string::npos)
        what += " (each option may be given once; --mask, --features and --filter-info once per plugin name)";
      throw UsageError(what);
    }
    catch (const CLI::ParseError& e)
    {
      throw UsageError(e.what());
    }
    for (const auto& extra : app_.remaining())
      throw UsageError(extra.rfind("-", 0) == 0 ? "unknown option " + extra : "unexpected argument \"" + extra + "\"");
    ToolArgs a;
    a.map = map_;
    a.params = params_;
    a.ns = ns_;
    a.out_raw = out_raw_;
    a.out_png = out_png_;
    a.masks = assignments("--mask", masks_);
    a.features = assignments("--features", features_);
    a.infos = assignments("--filter-info", infos_);
    a.plans = assignments("--plan", plans_);
    if (app_.count("--repeat")) a.repeat = parseRepeat(repeat_);
    if (app_.count("--pose")) parsePose(pose_, a);
    if (app_.count("--zoom")) a.zoom = parseZoom(zoom_);
    for (const auto& l : labels_)
      a.labels.push_back(parseLabel(l));
    if (costs_.size() > kMaxCostQueryPoses)
      throw UsageError("--cost is given " + std::to_string(costs_.size()) + " times, at most " +
                       std::to_string(kMaxCostQueryPoses));
    for (const auto& c : costs_)
      a.costs.push_back(parseCostPose(c));
    a.cost_footprint = cost_footprint_;
    if (a.cost_footprint && a.costs.empty())
      throw UsageError("--cost-footprint shapes the --cost answers: give --cost too");
    if ((app_.count("--zoom") || !a.labels.empty()) && a.out_png.empty())
      throw UsageError("--zoom and --label shape the --out-png picture: give --out-png FILE too");
    return a;
  }

private:
  CLI::App app_;
  std::string map_, params_, ns_, out_raw_, out_png_, pose_, repeat_, zoom_;
  std::vector<std::string> masks_, features_, infos_, plans_, labels_, costs_;
  bool cost_footprint_ = false;
};

/// The tool's LayerContext: no tf (every frame is the global frame), reports to stderr. The tool itself
/// plays the host's part for inputs and outputs: files to the layers' input ports.
class FileContext : public LayerContext
{
public:
  FileContext(std::string name, ParamValue params, std::string global_frame, double tolerance, std::ostream& err,
              int& error_count)
      : name_(std::move(name)),
        params_(std::move(params)),
        global_frame_(std::move(global_frame)),
        tolerance_(tolerance),
        err_(err),
        error_count_(error_count)
  {
  }
  const ParamValue& params() const override { return params_; }
  const std::string& globalFrame() const override { return global_frame_; }
  double transformTolerance() const override { return tolerance_; }
  std::optional<Transform2D> lookupTransform(const std::string& target, const std::string& source,
                                             std::string* error) override
  {
    if (target == source) return Transform2D{};
    if (error) *error = "costmap_tool has no tf: frames " + source + " and " + target + " differ";
    return std::nullopt;
  }
  uint64_t nowNs() const override
  {
    return static_cast<uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
            .count());
  }
  void report(Severity severity, const std::string& key, const std::string& message) override
  {
    // An error means an input was refused: the result would not be what the files describe.
    if (severity == Severity::Error) ++error_count_;
    if (reported_count_[key]++ >= 3) return;  // the same problem every cycle says nothing new
    static const char* names[] = {"debug", "info", "warning", "error"};
    err_ << "costmap_tool: " << names[static_cast<int>(severity)] << ": " << message << "\n";
  }

private:
  std::string name_;
  ParamValue params_;
  std::string global_frame_;
  double tolerance_;
  std::ostream& err_;
  int& error_count_;
  std::map<std::string, int> reported_count_;
};

int run(const ToolArgs& a, std::ostream& out, std::ostream& err)
{
  // Typed as `rosparam load` types it (PyYAML's floats), so that the tool refuses what the node would.
  // A key written twice keeps its last value, as rosparam (PyYAML) loads it for costmap_node; said here,
  // where the file is read.
  std::vector<std::string> repeated_keys;
  ParamValue root = io::loadParamsYamlFile(a.params, io::kMaxParamsYamlBytes, true, &repeated_keys);
  for (const auto& r : repeated_keys)
    err << "costmap_tool: warning: " << r << " (as rosparam loads it)\n";
  const ParamValue* raw = a.ns.empty() ? &root : root.findPath(a.ns);
  if (raw == nullptr || !raw->isMap())
    throw std::runtime_error(a.params + ": namespace '" + a.ns + "' not found (or not a map)");
  // The costmap's namespace as costmap_node reads it from the parameter server: costmap_2d's rules
  // (pre-Hydro keys, copyParentParameters, searchParam in the levels around --namespace), said the same.
  std::string own_name = a.ns;
  while (!own_name.empty() && own_name.back() == '/')
    own_name.pop_back();
  own_name = own_name.substr(own_name.rfind('/') + 1);
  const CompatResult compat = prepareCostmapNamespace(*raw, own_name, parentsInTree(root, a.ns));
  for (const auto& w : compat.warnings)
    err << "costmap_tool: warning: " << w << "\n";
  for (const auto& n : compat.notes)
    err << "costmap_tool: info: " << n << "\n";
  if (compat.converted_pre_hydro)
    err << "costmap_tool: info: the same costmap as a plugin list (costmap_2d's form):\n"
        << io::paramToYaml(compat.plugin_list);
  const ParamValue* ns = &compat.params;
  // Every parameter look-up until the layers are set up is noted, so that unused keys can be named.
  ParamReadLog read_log;
  const CostmapConfig config = parseCostmapConfig(*ns);
  const PluginLists lists = parsePluginLists(*ns);
  int error_count = 0;

  auto map = std::make_shared<OccupancyGridData>(io::loadMapFile(a.map));
  map->frame_id = config.global_frame;

  PluginFactory factory;
  std::map<std::string, std::shared_ptr<FileContext>> contexts;
  std::vector<PluginSpec> made;
  auto costmap =
      std::make_unique<LayeredCostmap>(config.global_frame, config.rolling_window, config.track_unknown_space);
  // Declared after the factory and destroyed first, while the plugin library is loaded.
  struct Release
  {
    std::unique_ptr<LayeredCostmap>& c;
    ~Release() { c.reset(); }
  } release{costmap};

  // Not rolling: the map sets the master grid, as a static map does. Rolling: the master grid is the
  // configured window (width x height at the configured resolution), as costmap_node sizes it; the
  // update at the pose centres it there.
  if (config.rolling_window)
    costmap->resizeMap(config.sizeInCellsX(), config.sizeInCellsY(), config.resolution, config.origin_x,
                       config.origin_y);
  else
    costmap->resizeMap(map->width, map->height, map->resolution, map->origin_x, map->origin_y);
  loadPlugins(
      *costmap, lists, [&factory](const std::string& type) { return factory.create(type); },
      [&](const PluginSpec& spec)
      {
        const ParamValue* sub = pluginParams(*ns, spec.name);
        auto ctx = std::make_shared<FileContext>(spec.name, sub ? *sub : ParamValue::makeMap(), config.global_frame,
                                                 config.transform_tolerance, err, error_count);
        contexts[spec.name] = ctx;
        made.push_back(spec);  // a container's plugins too ("<container>/<plugin>")
        return ctx;
      });
  std::vector<std::pair<PluginSpec, const ParamValue*>> layer_params;
  for (const auto& spec : made)
    layer_params.emplace_back(spec, &contexts.at(spec.name)->params());
  for (const auto& line : unusedParameterLines(compat, read_log, layer_params, a.ns.empty() ? "/" : a.ns))
    err << "costmap_tool: warning: " << line << "\n";
  const Footprint footprint = config.footprint.padded();
  costmap->setFootprint(footprint);

  // Inputs: the map to every map input, masks and features to the named plugins' inputs.
  auto layerNamed = [&](const std::string& name, const char* flag)
  {
    auto layer = contexts.count(name) ? costmap->findLayer(name) : nullptr;
    if (!layer) throw std::runtime_error(std::string(flag) + " names plugin '" + name + "', which is not configured");
    return layer;
  };
  auto portsOf = [](const Layer& layer, InputKind kind)
  {
    std::vector<const InputPort*> ports;
    for (const auto& in : layer.inputs())
      if (in.kind == kind) ports.push_back(&in);
    return ports;
  };
  // Filters in Nav2's form (filter_info_topic) take their info from --filter-info; the mask port the
  // info connects replaces the declared one (kept here, as the node re-subscribes).
  std::map<std::string, std::map<std::size_t, InputPort>> replaced;
  std::map<std::string, bool> has_info;
  for (const auto& [name, spec] : a.infos)
  {
    auto layer = layerNamed(name, "--filter-info");
    const auto ports = portsOf(*layer, InputKind::FilterInfo);
    if (ports.empty())
      throw std::runtime_error("--filter-info names plugin '" + name +
                               "', which reads no filter info (no filter_info_topic)");
    auto info = std::make_shared<FilterInfoData>();
    std::istringstream in(spec);
    int type = -1;
    char c1 = 0, c2 = 0;
    if (!(in >> type >> c1 >> info->base >> c2 >> info->multiplier) || c1 != ',' || c2 != ',' || !in.eof() ||
        type < 0 || type > 255)
      throw std::runtime_error("--filter-info expects PLUGIN_NAME=TYPE,BASE,MULTIPLIER (got \"" + name + "=" + spec +
                               "\")");
    info->type = static_cast<uint8_t>(type);
    info->filter_mask_topic = "costmap_tool/" + name;
    layer->setInputListener([&replaced, name = name](std::size_t index, const InputPort& port)
                            { replaced[name][index] = port; });
    for (const InputPort* port : ports)
      port->on_info(info);
    layer->setInputListener({});
    has_info[name] = true;
  }
  std::vector<std::pair<GridCallback, std::shared_ptr<const OccupancyGridData>>> masks;
  for (const auto& [name, file] : a.masks)
  {
    auto layer = layerNamed(name, "--mask");
    if (!portsOf(*layer, InputKind::FilterInfo).empty() && !has_info[name])
      throw std::runtime_error("--mask names plugin '" + name +
                               "', which reads its mask's meaning from a filter info " +
                               "(filter_info_topic): give --filter-info " + name + "=TYPE,BASE,MULTIPLIER too");
    std::vector<GridCallback> handlers;
    for (std::size_t i = 0; i < layer->inputs().size(); ++i)
    {
      if (layer->inputs()[i].kind != InputKind::Mask) continue;
      const auto r = replaced[name].find(i);
      handlers.push_back(r != replaced[name].end() ? r->second.on_grid : layer->inputs()[i].on_grid);
    }
    if (handlers.empty()) throw std::runtime_error("--mask names plugin '" + name + "', which takes no mask");
    // A zone file (zone_server's shapes) is rasterised as zone_server would publish it.
    const auto zones = io::loadIfZoneFile(file);
    auto mask = std::make_shared<OccupancyGridData>(zones ? rasterizeZones(*zones) : io::loadMapFile(file));
    mask->frame_id = config.global_frame;
    for (const GridCallback& handler : handlers)
      masks.emplace_back(handler, mask);
  }
  for (const auto& [name, file] : a.features)
  {
    const auto ports = portsOf(*layerNamed(name, "--features"), InputKind::SpeedLimits);
    if (ports.empty()) throw std::runtime_error("--features names plugin '" + name + "', which takes no speed limits");
    auto limits = std::make_shared<SpeedLimitsData>(io::loadFeaturesFile(file));
    limits->frame_id = config.global_frame;
    for (const InputPort* port : ports)
      port->on_limits(limits);
  }
  for (const auto& [name, spec] : a.plans)
  {
    const auto ports = portsOf(*layerNamed(name, "--plan"), InputKind::Path);
    if (ports.empty()) throw std::runtime_error("--plan names plugin '" + name + "', which takes no plan");
    // X1,Y1,X2,Y2,...: the layer checks the poses themselves (finite, how many) as it checks a message.
    auto plan = std::make_shared<PathData>();
    plan->frame_id = config.global_frame;
    std::istringstream in(spec);
    std::string item;
    std::vector<double> values;
    while (std::getline(in, item, ','))
    {
      std::size_t used = 0;
      double v = 0.0;
      try
      {
        v = std::stod(item, &used);
      }
      catch (const std::exception&)
      {
        used = 0;
      }
      if (used == 0 || used != item.size() || values.size() > 2 * limits::kMaxPathPoses)
        throw std::runtime_error("--plan expects PLUGIN_NAME=X1,Y1,X2,Y2[,...] with at most " +
                                 std::to_string(limits::kMaxPathPoses) + " poses (got \"" + name + "=" +
                                 shownText(spec, 80) + "\")");
      values.push_back(v);
    }
    if (values.size() % 2 != 0)
      throw std::runtime_error("--plan for '" + name + "' has an odd count of numbers (" +
                               std::to_string(values.size()) + "): X and Y of each pose");
    for (std::size_t k = 0; k + 1 < values.size(); k += 2)
      plan->poses.push_back({values[k], values[k + 1]});
    for (const InputPort* port : ports)
      port->on_path(plan);
  }
  auto deliverMasks = [&]
  {
    for (const auto& [handler, mask] : masks)
      handler(mask);
  };
  deliverMasks();
  auto deliverMaps = [&]
  {
    for (const auto& [name, ctx] : contexts)
      for (const InputPort* port : portsOf(*costmap->findLayer(name), InputKind::Map))
        port->on_grid(map);
  };
  deliverMaps();
  // Outputs: the last max speed of each plugin that has one.
  std::map<std::string, double> max_speeds;
  for (const auto& [name, ctx] : contexts)
  {
    auto layer = costmap->findLayer(name);
    if (layer->outputs().empty()) continue;
    layer->setOutputListener(
        [&max_speeds, name = name](const OutputEvent& e)
        {
          if (e.kind == OutputKind::MaxSpeed) max_speeds[name] = e.value;
        });
  }

  // Without --pose: the map's centre (the map's, not the grid's: a rolling window moves).
  const double x = a.has_pose ? a.x : map->origin_x + map->width * map->resolution / 2;
  const double y = a.has_pose ? a.y : map->origin_y + map->height * map->resolution / 2;
  const double yaw = a.has_pose ? a.yaw : 0.0;
  // --repeat N: one warm-up, then N timed updates; each redoes every layer's full work, as when a new
  // map (and new masks) arrive. Summarised by the same code as the benchmarks' "min" (run_timing.hpp).
  const RunTimes times = timeRuns(a.repeat > 0 ? 1 : 0, a.repeat > 0 ? a.repeat : 1,
                                  [&](int k)
                                  {
                                    if (k > 0)
                                    {
                                      costmap->setFootprint(footprint);
                                      deliverMaps();
                                      deliverMasks();
                                    }
                                    costmap->updateMap(x, y, yaw);
                                  });

  // A layer that refused an input (a map, a mask, speed limits) reported it as an error above: the
  // costmap is not what the files describe, so nothing is written and the exit status says so.
  if (error_count > 0)
    throw std::runtime_error(std::to_string(error_count) + " error(s) reported above; no result written");

  const Costmap2D& grid = costmap->getCostmap();
  if (!a.out_raw.empty()) io::writeRawBytes(a.out_raw, grid.data(), grid.cellCount());
  if (!a.out_png.empty())
  {
    io::PngOptions png;
    png.zoom = a.zoom;
    const double res = grid.getResolution();
    const double w = grid.getSizeInCellsX(), h = grid.getSizeInCellsY();
    for (const auto& l : a.labels)  // into cells; what the text may hold the writer checks
    {
      const double col = (l.x - grid.getOriginX()) / res, row = (l.y - grid.getOriginY()) / res;
      if (!(col >= 0 && col <= w && row >= 0 && row <= h))
      {
        std::ostringstream msg;
        msg << "--label \"" << l.text.substr(0, 48) << "\": (" << l.x << ", " << l.y
            << ") is outside the costmap, which spans x " << grid.getOriginX() << ".." << grid.getOriginX() + w * res
            << " and y " << grid.getOriginY() << ".." << grid.getOriginY() + h * res << " m";
        throw std::runtime_error(msg.str());
      }
      png.labels.push_back({col, row, l.text});
    }
    io::writeCostmapPng(a.out_png, grid.data(), grid.getSizeInCellsX(), grid.getSizeInCellsY(), png);
  }

  nlohmann::ordered_json json;
  json["width"] = grid.getSizeInCellsX();
  json["height"] = grid.getSizeInCellsY();
  json["resolution"] = grid.getResolution();
  json["origin_x"] = grid.getOriginX();
  json["origin_y"] = grid.getOriginY();
  json["update_ms_median"] = times.median_ms();
  json["update_ms_min"] = times.min_ms();
  json["repeats"] = times.ms.size();
  json["max_speed"] = nlohmann::ordered_json::object();
  for (const auto* list : {&lists.plugins, &lists.filters})
    for (const auto& spec : *list)
    {
      const auto it = max_speeds.find(spec.name);
      if (it != max_speeds.end()) json["max_speed"][spec.name] = it->second;  // a non-finite number is null
    }
  if (!a.costs.empty())
  {
    // As costmap_node's ~get_cost answers them (cost_query.hpp): 254 off the map, success false then.
    json["costs"] = nlohmann::ordered_json::array();
    bool success = true;
    for (const auto& c : a.costs)
    {
      const CostAnswer answer =
          a.cost_footprint ? footprintCostAtPose(grid, c.x, c.y, c.yaw, footprint) : pointCost(grid, c.x, c.y);
      json["costs"].push_back(answer.cost);
      success = success && answer.ok;
    }
    json["costs_success"] = success;
  }
  err.flush();
  out << json.dump() << std::endl;
  return 0;
}
}  // namespace

int runCostmapTool(const std::vector<std::string>& args, std::ostream& out, std::ostream& err)
{
  // The reference mode needs no map and no params: what every plugin reads, from its parse functions.
  if (!args.empty() && args[0] == "--describe-params")
  {
    const bool markdown = args.size() == 2 && args[1] == "--markdown";
    if (args.size() > 2 || (args.size() == 2 && !markdown))
    {
      err << "costmap_tool: --describe-params takes only --markdown (got \"" << args.back() << "\")" << std::endl;
      return 2;
    }
    try
    {
      PluginFactory factory;
      const ParamReference reference = describeParameters(factory);
      out << (markdown ? referenceMarkdown(reference) : referenceText(reference));
      out.flush();
      return 0;
    }
    catch (const std::exception& e)
    {
      err << "costmap_tool: error: " << e.what() << std::endl;
      return 1;
    }
  }
  ToolCommandLine command_line;
  ToolArgs parsed;
  try
  {
    parsed = command_line.parse(args);
  }
  catch (const CLI::CallForHelp&)
  {
    out << command_line.usage() << std::endl;
    return 0;
  }
  catch (const UsageError& e)
  {
    err << "costmap_tool: " << e.what() << "\n"
        << "run costmap_tool --help for the options" << std::endl;
    return 2;
  }
  try
  {
    return run(parsed, out, err);
  }
  catch (const std::exception& e)
  {
    err << "costmap_tool: error: " << e.what() << std::endl;
    return 1;
  }
}
}  // namespace costmap_layers_ros
