#include "costmap_layers/ros/costmap_tool_app.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

#include "costmap_layers/core/costmap_builder.hpp"
#include "costmap_layers/core/costmap_config.hpp"
#include "costmap_layers/core/layer.hpp"
#include "costmap_layers/core/layered_costmap.hpp"
#include "costmap_layers/core/limits.hpp"
#include "costmap_layers/io/features_file.hpp"
#include "costmap_layers/io/map_file.hpp"
#include "costmap_layers/io/param_yaml.hpp"
#include "costmap_layers/io/png_writer.hpp"
#include "costmap_layers/ros/plugin_factory.hpp"

namespace costmap_layers_ros
{
using namespace costmap_layers;

namespace
{
const char* kUsage =
    "usage: costmap_tool --map MAP.yaml --params PARAMS.yaml [--namespace NS]\n"
    "                    [--mask PLUGIN_NAME=MASK.yaml]... [--features PLUGIN_NAME=FEATURES.yaml]...\n"
    "                    [--filter-info PLUGIN_NAME=TYPE,BASE,MULTIPLIER]...\n"
    "                    [--pose X,Y,YAW] [--repeat N] [--out-raw FILE] [--out-png FILE]";

struct ToolArgs
{
  std::string map, params, ns, out_raw, out_png;
  std::vector<std::pair<std::string, std::string>> masks, features, infos;
  bool has_pose = false;
  double x = 0, y = 0, yaw = 0;
  int repeat = 0;
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

ToolArgs parseArgs(const std::vector<std::string>& args)
{
  ToolArgs a;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& flag = args[i];
    if (flag == "-h" || flag == "--help") throw UsageError("");
    if (i + 1 >= args.size()) throw UsageError("missing value after " + flag);
    const std::string& v = args[++i];
    if (flag == "--map")
      a.map = v;
    else if (flag == "--params")
      a.params = v;
    else if (flag == "--namespace")
      a.ns = v;
    else if (flag == "--mask")
      a.masks.push_back(splitAssignment(flag, v));
    else if (flag == "--features")
      a.features.push_back(splitAssignment(flag, v));
    else if (flag == "--filter-info")
      a.infos.push_back(splitAssignment(flag, v));
    else if (flag == "--out-raw")
      a.out_raw = v;
    else if (flag == "--out-png")
      a.out_png = v;
    else if (flag == "--repeat")
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
      a.repeat = static_cast<int>(n);
    }
    else if (flag == "--pose")
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
    else
      throw UsageError("unknown option " + flag);
  }
  if (a.map.empty()) throw UsageError("--map is required");
  if (a.params.empty()) throw UsageError("--params is required");
  return a;
}

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

std::string jsonString(const std::string& s)
{
  std::string out = "\"";
  for (char c : s)
  {
    if (c == '"' || c == '\\')
      out += std::string("\\") + c;
    else if (static_cast<unsigned char>(c) < 0x20)
    {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    }
    else
      out += c;
  }
  return out + "\"";
}

std::string jsonNumber(double v)
{
  if (!std::isfinite(v)) return "null";
  std::ostringstream o;
  o << std::setprecision(10) << v;
  return o.str();
}

int run(const ToolArgs& a, std::ostream& out, std::ostream& err)
{
  ParamValue root = io::loadParamsYamlFile(a.params);
  const ParamValue* ns = a.ns.empty() ? &root : root.findPath(a.ns);
  if (ns == nullptr || !ns->isMap())
    throw std::runtime_error(a.params + ": namespace '" + a.ns + "' not found (or not a map)");
  const CostmapConfig config = parseCostmapConfig(*ns);
  const PluginLists lists = parsePluginLists(*ns);
  int error_count = 0;

  auto map = std::make_shared<OccupancyGridData>(io::loadMapFile(a.map));
  map->frame_id = config.global_frame;

  PluginFactory factory;
  std::map<std::string, std::shared_ptr<FileContext>> contexts;
  auto costmap =
      std::make_unique<LayeredCostmap>(config.global_frame, config.rolling_window, config.track_unknown_space);
  // Declared after the factory and destroyed first, while the plugin library is loaded.
  struct Release
  {
    std::unique_ptr<LayeredCostmap>& c;
    ~Release() { c.reset(); }
  } release{costmap};

  // The map sets the master grid, as a static map does.
  costmap->resizeMap(map->width, map->height, map->resolution, map->origin_x, map->origin_y);
  loadPlugins(
      *costmap, lists, [&factory](const std::string& type) { return factory.create(type); },
      [&](const PluginSpec& spec)
      {
        const ParamValue* sub = ns->find(spec.name);
        auto ctx = std::make_shared<FileContext>(spec.name, sub ? *sub : ParamValue::makeMap(), config.global_frame,
                                                 config.transform_tolerance, err, error_count);
        contexts[spec.name] = ctx;
        return ctx;
      });
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
    auto mask = std::make_shared<OccupancyGridData>(io::loadMapFile(file));
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

  auto pose = [&](double& x, double& y, double& yaw)
  {
    const Costmap2D& g = costmap->getCostmap();
    x = a.has_pose ? a.x : g.getOriginX() + g.getSizeInMetersX() / 2;
    y = a.has_pose ? a.y : g.getOriginY() + g.getSizeInMetersY() / 2;
    yaw = a.has_pose ? a.yaw : 0.0;
  };
  double x, y, yaw;
  using Clock = std::chrono::steady_clock;
  std::vector<double> times_ms;
  const int timed = a.repeat > 0 ? a.repeat : 1;
  for (int k = 0; k < timed + (a.repeat > 0 ? 1 : 0); ++k)
  {
    const bool warm_up = a.repeat > 0 && k == 0;
    const auto t0 = Clock::now();
    if (k > 0)
    {
      // Redo every layer's full work, as when a new map (and new masks) arrive.
      costmap->setFootprint(footprint);
      deliverMaps();
      deliverMasks();
    }
    pose(x, y, yaw);
    costmap->updateMap(x, y, yaw);
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    if (!warm_up) times_ms.push_back(ms);
  }
  std::vector<double> sorted = times_ms;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  const double median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);

