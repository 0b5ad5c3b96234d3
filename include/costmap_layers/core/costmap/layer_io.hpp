// What a layer takes from and gives to the world, as data. A layer declares its input ports (a kind,
// a topic, a typed handler) and output ports (a kind and a topic) while it initialises; the host (the
// ROS node, costmap_tool, a test) owns every subscription and publication: it subscribes to each
// input port and hands the typed message to the handler, and publishes the events the layer emits.
// The core never subscribes, advertises or publishes anything itself.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "costmap_layers/core/data/grid_data.hpp"
#include "costmap_layers/core/config/param_value.hpp"
#include "costmap_layers/core/data/path_data.hpp"
#include "costmap_layers/core/data/sensor_data.hpp"
#include "costmap_layers/core/data/voxel_grid_data.hpp"

namespace costmap_layers
{
/// What an input carries, so that a host knows the message type (and an offline host which file).
enum class InputKind
{
  Map,          ///< nav_msgs/OccupancyGrid: a map
  Mask,         ///< nav_msgs/OccupancyGrid: a filter mask
  MapUpdates,   ///< map_msgs/OccupancyGridUpdate
  SpeedLimits,  ///< costmap_layers/SpeedLimits
  LaserScan,    ///< sensor_msgs/LaserScan, delivered with the sensor pose
  PointCloud2,  ///< sensor_msgs/PointCloud2, delivered with the sensor pose
  PointCloud,   ///< sensor_msgs/PointCloud (the older type costmap_2d reads too), delivered as a
                ///< PointCloud2Data of its x, y, z (on_cloud) with the sensor pose
  Range,        ///< sensor_msgs/Range, delivered with the sensor pose
  FilterInfo,   ///< costmap_layers/CostmapFilterInfo (Nav2's CostmapFilterInfo fields)
  Path,         ///< nav_msgs/Path: a planned path (positions only)
  Odometry      ///< nav_msgs/Odometry: the robot's velocity
};

/// A short name of what an input carries ("map", "laser scans", ...), for messages.
const char* inputKindName(InputKind kind);

using GridCallback = std::function<void(const std::shared_ptr<const OccupancyGridData>&)>;
using GridUpdateCallback = std::function<void(const std::shared_ptr<const OccupancyGridUpdateData>&)>;
using SpeedLimitsCallback = std::function<void(const std::shared_ptr<const SpeedLimitsData>&)>;
using FilterInfoCallback = std::function<void(const std::shared_ptr<const FilterInfoData>&)>;
using PathCallback = std::function<void(const std::shared_ptr<const PathData>&)>;
using OdometryCallback = std::function<void(const std::shared_ptr<const OdometryData>&)>;
template <class Reading>
using SensorCallback = std::function<void(const std::shared_ptr<const Reading>&, const SensorPose&)>;

/// One input of a layer. Exactly the handler of its kind is set. Handlers may be called from any
/// thread; sensor handlers only once the host has the transform from the reading's frame into the
/// global frame at the reading's stamp (it waits a bounded time for tf, then drops the reading with a
/// throttled warning naming the frames).
///
/// An empty topic means "not connected yet": the host subscribes to nothing for that port until the
/// layer replaces the port (Layer::replaceInput(), e.g. a filter once its filter info named the mask
/// topic); from then on the host subscribes the replacement's topic and calls its handler instead.
struct InputPort
{
  InputKind kind = InputKind::Map;
  std::string topic;
  /// Sensors: when not empty, the frame whose origin is the sensor origin (else the reading's frame).
  std::string sensor_frame;
  GridCallback on_grid;           ///< Map, Mask
  GridUpdateCallback on_update;   ///< MapUpdates
  SpeedLimitsCallback on_limits;  ///< SpeedLimits
  FilterInfoCallback on_info;     ///< FilterInfo
  PathCallback on_path;           ///< Path
  OdometryCallback on_odom;       ///< Odometry
  SensorCallback<LaserScanData> on_scan;
  SensorCallback<PointCloud2Data> on_cloud;  ///< PointCloud2 and PointCloud
  SensorCallback<RangeData> on_range;

