// A LayerContext for core tests: parameters from a ParamValue, reports recorded, transforms from a
// table; and, once bound to a layer (bind()), the host's part: inputs pushed by the test to the
// layer's ports, output events recorded. No ROS.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "costmap_layers/core/filters/costmap_filter.hpp"
#include "costmap_layers/core/costmap/layer.hpp"
#include "costmap_layers/core/costmap/layer_context.hpp"

namespace costmap_layers_test
{
using namespace costmap_layers;

/// What a grid input is for, as tests name it.
enum class GridKind
{
  Map,
  Mask
};

class FakeContext : public LayerContext
{
public:
  explicit FakeContext(ParamValue params = ParamValue::makeMap(), std::string global_frame = "map")
      : params_(std::move(params)), global_frame_(std::move(global_frame))
  {
  }

  const ParamValue& params() const override { return params_; }
  const std::string& globalFrame() const override { return global_frame_; }
  double transformTolerance() const override { return 0.3; }

  /// Plays the host's part for a layer that has initialised: takes its input ports (so that the test
  /// can publish to them), its output events and, for a filter, its switch (the ~toggle service).
  void bind(Layer& layer)
  {
    for (std::size_t index = 0; index < layer.inputs().size(); ++index)
    {
      const InputPort& in = layer.inputs()[index];
      switch (in.kind)
      {
        case InputKind::Map:
        case InputKind::Mask:
          grid_subs.push_back(
              {in.topic, in.kind == InputKind::Map ? GridKind::Map : GridKind::Mask, in.on_grid, index});
          break;
        case InputKind::FilterInfo:
          info_subs.push_back({in.topic, in.on_info});
          break;
        case InputKind::MapUpdates:
          update_subs.push_back({in.topic, in.on_update});
          break;
        case InputKind::SpeedLimits:
          speed_subs.push_back({in.topic, in.on_limits});
          break;
        case InputKind::LaserScan:
          scan_subs.push_back({in.topic, in.sensor_frame, in.on_scan});
          break;
        case InputKind::PointCloud2:
        case InputKind::PointCloud:
          cloud_subs.push_back({in.topic, in.sensor_frame, in.on_cloud});
          break;
        case InputKind::Range:
          range_subs.push_back({in.topic, "", in.on_range});
          break;
        case InputKind::Path:
          path_subs.push_back({in.topic, in.on_path});
          break;
        case InputKind::Odometry:
          odom_subs.push_back({in.topic, in.on_odom});
          break;
      }
    }
    // A replaced port (a filter info naming the mask topic): the test's "subscription" follows it.
    layer.setInputListener(
        [this](std::size_t index, const InputPort& port)
        {
          std::lock_guard<std::mutex> lock(subs_mutex);
          for (auto& s : grid_subs)
            if (s.port == index)
            {
              s.topic = port.topic;
              s.cb = port.on_grid;
            }
          ++replaced_inputs;
        });
    for (const OutputPort& out : layer.outputs())
      if (out.kind == OutputKind::MaxSpeed)
        max_speed_topic = out.topic;
      else if (out.kind == OutputKind::SpeedLimit)
        speed_limit_topic = out.topic;
      else
        binary_state_topic = out.topic;
    if (!layer.outputs().empty())
      layer.setOutputListener(
          [this](const OutputEvent& e)
          {
            if (e.kind == OutputKind::MaxSpeed)
              published_speeds.push_back(e.value);
            else if (e.kind == OutputKind::SpeedLimit)
              published_limits.push_back({e.percentage, e.value});
            else
              published_states.push_back(e.state);
          });
    if (auto* filter = dynamic_cast<CostmapFilter*>(&layer)) toggle = [filter](bool on) { filter->setEnabled(on); };
  }
  /// Delivers a reading to every subscription of its topic (as the node would once tf had the pose).
  template <class Reading, class Subs>
  static int deliver(Subs& subs, const std::string& topic, const Reading& reading, const SensorPose& pose)
  {
    auto shared = std::make_shared<const Reading>(reading);
    int n = 0;
    for (auto& s : subs)
      if (s.topic == topic) s.cb(shared, pose), ++n;
    return n;
  }
  int publishScan(const std::string& topic, const LaserScanData& scan, const SensorPose& pose = {})
  {
    return deliver(scan_subs, topic, scan, pose);
  }
  int publishCloud(const std::string& topic, const PointCloud2Data& cloud, const SensorPose& pose = {})
  {
    return deliver(cloud_subs, topic, cloud, pose);
  }
  int publishRange(const std::string& topic, const RangeData& range, const SensorPose& pose = {})
  {
    return deliver(range_subs, topic, range, pose);
  }