  // A layer that refused an input (a map, a mask, speed limits) reported it as an error above: the
  // costmap is not what the files describe, so nothing is written and the exit status says so.
  if (error_count > 0)
    throw std::runtime_error(std::to_string(error_count) + " error(s) reported above; no result written");

  const Costmap2D& grid = costmap->getCostmap();
  if (!a.out_raw.empty()) io::writeRawBytes(a.out_raw, grid.data(), grid.cellCount());
  if (!a.out_png.empty()) io::writeCostmapPng(a.out_png, grid.data(), grid.getSizeInCellsX(), grid.getSizeInCellsY());

  std::ostringstream json;
  json << "{\"width\": " << grid.getSizeInCellsX() << ", \"height\": " << grid.getSizeInCellsY()
       << ", \"resolution\": " << jsonNumber(grid.getResolution()) << ", \"update_ms_median\": " << jsonNumber(median)
       << ", \"update_ms_min\": " << jsonNumber(sorted.front()) << ", \"repeats\": " << n << ", \"max_speed\": {";
  bool first = true;
  for (const auto* list : {&lists.plugins, &lists.filters})
  {
    for (const auto& spec : *list)
    {
      const auto it = max_speeds.find(spec.name);
      if (it == max_speeds.end()) continue;
      json << (first ? "" : ", ") << jsonString(spec.name) << ": " << jsonNumber(it->second);
      first = false;
    }
  }
  json << "}}";
  err.flush();
  out << json.str() << std::endl;
  return 0;
}
}  // namespace

int runCostmapTool(const std::vector<std::string>& args, std::ostream& out, std::ostream& err)
{
  ToolArgs parsed;
  try
  {
    parsed = parseArgs(args);
  }
  catch (const UsageError& e)
  {
    if (std::string(e.what()).empty())
    {
      out << kUsage << std::endl;
      return 0;
    }
    err << "costmap_tool: " << e.what() << "\n" << kUsage << std::endl;
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