  static InputPort grid(InputKind kind, std::string topic, GridCallback cb);
  static InputPort mapUpdates(std::string topic, GridUpdateCallback cb);
  static InputPort speedLimits(std::string topic, SpeedLimitsCallback cb);
  static InputPort filterInfo(std::string topic, FilterInfoCallback cb);
  static InputPort path(std::string topic, PathCallback cb);
  static InputPort odometry(std::string topic, OdometryCallback cb);
  static InputPort laserScan(std::string topic, std::string sensor_frame, SensorCallback<LaserScanData> cb);
  static InputPort pointCloud2(std::string topic, std::string sensor_frame, SensorCallback<PointCloud2Data> cb);
  /// sensor_msgs/PointCloud, handed to cb as a PointCloud2Data (fields x, y, z, FLOAT32).
  static InputPort pointCloud(std::string topic, std::string sensor_frame, SensorCallback<PointCloud2Data> cb);
  static InputPort range(std::string topic, SensorCallback<RangeData> cb);
};

/// Where a host hears that a layer replaced one of its input ports: index into Layer::inputs(), and
/// the port now in force (its topic and handler replace the declared ones).
using InputListener = std::function<void(std::size_t index, const InputPort& port)>;

/// What an output carries.
enum class OutputKind
{
  MaxSpeed,    ///< costmap_layers/MaxSpeed, latched: the speed limit in force [m/s] (0 = none)
  SpeedLimit,  ///< costmap_layers/Nav2SpeedLimit (Nav2's SpeedLimit fields): percentage + speed_limit
  ZoneState,   ///< std_msgs/UInt8, latched: the id of the zone state in force (Nav2's state event)
  Setpoints,   ///< parameters of other nodes to set through their dynamic_reconfigure servers (no topic)
  BinaryState,   ///< std_msgs/Bool, latched: a BinaryFilter's state (OutputEvent::state)
  VoxelGrid,     ///< costmap_layers/VoxelMap: a VoxelLayer's voxels (OutputEvent::voxels), on demand
  VoxelMarkers,  ///< visualization_msgs/Marker: its marked voxels as a cube list, on demand
  VoxelCloud     ///< sensor_msgs/PointCloud2: the centres of its marked voxels, on demand
};

/// One parameter of another node, set through that node's dynamic_reconfigure server
/// (<node>/set_parameters). The value's type (Bool, Int, Double, String) says which list of the
/// request it goes in, as dynamic_reconfigure's own clients do.
struct Setpoint
{
  std::string node;       ///< e.g. "/move_base/DWAPlannerROS"
  std::string parameter;  ///< e.g. "max_vel_x"
  ParamValue value;
};

/// One output of a layer: the host advertises it when the layer is loaded.
struct OutputPort
{
  OutputKind kind = OutputKind::MaxSpeed;
  std::string topic;     ///< Setpoints: a name for the port (the host sets parameters, it publishes nothing)
  double timeout = 0.0;  ///< Setpoints: how long the host waits for each server [s]
  /// The topic resolves in the layer's own namespace (~<name>/topic), as costmap_2d's voxel_grid does.
  bool layer_namespace = false;
  /// Costly to build: the host tells the layer whether anyone reads it (Layer::setOutputWanted()), and
  /// the layer emits it only while someone does. Not latched.
  bool on_demand = false;
};

/// An event on an output port, emitted by the layer (on the update thread) for the host to publish.
struct OutputEvent
{
  OutputKind kind = OutputKind::MaxSpeed;
  std::string topic;
  double value = 0.0;  ///< MaxSpeed: [m/s]; SpeedLimit: [%] or [m/s] as `percentage` says (0 = none); ZoneState: the id
  bool percentage = false;  ///< SpeedLimit only
  /// Setpoints only: every parameter that must hold its value from now on (a complete set, so that a
  /// later event replaces an earlier one that was not applied yet), and what the set is for (a state
  /// name, for messages).
  std::vector<Setpoint> setpoints;
  std::string label;
  bool state = false;  ///< BinaryState only
  std::shared_ptr<const VoxelGridData> voxels;  ///< VoxelGrid, VoxelMarkers, VoxelCloud (one snapshot shared)
};
using OutputListener = std::function<void(const OutputEvent&)>;
}  // namespace costmap_layers
