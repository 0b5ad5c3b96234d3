#include "costmap_layers/core/costmap/layer_io.hpp"

#include <utility>

namespace costmap_layers
{
InputPort InputPort::grid(InputKind kind, std::string topic, GridCallback cb)
{
  InputPort p;
  p.kind = kind;
  p.topic = std::move(topic);
  p.on_grid = std::move(cb);
  return p;
}

InputPort InputPort::mapUpdates(std::string topic, GridUpdateCallback cb)
{
  InputPort p;
  p.kind = InputKind::MapUpdates;
  p.topic = std::move(topic);
  p.on_update = std::move(cb);
  return p;
}

InputPort InputPort::speedLimits(std::string topic, SpeedLimitsCallback cb)
{
  InputPort p;
  p.kind = InputKind::SpeedLimits;
  p.topic = std::move(topic);
  p.on_limits = std::move(cb);
  return p;
}

InputPort InputPort::filterInfo(std::string topic, FilterInfoCallback cb)
{
  InputPort p;
  p.kind = InputKind::FilterInfo;
  p.topic = std::move(topic);
  p.on_info = std::move(cb);
  return p;
}

InputPort InputPort::path(std::string topic, PathCallback cb)
{
  InputPort p;
  p.kind = InputKind::Path;
  p.topic = std::move(topic);
  p.on_path = std::move(cb);
  return p;
}

InputPort InputPort::odometry(std::string topic, OdometryCallback cb)
{
  InputPort p;
  p.kind = InputKind::Odometry;
  p.topic = std::move(topic);
  p.on_odom = std::move(cb);
  return p;
}

InputPort InputPort::laserScan(std::string topic, std::string sensor_frame, SensorCallback<LaserScanData> cb)
{
  InputPort p;
  p.kind = InputKind::LaserScan;
  p.topic = std::move(topic);
  p.sensor_frame = std::move(sensor_frame);
  p.on_scan = std::move(cb);
  return p;
}

InputPort InputPort::pointCloud2(std::string topic, std::string sensor_frame, SensorCallback<PointCloud2Data> cb)
{
  InputPort p;
  p.kind = InputKind::PointCloud2;
  p.topic = std::move(topic);
  p.sensor_frame = std::move(sensor_frame);
  p.on_cloud = std::move(cb);
  return p;
}

InputPort InputPort::pointCloud(std::string topic, std::string sensor_frame, SensorCallback<PointCloud2Data> cb)
{
  InputPort p = pointCloud2(std::move(topic), std::move(sensor_frame), std::move(cb));
  p.kind = InputKind::PointCloud;
  return p;
}

InputPort InputPort::range(std::string topic, SensorCallback<RangeData> cb)
{
  InputPort p;
  p.kind = InputKind::Range;
  p.topic = std::move(topic);
  p.on_range = std::move(cb);
  return p;
}
}  // namespace costmap_layers
