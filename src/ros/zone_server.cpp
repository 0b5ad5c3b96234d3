#include "costmap_layers/ros/zone_server.hpp"

#include <visualization_msgs/InteractiveMarker.h>
#include <visualization_msgs/InteractiveMarkerControl.h>
#include <visualization_msgs/Marker.h>

#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>

#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/io/zone_file.hpp"
#include "costmap_layers/ros/node_params.hpp"

namespace costmap_layers_ros
{
using costmap_layers::InputError;
using costmap_layers::ZoneLayout;
using costmap_layers::ZonePoint;
using costmap_layers::ZoneShapeType;

namespace
{
/// The zone file named at start-up; an error names the parameter that named it.
costmap_layers::ZoneLayout loadStartFile(const ZoneServer::Options& o)
{
  try
  {
    return costmap_layers::io::loadZoneFile(o.yaml_filename);
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error("parameter " + o.file_parameter + ": " + e.what());
  }
}

constexpr double kHandleSize = 0.25;  ///< [m] diameter of a handle's sphere in RViz
constexpr int kCircleSegments = 72;   ///< of a circle's drawn outline

geometry_msgs::Point toPoint(const ZonePoint& p)
{
  geometry_msgs::Point q;
  q.x = p.x;
  q.y = p.y;
  return q;
}

std::string handleName(const costmap_layers::ZoneShape& s, std::size_t k)
{
  if (s.type == ZoneShapeType::Circle) return s.name + (k == 0 ? "/center" : "/radius");
  return s.name + "/" + std::to_string(k);
}

/// A handle: a sphere that moves in the ground plane.
visualization_msgs::InteractiveMarker handleMarker(const std::string& frame, const std::string& name,
                                                   const ZonePoint& at)
{
  visualization_msgs::InteractiveMarker im;
  im.header.frame_id = frame;
  im.name = name;
  im.description = name;
  im.scale = static_cast<float>(2.0 * kHandleSize);
  im.pose.position = toPoint(at);
  im.pose.orientation.w = 1.0;
  visualization_msgs::InteractiveMarkerControl control;
  // MOVE_PLANE moves in the plane normal to the control's x axis: turn x onto z (90 degrees about y).
  control.orientation.w = std::sqrt(0.5);
  control.orientation.y = std::sqrt(0.5);
  control.interaction_mode = visualization_msgs::InteractiveMarkerControl::MOVE_PLANE;
  control.always_visible = true;
  visualization_msgs::Marker sphere;
  sphere.type = visualization_msgs::Marker::SPHERE;
  sphere.scale.x = sphere.scale.y = sphere.scale.z = kHandleSize;
  sphere.color.r = 1.0f;
  sphere.color.g = 0.55f;
  sphere.color.a = 0.9f;
  control.markers.push_back(sphere);
  im.controls.push_back(control);
  return im;
}

/// A shape's outline, drawn only, named "<shape>/outline": a handle's name ends in a number, "center" or
/// "radius", so no two markers share a name whatever the shape names hold ('/' included).
visualization_msgs::InteractiveMarker outlineMarker(const std::string& frame, const costmap_layers::ZoneShape& s)
{
  visualization_msgs::InteractiveMarker im;
  im.header.frame_id = frame;
  im.name = s.name + "/outline";
  im.description = s.name + " (" + std::to_string(s.value) + ")";
  im.pose.orientation.w = 1.0;
  visualization_msgs::InteractiveMarkerControl control;
  control.interaction_mode = visualization_msgs::InteractiveMarkerControl::NONE;
  control.always_visible = true;
  control.orientation.w = 1.0;
  visualization_msgs::Marker line;
  line.type = visualization_msgs::Marker::LINE_STRIP;
  line.scale.x = 0.05;
  line.color.r = s.value >= 100 ? 0.9f : 0.2f;
  line.color.g = 0.3f;
  line.color.b = s.value >= 100 ? 0.2f : 0.9f;
  line.color.a = 1.0f;
  line.pose.orientation.w = 1.0;
  if (s.type == ZoneShapeType::Circle)
    for (int k = 0; k <= kCircleSegments; ++k)
    {
      const double a = 2.0 * M_PI * k / kCircleSegments;
      line.points.push_back(toPoint({s.center.x + s.radius * std::cos(a), s.center.y + s.radius * std::sin(a)}));
    }
  else
  {
    for (const auto& p : s.points)
      line.points.push_back(toPoint(p));
    line.points.push_back(toPoint(s.points.front()));
  }
  control.markers.push_back(line);
  im.controls.push_back(control);
  return im;
}
}  // namespace

nav_msgs::OccupancyGrid toMaskMsg(const costmap_layers::OccupancyGridData& grid, const ros::Time& stamp)
{
  nav_msgs::OccupancyGrid msg;
  msg.header.frame_id = grid.frame_id;
  msg.header.stamp = stamp;
  msg.info.map_load_time = stamp;
  // The core keeps resolution in [kMinResolution, kMaxResolution]: normal float32 numbers.
  msg.info.resolution = static_cast<float>(grid.resolution);
  msg.info.width = grid.width;
  msg.info.height = grid.height;
  msg.info.origin.position.x = grid.origin_x;
  msg.info.origin.position.y = grid.origin_y;
  msg.info.origin.orientation.w = 1.0;
  msg.data.assign(grid.data.begin(), grid.data.end());
  return msg;
}

ZoneServer::Options ZoneServer::readOptions(const ros::NodeHandle& pnh)
{
  const NodeParams params(pnh);
  const std::string node = ros::this_node::getName();
  for (const auto& key : params.unknownKeys({"yaml_filename", "topic", "markers", "save_directory", "publish_rate"}))
    ROS_WARN(
        "%s: parameter %s%s is not one of yaml_filename, topic, markers, save_directory, publish_rate: ignored "
        "[%s/unknown]",
        node.c_str(), params.where().c_str(), key.c_str(), node.c_str());
  Options o;
  o.yaml_filename = params.getFile("yaml_filename");
  o.file_parameter = params.where() + "yaml_filename";
  o.topic = params.getTopic("topic", o.topic);
  o.markers = params.getBool("markers", o.markers);
  o.save_directory = params.getString("save_directory", o.save_directory);
  for (std::size_t k = 0; k < o.save_directory.size(); ++k)
    if (static_cast<unsigned char>(o.save_directory[k]) < ' ' || o.save_directory[k] == 127)
      throw std::invalid_argument("parameter " + params.where() + "save_directory has character code " +
                                  std::to_string(static_cast<unsigned char>(o.save_directory[k])) + " at position " +
                                  std::to_string(k) + ": a folder name holds no control characters");
  o.publish_rate = params.getDoubleIn("publish_rate", o.publish_rate, costmap_layers::limits::kMinFrequency,
                                      costmap_layers::limits::kMaxFrequency);
  return o;
}

ZoneServer::ZoneServer(ros::NodeHandle nh, ros::NodeHandle pnh, Options options)
    : nh_(std::move(nh)),
      pnh_(std::move(pnh)),
      options_(std::move(options)),
      node_(ros::this_node::getName()),
      log_(std::make_shared<ThrottledLog>()),
      info_log_(1.0),
      editor_(costmap_layers::ZoneSet(loadStartFile(options_)), options_.yaml_filename, options_.save_directory)
{
  // Not fatal: the folder may be made later (it is resolved at each request), but say so now.
  struct stat st
  {
  };
  if (::stat(editor_.folder().directory().c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    ROS_WARN(
        "%s: the save directory '%s' (~save_directory) is not a folder now: save and load will refuse every "
        "named file until it is [%s/save_directory]",
        node_.c_str(), costmap_layers::shownText(editor_.folder().directory(), 200).c_str(), node_.c_str());
  mask_pub_ = nh_.advertise<nav_msgs::OccupancyGrid>(options_.topic, 1, true);
  if (options_.markers) markers_ = std::make_unique<interactive_markers::InteractiveMarkerServer>(node_);
  set_srv_ = pnh_.advertiseService("set_shape", &ZoneServer::onSet, this);
  remove_srv_ = pnh_.advertiseService("remove_shape", &ZoneServer::onRemove, this);
  save_srv_ = pnh_.advertiseService("save", &ZoneServer::onSave, this);
  load_srv_ = pnh_.advertiseService("load", &ZoneServer::onLoad, this);
  costmap_layers::ZoneLayout drawn;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    publish();
    drawn = editor_.zones().layout();
  }
  rebuildMarkers(drawn);
  publish_timer_ =
      nh_.createSteadyTimer(ros::WallDuration(1.0 / options_.publish_rate), &ZoneServer::onPublishTimer, this);
}

void ZoneServer::changed()
{
  dirty_ = true;
}

void ZoneServer::onPublishTimer(const ros::SteadyTimerEvent&)
{
  std::lock_guard<std::mutex> lock(mutex_);
  if (!dirty_) return;
  dirty_ = false;
  publish();
}

void ZoneServer::publish()
{
  const costmap_layers::ZoneSet& zones = editor_.zones();
  const costmap_layers::OccupancyGridData grid = zones.rasterize();
  mask_pub_.publish(toMaskMsg(grid, ros::Time::now()));
  std::size_t claimed = 0;
  for (const int8_t v : grid.data)
    claimed += v != zones.layout().default_value;
  char line[1024];
  std::snprintf(line, sizeof(line),
                "%s: publishing %zu shape(s) on %s: %ux%u cells at %g m/cell, origin (%g, %g), frame %s, %zu "
                "cell(s) not at default_value %d",
                node_.c_str(), zones.layout().shapes.size(), mask_pub_.getTopic().c_str(), grid.width, grid.height,
                grid.resolution, grid.origin_x, grid.origin_y, grid.frame_id.c_str(), claimed,
                zones.layout().default_value);
  info_log_.log(costmap_layers::Severity::Info, node_ + "/published", line);
}

void ZoneServer::rebuildMarkers(const ZoneLayout& l)
{
  if (!markers_) return;
  markers_->clear();
  std::size_t offered = 0, left_out = 0;
  for (const auto& s : l.shapes)
  {
    markers_->insert(outlineMarker(l.frame_id, s));
    const auto handles = costmap_layers::zoneHandles(s);
    // Whole shapes only, in file order, up to the limit: a shape has all its handles or none.
    if (offered + handles.size() > costmap_layers::limits::kMaxZoneHandles)
    {
      left_out += handles.size();
      continue;
    }
    offered += handles.size();
    for (std::size_t k = 0; k < handles.size(); ++k)
      markers_->insert(handleMarker(l.frame_id, handleName(s, k), handles[k]),
                       [this](const visualization_msgs::InteractiveMarkerFeedbackConstPtr& f) { onFeedback(f); });
  }
  markers_->applyChanges();
  if (left_out > 0)
    log_->log(costmap_layers::Severity::Warn, node_ + "/markers",
              node_ + ": " + std::to_string(left_out) +
                  " handle(s) of the later shapes are not offered in RViz: at most " +
                  std::to_string(costmap_layers::limits::kMaxZoneHandles) +
                  " handles, whole shapes in file order (edit those shapes through ~set_shape)");
}

bool ZoneServer::redraw(std::unique_lock<std::mutex>& lock)
{
  // The marker server calls onFeedback holding its own lock, and onFeedback takes mutex_: so mutex_ is
  // never held while calling into the marker server, or two callback threads could deadlock.
  const ZoneLayout drawn = editor_.zones().layout();
  lock.unlock();
  rebuildMarkers(drawn);
  return true;
}

void ZoneServer::refuse(const std::string& what, const InputError& error)
{
  log_->log(costmap_layers::Severity::Error, node_ + "/" + error.field,
            what + " refused, keeping the shapes in force: " + error.message);
}

void ZoneServer::onFeedback(const visualization_msgs::InteractiveMarkerFeedbackConstPtr& f)
{
  if (f->event_type != visualization_msgs::InteractiveMarkerFeedback::POSE_UPDATE) return;
  // Decided under mutex_, drawn after it is released (see redraw()): the handle put back, or this
  // shape's outline and its other handles (a circle's radius handle follows its centre); the dragged
  // handle itself is where the user holds it.
  ZoneDrag drag;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    drag = editor_.drag(f->marker_name, f->header.frame_id, f->pose.position.x, f->pose.position.y);
    if (!drag.applies) return;
    if (!drag.error.ok())
      refuse("moving " + f->marker_name + " to (" + std::to_string(f->pose.position.x) + ", " +
                 std::to_string(f->pose.position.y) + ")",
             drag.error);
    else
      changed();
  }
  const std::optional<ZonePoint>& put_back = drag.put_back;
  const std::optional<costmap_layers::ZoneShape>& moved = drag.moved;
  const std::string& frame = drag.frame;
  const std::size_t index = drag.index;
  if (!markers_) return;
  if (put_back)
  {
    geometry_msgs::Pose back;
    back.position = toPoint(*put_back);
    back.orientation.w = 1.0;
    markers_->setPose(f->marker_name, back);
    markers_->applyChanges();
    return;
  }
  if (!moved) return;
  markers_->insert(outlineMarker(frame, *moved));
  const auto handles = costmap_layers::zoneHandles(*moved);
  for (std::size_t k = 0; k < handles.size(); ++k)
    if (k != index)
    {
      geometry_msgs::Pose p;
      p.position = toPoint(handles[k]);
      p.orientation.w = 1.0;
      markers_->setPose(handleName(*moved, k), p);
    }
  markers_->applyChanges();
}

bool ZoneServer::onSet(costmap_layers::SetZoneShape::Request& req, costmap_layers::SetZoneShape::Response& res)
{
  std::unique_lock<std::mutex> lock(mutex_);
  const ZoneEdit edit = editor_.set(req.shape);
  res.success = edit.success;
  res.message = edit.message;
  if (!edit.success)
  {
    refuse("set_shape", edit.error);
    return true;
  }
  changed();
  return redraw(lock);
}

bool ZoneServer::onRemove(costmap_layers::RemoveZoneShape::Request& req, costmap_layers::RemoveZoneShape::Response& res)
{
  std::unique_lock<std::mutex> lock(mutex_);
  const ZoneEdit edit = editor_.remove(req.name);
  res.success = edit.success;
  res.message = edit.message;
  if (!edit.success)
  {
    refuse("remove_shape", edit.error);
    return true;
  }
  changed();
  return redraw(lock);
}

bool ZoneServer::onSave(costmap_layers::SaveZones::Request& req, costmap_layers::SaveZones::Response& res)
{
  std::lock_guard<std::mutex> lock(mutex_);
  const ZoneEdit edit = editor_.save(req.filename);
  res.success = edit.success;
  res.message = edit.message;
  if (!edit.success)
  {
    refuse("save", edit.error);
    return true;
  }
  ROS_INFO("%s: saved %zu shape(s) to %s [%s/saved]", node_.c_str(), editor_.zones().layout().shapes.size(),
           edit.message.c_str(), node_.c_str());
  return true;
}

bool ZoneServer::onLoad(costmap_layers::LoadZones::Request& req, costmap_layers::LoadZones::Response& res)
{
  std::unique_lock<std::mutex> lock(mutex_);
  const ZoneEdit edit = editor_.load(req.filename);
  res.success = edit.success;
  res.message = edit.message;
  if (!edit.success)
  {
    refuse("load", edit.error);
    return true;
  }
  changed();
  return redraw(lock);
}
}  // namespace costmap_layers_ros