  std::optional<Transform2D> lookupTransform(const std::string& target, const std::string& source,
                                             std::string* error) override
  {
    if (target == source) return Transform2D{};
    auto it = transforms.find({target, source});
    if (it != transforms.end()) return it->second;
    if (error) *error = "no transform " + source + " -> " + target;
    return std::nullopt;
  }
  uint64_t nowNs() const override { return now_ns; }
  void report(Severity severity, const std::string& key, const std::string& message) override
  {
    std::lock_guard<std::mutex> lock(reports_mutex);  // layers report from the hosts' threads too
    reports.push_back({severity, key, message});
  }

  /// Delivers a grid to every subscription of that kind (as the node would on the topic).
  void publishGrid(GridKind kind, const OccupancyGridData& grid)
  {
    auto shared = std::make_shared<const OccupancyGridData>(grid);
    for (auto& s : grid_subs)
      if (s.kind == kind) s.cb(shared);
  }
  /// Delivers a map update to every map update input.
  void publishGridUpdate(const OccupancyGridUpdateData& update)
  {
    auto shared = std::make_shared<const OccupancyGridUpdateData>(update);
    for (auto& s : update_subs)
      s.cb(shared);
  }
  /// Delivers a grid to the grid subscriptions of that topic only (the mask a filter info names).
  /// Safe against a concurrent port replacement (as the node's subscriptions are).
  int publishGridOn(const std::string& topic, const OccupancyGridData& grid)
  {
    auto shared = std::make_shared<const OccupancyGridData>(grid);
    std::lock_guard<std::mutex> lock(subs_mutex);
    int n = 0;
    for (auto& s : grid_subs)
      if (s.topic == topic && !topic.empty()) s.cb(shared), ++n;
    return n;
  }
  void publishFilterInfo(const FilterInfoData& info)
  {
    auto shared = std::make_shared<const FilterInfoData>(info);
    for (auto& s : info_subs)
      s.cb(shared);
  }
  /// Number of reports with this key.
  int countKey(const std::string& key) const
  {
    int n = 0;
    for (const auto& r : reports)
      if (r.key == key) ++n;
    return n;
  }
  /// Delivers a path / odometry to every such input.
  int publishPath(const PathData& path)
  {
    auto shared = std::make_shared<const PathData>(path);
    for (auto& s : path_subs)
      s.cb(shared);
    return static_cast<int>(path_subs.size());
  }
  int publishOdometry(const OdometryData& odom)
  {
    auto shared = std::make_shared<const OdometryData>(odom);
    for (auto& s : odom_subs)
      s.cb(shared);
    return static_cast<int>(odom_subs.size());
  }
  void publishSpeedLimits(const SpeedLimitsData& limits)
  {
    auto shared = std::make_shared<const SpeedLimitsData>(limits);
    for (auto& s : speed_subs)
      s.cb(shared);
  }
  /// Number of reports whose text contains needle.
  int countReports(const std::string& needle) const
  {
    int n = 0;
    for (const auto& r : reports)
      if (r.message.find(needle) != std::string::npos) ++n;
    return n;
  }

  struct GridSub
  {
    std::string topic;
    GridKind kind;
    GridCallback cb;
    std::size_t port = 0;  ///< index of the layer's input
  };
  struct InfoSub
  {
    std::string topic;
    FilterInfoCallback cb;
  };
  struct SpeedSub
  {
    std::string topic;
    SpeedLimitsCallback cb;
  };
  template <class Callback>
  struct TopicSub
  {
    std::string topic;
    Callback cb;
  };
  std::vector<TopicSub<PathCallback>> path_subs;
  std::vector<TopicSub<OdometryCallback>> odom_subs;
  struct UpdateSub
  {
    std::string topic;
    GridUpdateCallback cb;
  };
  template <class Reading>
  struct SensorSub
  {
    std::string topic;
    std::string sensor_frame;
    SensorCallback<Reading> cb;
  };
  std::vector<SensorSub<LaserScanData>> scan_subs;
  std::vector<SensorSub<PointCloud2Data>> cloud_subs;
  std::vector<SensorSub<RangeData>> range_subs;

  struct Report
  {
    Severity severity;
    std::string key;
    std::string message;
  };

  ParamValue params_;
  std::string global_frame_;
  std::mutex reports_mutex;
  std::mutex subs_mutex;  ///< guards grid_subs' topics and handlers against replacements
  std::vector<GridSub> grid_subs;
  std::vector<InfoSub> info_subs;
  int replaced_inputs = 0;
  std::vector<SpeedSub> speed_subs;
  std::vector<UpdateSub> update_subs;
  std::string max_speed_topic;
  std::vector<double> published_speeds;
  std::string speed_limit_topic;
  std::vector<std::pair<bool, double>> published_limits;  ///< (percentage, speed_limit)
  std::string binary_state_topic;
  std::vector<bool> published_states;
  std::function<void(bool)> toggle;
  std::map<std::pair<std::string, std::string>, Transform2D> transforms;  ///< (target, source) -> T
  uint64_t now_ns = 0;
  std::vector<Report> reports;
};
}  // namespace costmap_layers_test
