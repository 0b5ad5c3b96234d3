#include "costmap_layers/move_base/layer_bridge.hpp"

#include <costmap_2d/layered_costmap.h>
#include <ros/ros.h>

#include <algorithm>
#include <limits>
#include <type_traits>
#include <vector>

#include "costmap_layers/core/config/config_compat.hpp"
#include "costmap_layers/core/costmap/costmap_clearing.hpp"
#include "costmap_layers/core/rules/stamp_order.hpp"
#include "costmap_layers/core/filters/costmap_filter.hpp"
#include "costmap_layers/core/costmap/costmap_layer.hpp"
#include "costmap_layers/core/grid/footprint.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/layers/plugin_container_layer.hpp"
#include "costmap_layers/core/layers/static_layer.hpp"
#include "costmap_layers/core/config/plugin_types.hpp"
#include "costmap_layers/core/config/unknown_keys.hpp"
#include "costmap_layers/ros/conversions.hpp"
#include "costmap_layers/ros/costmap_node.hpp"
#include "costmap_layers/ros/layer_ports.hpp"
#include "costmap_layers/ros/layer_reconfigure.hpp"
#include "costmap_layers/ros/plugin_factory.hpp"
#include "costmap_layers/ros/ros_layer_context.hpp"

namespace costmap_layers
{
namespace move_base
{
namespace
{
/// The factory of a PluginContainerLayer's plugins: costmap_node's (this package's layers, by pluginlib).
/// One for the library's life, so that its plugin library outlives every layer it made.
costmap_layers_ros::PluginFactory& heldLayerFactory()
{
  static costmap_layers_ros::PluginFactory factory;
  return factory;
}

/// costmap_2d's Costmap2DROS default; its layers are not told the costmap's value.
constexpr double kDefaultTransformTolerance = 0.3;

/// The costmap's transform_tolerance: the parent namespace of the plugin's (~/<costmap>), as
/// Costmap2DROS reads it.
double transformTolerance(const ros::NodeHandle& plugin_nh)
{
  const std::string costmap_ns = ros::names::parentNamespace(plugin_nh.getNamespace());
  double tolerance = kDefaultTransformTolerance;
  ros::param::param(costmap_ns + "/transform_tolerance", tolerance, kDefaultTransformTolerance);
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
  {
    ROS_ERROR("%s/transform_tolerance is %f; it must be a finite number >= 0: using %.1f", costmap_ns.c_str(),
              tolerance, kDefaultTransformTolerance);
    tolerance = kDefaultTransformTolerance;
  }
  return tolerance;
}
}  // namespace

template <class Base>
LayerBridgeOn<Base>::LayerBridgeOn(std::shared_ptr<costmap_layers::Layer> core, std::string class_name)
    : core_(std::move(core)), class_name_(std::move(class_name))
{
}

// Ports and the reconfigure server go first: their callbacks reach into the core layer.
template <class Base>
LayerBridgeOn<Base>::~LayerBridgeOn()
{
  held_reconfigure_.clear();
  held_ports_.clear();
  reconfigure_.reset();
  ports_.reset();
}

template <class Base>
void LayerBridgeOn<Base>::onInitialize()
{
  try
  {
    setUp();
  }
  catch (const std::exception& e)
  {
    // A parameter out of range or of the wrong type stops the start-up, naming it, as in costmap_node.
    ROS_FATAL("%s (costmap_layers %s): %s", ros::NodeHandle("~/" + this->name_).getNamespace().c_str(),
              class_name_.c_str(), e.what());
    throw;
  }
}

template <class Base>
void LayerBridgeOn<Base>::setUp()
{
  ros::NodeHandle nh("~/" + this->name_);
  const std::string global_frame = this->layered_costmap_->getGlobalFrameID();
  costmap_layers::ParamValue params = layerParameters(nh);
  log_ = std::make_shared<costmap_layers_ros::ThrottledLog>();
  context_ = std::make_shared<costmap_layers_ros::RosLayerContext>(nh, params, global_frame, transformTolerance(nh),
                                                                   *this->tf_, log_);
  host_ = std::make_unique<costmap_layers::LayeredCostmap>(global_frame, this->layered_costmap_->isRolling(),
                                                           this->layered_costmap_->isTrackingUnknown());
  // A layer that resizes the master (the static layer, to its map) resizes move_base's; costmap_2d
  // then calls matchSize on every plugin, this one included, which views the new memory.
  host_->setResizeHandler(
      [this](unsigned int size_x, unsigned int size_y, double resolution, double origin_x, double origin_y,
             bool size_locked)
      { this->layered_costmap_->resizeMap(size_x, size_y, resolution, origin_x, origin_y, size_locked); });
  readCostmap2dStaticLayers(nh);
  viewMaster();
  host_->addPlugin(core_);
  // A container's plugins: this package's layers, made by costmap_node's factory (pluginlib), each with
  // its namespace below the container's, ~/<costmap>/<container>/<plugin>.
  std::vector<std::pair<costmap_layers::PluginSpec, std::shared_ptr<costmap_layers_ros::RosLayerContext>>> held;
  if (auto* container = dynamic_cast<costmap_layers::PluginContainerLayer*>(core_.get()))
  {
    costmap_layers::LayerMaker maker;
    maker.layers = [](const std::string& type) { return heldLayerFactory().create(type); };
    maker.contexts = [&, this](const costmap_layers::PluginSpec& spec)
    {
      const costmap_layers::ParamValue* sub =
          costmap_layers::pluginParams(context_->params(), spec.name.substr(this->name_.size() + 1));
      auto ctx = std::make_shared<costmap_layers_ros::RosLayerContext>(
          ros::NodeHandle("~/" + spec.name), sub != nullptr ? *sub : costmap_layers::ParamValue::makeMap(),
          global_frame, transformTolerance(nh), *this->tf_, log_);
      held.emplace_back(spec, ctx);
      return ctx;
    };
    container->setMaker(std::move(maker), 1);
  }
  {
    costmap_layers::ParamReadLog read_log;
    core_->initialize(host_.get(), this->name_, context_);
    std::vector<std::string> known = {"plugin"};
    known.insert(known.end(), consumed_keys_.begin(), consumed_keys_.end());
    // A container's plugin namespaces are walked as the plugins' own, below.
    std::vector<std::string> skip;
    for (const auto& layer : core_->heldLayers())
      skip.push_back(layer->getName().substr(this->name_.size() + 1));
    for (const auto& u : costmap_layers::unknownKeys(context_->params(), read_log, class_name_, known, skip))
      ROS_WARN("%s", costmap_layers::describeUnknownKey(u, nh.getNamespace()).c_str());
    for (const auto& [spec, ctx] : held)
    {
      std::vector<std::string> held_skip;
      for (const auto& layer : host_->findLayer(spec.name)->heldLayers())
        held_skip.push_back(layer->getName().substr(spec.name.size() + 1));
      const std::string scope = costmap_layers::pluginClassName(costmap_layers::resolvePluginType(spec.type));
      for (const auto& u : costmap_layers::unknownKeys(ctx->params(), read_log, scope, {"plugin"}, held_skip))
        ROS_WARN(
            "%s",
            costmap_layers::describeUnknownKey(u, ros::NodeHandle("~/" + spec.name).getNamespace(), {}, scope).c_str());
    }
  }
  onFootprintChanged();
  ports_ =
      std::make_unique<costmap_layers_ros::LayerPorts>(ros::NodeHandle(), nh, *core_, global_frame, *this->tf_, log_);
  const costmap_layers_ros::LayerReconfigure::RunLocked run_locked = [this](const std::function<void()>& fn)
  {
    boost::unique_lock<costmap_2d::Costmap2D::mutex_t> lock(*this->layered_costmap_->getCostmap()->getMutex());
    const auto own = lockOwnGrid();
    fn();
    full_update_ = true;
  };
  reconfigure_ = std::make_unique<costmap_layers_ros::LayerReconfigure>(nh, core_, params, run_locked);
  for (const auto& [spec, ctx] : held)
  {
    const ros::NodeHandle held_nh("~/" + spec.name);
    const auto layer = host_->findLayer(spec.name);
    held_ports_.push_back(std::make_unique<costmap_layers_ros::LayerPorts>(ros::NodeHandle(), held_nh, *layer,
                                                                           global_frame, *this->tf_, log_));
    held_reconfigure_.push_back(
        std::make_unique<costmap_layers_ros::LayerReconfigure>(held_nh, layer, ctx->params(), run_locked));
  }
  if (const auto* static_layer = dynamic_cast<const costmap_layers::StaticLayer*>(core_.get()))
    waitForMap(*static_layer, nh);
  for (const auto& [spec, ctx] : held)
    if (const auto* static_layer = dynamic_cast<const costmap_layers::StaticLayer*>(host_->findLayer(spec.name).get()))
      waitForMap(*static_layer, ros::NodeHandle("~/" + spec.name));
  this->enabled_ = true;  // costmap_2d skips disabled plugins; the core layer's own switch is honoured below
  this->current_ = core_->isCurrent();
  ROS_INFO("%s: costmap_layers %s hosted in costmap_2d", nh.getNamespace().c_str(), class_name_.c_str());
}

template <class Base>
costmap_layers::ParamValue LayerBridgeOn<Base>::layerParameters(const ros::NodeHandle& nh)
{
  // costmap_2d copies costmap-level keys into its own layers and looks some up in the namespaces above
  // (copyParentParameters, searchParam), for its own types only: a user who swaps costmap_2d's type for
  // this one keeps what those rules gave the layer, told what came from where.
  const std::string costmap_ns = ros::names::parentNamespace(nh.getNamespace());
  const std::string key = this->name_.substr(this->name_.rfind('/') + 1);
  const std::string role = costmap_layers::costmap2dRole(class_name_);
  const costmap_layers::CompatResult compat =
      costmap_layers::applyCostmap2dRulesAsRole(costmap_layers_ros::readNamespace(ros::NodeHandle(costmap_ns)), key,
                                                role, costmap_layers_ros::readParentNamespaces(costmap_ns));
  for (const auto& w : compat.warnings)
    ROS_WARN("%s: %s", costmap_ns.c_str(), w.c_str());
  for (const auto& n : compat.notes)
    ROS_INFO("%s: %s (this layer stands in for %s)", costmap_ns.c_str(), n.c_str(), role.c_str());
  const auto consumed = compat.layer_consumed.find(key);
  if (consumed != compat.layer_consumed.end()) consumed_keys_ = consumed->second;
  const costmap_layers::ParamValue* layer = compat.params.find(key);
  return layer != nullptr && layer->isMap() ? *layer : costmap_layers::ParamValue::makeMap();
}

template <class Base>
void LayerBridgeOn<Base>::waitForMap(const costmap_layers::StaticLayer& layer, const ros::NodeHandle& nh)
{
  // As costmap_2d's StaticLayer: move_base does not come up before the map. Otherwise the global
  // planner, which does not ask whether the costmap is current, plans on a costmap without walls.
  if (!layer.enabled() || layer.mapAccepted()) return;
  const std::string topic = ros::NodeHandle().resolveName(layer.config().map_topic);
  ROS_INFO("%s: waiting for the map on %s (as costmap_2d's static layer, move_base starts once it has come)",
           nh.getNamespace().c_str(), topic.c_str());
  ros::WallRate rate(20.0);  // wall time: under /use_sim_time the map may come before /clock
  const ros::WallTime started = ros::WallTime::now();
  while (ros::ok() && !layer.mapAccepted())
  {
    ros::spinOnce();
    rate.sleep();
    // A latched map comes moments after start: warn once the start-up grace is over, then every 5 s.
    if ((ros::WallTime::now() - started).toNSec() >= static_cast<int64_t>(costmap_layers::kStartupGraceNs))
      ROS_WARN_THROTTLE(5.0, "%s: still waiting for the map on %s (is map_server running, and is map_topic right?)",
                        nh.getNamespace().c_str(), topic.c_str());
  }
}

template <class Base>
void LayerBridgeOn<Base>::viewMaster()
{
  costmap_2d::Costmap2D& master = *this->layered_costmap_->getCostmap();
  host_->viewMaster(master.getCharMap(), master.getSizeInCellsX(), master.getSizeInCellsY(), master.getResolution(),
                    master.getOriginX(), master.getOriginY());
}

template <class Base>
void LayerBridgeOn<Base>::expandToWholeMap(double* min_x, double* min_y, double* max_x, double* max_y) const
{
  const costmap_2d::Costmap2D& master = *this->layered_costmap_->getCostmap();
  // The whole map first: NaN bounds from an earlier plugin give way to it instead of cancelling the
  // redraw (std::min returns its first argument when a comparison with NaN fails).
  *min_x = std::min(master.getOriginX(), *min_x);
  *min_y = std::min(master.getOriginY(), *min_y);
  *max_x = std::max(master.getOriginX() + master.getSizeInCellsX() * master.getResolution(), *max_x);
  *max_y = std::max(master.getOriginY() + master.getSizeInCellsY() * master.getResolution(), *max_y);
}

template <class Base>
void LayerBridgeOn<Base>::updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y,
                                       double* max_x, double* max_y)
{
  const auto own = lockOwnGrid();
  viewMaster();  // a rolling master has moved its origin since the last cycle
  const bool on = core_->enabled();
  // The core layer's switch flipped since the last cycle (and its cells are to appear or go).
  const bool switched = core_->takeEnabledFlip() && core_->writesCosts();
  if (on) core_->updateBounds(robot_x, robot_y, robot_yaw, min_x, min_y, max_x, max_y);
  if (full_update_.exchange(false) || host_->takeFullUpdateRequest() || switched)
    expandToWholeMap(min_x, min_y, max_x, max_y);
  this->current_ = !on || core_->isCurrent();
}

template <class Base>
void LayerBridgeOn<Base>::updateCosts(costmap_2d::Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j)
{
  const auto own = lockOwnGrid();
  if (!core_->enabled()) return;
  if (&master_grid != this->layered_costmap_->getCostmap())
  {
    // Not the grid this plugin belongs to (costmap_2d always passes its own): refuse rather than write
    // into memory the view does not describe.
    ROS_ERROR_THROTTLE(5.0, "%s: updateCosts on a grid that is not the costmap's own master, skipped",
                       this->name_.c_str());
    return;
  }
  viewMaster();  // the master may have been resized since updateBounds
  core_->updateCosts(host_->getCostmap(), min_i, min_j, max_i, max_j);
  checkPluginOrder();
}

template <class Base>
void LayerBridgeOn<Base>::checkPluginOrder()
{
  const auto* filter = dynamic_cast<const costmap_layers::CostmapFilter*>(core_.get());
  if (filter == nullptr || !filter->writesCosts()) return;
  std::string problem;
  bool after = false;
  const costmap_layers::Costmap2D& master = host_->getCostmap();
  const int sx = static_cast<int>(master.getSizeInCellsX()), sy = static_cast<int>(master.getSizeInCellsY());
  for (const auto& plugin : *this->layered_costmap_->getPlugins())
  {
    if (plugin.get() == this)
    {
      after = true;
      continue;
    }
    if (!after || !plugin->isEnabled()) continue;
    const costmap_layers::Layer* other = nullptr;
    if (const auto* b = dynamic_cast<const LayerBridgeOn<costmap_2d::Layer>*>(plugin.get()))
      other = &b->core();
    else if (const auto* c = dynamic_cast<const LayerBridgeOn<costmap_2d::CostmapLayer>*>(plugin.get()))
      other = &c->core();
    if (other != nullptr && other->enabled() && other->overwritesWindow(master, 0, 0, sx, sy))
      problem =
          plugin->getName() + " (a static layer) comes after it in the plugin list and overwrites the cells it draws";
    else if (std::find(costmap2d_static_layers_.begin(), costmap2d_static_layers_.end(), plugin->getName()) !=
             costmap2d_static_layers_.end())
      problem = plugin->getName() +
                " (costmap_2d's static layer, use_maximum false) comes after it in the plugin list and overwrites "
                "the cells it draws";
    if (!problem.empty()) break;
  }
  if (problem != order_problem_ && !problem.empty())
    context_->report(costmap_layers::Severity::Warn, "plugin_order",
                     this->name_ + ": " + problem +
                         ": list the filter after it (before the inflation layer to inflate "
                         "its zones, or last to keep them sharp)");
  order_problem_ = problem;
}

template <class Base>
void LayerBridgeOn<Base>::readCostmap2dStaticLayers(const ros::NodeHandle& nh)
{
  // Costmap2DROS loads its plugins from <costmap ns>/plugins, a list of {name, type} (it writes one
  // there for pre-Hydro parameters too), and names each plugin <costmap>/<name>; costmap_2d's
  // StaticLayer reads use_maximum once, at its start-up, from its own namespace. So the list and that
  // key say, for the rest of the run, which later plugins overwrite what a filter draws.
  costmap2d_static_layers_.clear();
  const std::string costmap_ns = ros::names::parentNamespace(nh.getNamespace());
  const std::string prefix = this->name_.substr(0, this->name_.rfind('/') + 1);  // "" for a name without '/'
  XmlRpc::XmlRpcValue list;
  if (!ros::param::get(costmap_ns + "/plugins", list) || list.getType() != XmlRpc::XmlRpcValue::TypeArray) return;
  for (int i = 0; i < list.size(); ++i)
  {
    XmlRpc::XmlRpcValue& entry = list[i];
    // A malformed entry is Costmap2DROS's to refuse; it names nothing here.
    if (entry.getType() != XmlRpc::XmlRpcValue::TypeStruct || !entry.hasMember("name") || !entry.hasMember("type") ||
        entry["name"].getType() != XmlRpc::XmlRpcValue::TypeString ||
        entry["type"].getType() != XmlRpc::XmlRpcValue::TypeString)
      continue;
    const std::string name = static_cast<std::string>(entry["name"]);
    if (static_cast<std::string>(entry["type"]) != "costmap_2d::StaticLayer") continue;
    bool use_maximum = false;
    ros::param::param(costmap_ns + "/" + name + "/use_maximum", use_maximum, false);
    if (!use_maximum) costmap2d_static_layers_.push_back(prefix + name);
  }
}

template <class Base>
void LayerBridgeOn<Base>::matchSize()
{
  if (!host_) return;
  const auto own = lockOwnGrid();
  viewMaster();  // the core layers' matchSize runs when the geometry changed
  // costmap_2d has reset its master (Costmap2D::resizeMap), also for the same geometry (every
  // dynamic_reconfigure of a costmap whose size is not locked): what the layer drew is gone.
  full_update_ = true;
}

template <class Base>
void LayerBridgeOn<Base>::onFootprintChanged()
{
  if (!host_) return;
  // costmap_2d calls this from its footprint subscriber with no lock, while the map update thread may
  // be inside the core layers (the inflation layer's cost table, the footprint the obstacle layer
  // clears): the costmap's mutex (recursive; updateMap holds it) keeps them apart.
  boost::unique_lock<costmap_2d::Costmap2D::mutex_t> lock(*this->layered_costmap_->getCostmap()->getMutex());
  const auto own = lockOwnGrid();
  costmap_layers::Footprint footprint;
  for (const auto& p : this->layered_costmap_->getFootprint())
    footprint.emplace_back(p.x, p.y);
  // costmap_2d passes on whatever its footprint topic or parameters carried (float32, NaN included):
  // a polygon the core could not use keeps the last good one (NaN vertices would make every inflated
  // cell inscribed, and a keepout filter's escape mode switch on anywhere).
  // (Empty before costmap_2d has set its own: it loads the plugins first, initialize() asks here. The
  // host's footprint is empty until one has passed below.)
  if (footprint.empty() && host_->getFootprint().empty()) return;
  const std::string problem = costmap_layers::footprintProblem(footprint);
  if (!problem.empty())
  {
    context_->report(costmap_layers::Severity::Error, "footprint",
                     this->name_ + ": footprint from move_base's costmap ignored, the last good one stays: " + problem);
    return;
  }
  host_->setFootprint(footprint);
}

template <class Base>
void LayerBridgeOn<Base>::reset()
{
  const auto own = lockOwnGrid();
  core_->reset();
  full_update_ = true;
}

template <class Base>
void LayerBridgeOn<Base>::activate()
{
  const auto own = lockOwnGrid();
  core_->activate();
  full_update_ = true;
}

template <class Base>
void LayerBridgeOn<Base>::deactivate()
{
  const auto own = lockOwnGrid();
  core_->deactivate();
}

template <class Base>
boost::unique_lock<costmap_2d::Costmap2D::mutex_t> LayerBridgeOn<Base>::lockOwnGrid()
{
  if constexpr (std::is_base_of_v<costmap_2d::Costmap2D, Base>)
    return boost::unique_lock<costmap_2d::Costmap2D::mutex_t>(*this->getMutex());
  else
    return {};
}
template class LayerBridgeOn<costmap_2d::Layer>;
template class LayerBridgeOn<costmap_2d::CostmapLayer>;

ClearableLayerBridge::~ClearableLayerBridge()
{
  costmap_ = nullptr;  // the core layer's cells: ~Costmap2D's delete[] must not free them
}

void ClearableLayerBridge::onInitialize()
{
  LayerBridgeOn<costmap_2d::CostmapLayer>::onInitialize();
  viewCoreGrid();
}

void ClearableLayerBridge::viewCoreGrid()
{
  auto* grid_layer = dynamic_cast<costmap_layers::CostmapLayer*>(&core());
  if (grid_layer == nullptr) return;
  costmap_layers::Costmap2D& grid = grid_layer->costmap();
  costmap_ = grid.data();
  size_x_ = grid.getSizeInCellsX();
  size_y_ = grid.getSizeInCellsY();
  resolution_ = grid.getResolution();
  origin_x_ = grid.getOriginX();
  origin_y_ = grid.getOriginY();
  default_value_ = grid.getDefaultValue();
}

void ClearableLayerBridge::deleteMaps()
{
  costmap_ = nullptr;  // not ours to free (see viewCoreGrid)
}

void ClearableLayerBridge::initMaps(unsigned int, unsigned int)
{
  viewCoreGrid();  // a resizeMap on this layer views the core grid again instead of allocating
}

void ClearableLayerBridge::resetMaps()
{
  boost::unique_lock<costmap_2d::Costmap2D::mutex_t> lock(*getMutex());
  costmap_layers::resetLayerCells(core());
}

void ClearableLayerBridge::updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y,
                                        double* max_x, double* max_y)
{
  boost::unique_lock<costmap_2d::Costmap2D::mutex_t> lock(*getMutex());  // see clearArea
  LayerBridgeOn<costmap_2d::CostmapLayer>::updateBounds(robot_x, robot_y, robot_yaw, min_x, min_y, max_x, max_y);
  viewCoreGrid();                              // a rolling layer's grid has followed the master
  useExtraBounds(min_x, min_y, max_x, max_y);  // what clear_costmap_recovery asked for (the whole layer)
}

void ClearableLayerBridge::matchSize()
{
  boost::unique_lock<costmap_2d::Costmap2D::mutex_t> lock(*getMutex());  // see clearArea
  LayerBridgeOn<costmap_2d::CostmapLayer>::matchSize();
  viewCoreGrid();
}

void ClearableLayerBridge::clearArea(int start_x, int start_y, int end_x, int end_y, bool invert_area)
{
  // clear_costmap_recovery holds this layer's own mutex (recursive) while it reads the grid's geometry,
  // clears and adds extra bounds; it never holds the costmap's. So the bridge does everything it does
  // to the core layer, the grid's view and the extra bounds under the own mutex too (lockOwnGrid), and
  // takes it after the costmap's wherever it needs both (updateMap holds the costmap's mutex): taking
  // the costmap's mutex here, inside the own one, would be the reverse order (a deadlock waiting for
  // the update thread).
  boost::unique_lock<costmap_2d::Costmap2D::mutex_t> lock(*getMutex());
  costmap_layers::clearLayerArea(core(), start_x, start_y, end_x, end_y, invert_area);
}
}  // namespace move_base
}  // namespace costmap_layers
