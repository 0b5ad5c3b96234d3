#include "costmap_layers/ros/zone_server.hpp"

#include <std_msgs/ColorRGBA.h>
#include <visualization_msgs/InteractiveMarker.h>
#include <visualization_msgs/InteractiveMarkerControl.h>
#include <visualization_msgs/Marker.h>

#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <vector>

#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/core/zones/zone_set.hpp"
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
// Text in RViz: a handle's label as tall as the handle, a shape's name a little taller, both a small gap
// from what they name. Drawn above the masks (z = 0) and the spheres, so neither covers them.
constexpr double kLabelHeight = kHandleSize;  ///< [m]
constexpr double kNameHeight = 0.3;           ///< [m]
constexpr double kLabelGap = 0.05;            ///< [m] between a sphere and its label
constexpr double kLabelZ = kHandleSize;       ///< [m]
constexpr double kCharWidth = 0.6;            ///< RViz's text: a character's width over the text height
constexpr double kOutlineWidth = 0.05;        ///< [m] of a shape's drawn outline
constexpr double kOutlineZ = 0.05;            ///< [m] the outline's height above the masks

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

/// A text that faces the viewer, in the handles' orange, which reads on free (white), costly (blue to
/// red) and lethal (magenta) cells alike; at (x, y) relative to its interactive marker.
visualization_msgs::Marker textMarker(const std::string& text, double x, double y, double height)
{
  visualization_msgs::Marker m;
  m.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
  m.text = text;
  m.scale.z = height;
  m.pose.position.x = x;
  m.pose.position.y = y;
  m.pose.position.z = kLabelZ;
  m.pose.orientation.w = 1.0;
  m.color.r = 1.0f;
  m.color.g = 0.55f;
  m.color.a = 1.0f;
  return m;
}

/// +1 for a polygon listed counter-clockwise, -1 clockwise (the sign of its area, summed relative to its
/// first vertex so that far-away shapes keep their precision).
double winding(const std::vector<ZonePoint>& ring)
{
  double area2 = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i)
  {
    const ZonePoint& a = ring[i];
    const ZonePoint& b = ring[(i + 1) % ring.size()];
    area2 += (a.x - ring[0].x) * (b.y - ring[0].y) - (b.x - ring[0].x) * (a.y - ring[0].y);
  }
  return area2 < 0.0 ? -1.0 : 1.0;
}

/// Which way is out of a polygon of that winding at its vertex k: the sum of the outward normals of the
/// two edges that meet there (the outer bisector, at convex and reflex corners alike), a unit vector.
ZonePoint outwardAt(const std::vector<ZonePoint>& ring, std::size_t k, double sign)
{
  const std::size_t n = ring.size();
  const ZonePoint& v = ring[k];
  const ZonePoint& prev = ring[(k + n - 1) % n];
  const ZonePoint& next = ring[(k + 1) % n];
  const double l1 = std::hypot(v.x - prev.x, v.y - prev.y), l2 = std::hypot(next.x - v.x, next.y - v.y);
  if (!(l1 > 0.0) || !(l2 > 0.0)) return {0.0, 1.0};
  // Counter-clockwise, an edge's outward normal is its direction turned right: (dy, -dx).
  const double nx = sign * ((v.y - prev.y) / l1 + (next.y - v.y) / l2);
  const double ny = -sign * ((v.x - prev.x) / l1 + (next.x - v.x) / l2);
  const double length = std::hypot(nx, ny);
  if (!(length > 1e-9)) return {0.0, 1.0};
  return {nx / length, ny / length};
}

/// Where handle k's label goes, relative to the handle: a polygon vertex's outside the corner (so it
/// crosses neither edge), a circle's centre's above it, its radius handle's to the right (out of the
/// circle, whose rightmost point it is). Far enough that the label's box clears the sphere by kLabelGap.
ZonePoint labelOffset(const costmap_layers::ZoneShape& s, std::size_t k, double sign, const std::string& label)
{
  ZonePoint d{0.0, 1.0};
  if (s.type == ZoneShapeType::Circle)
    d = k == 0 ? ZonePoint{0.0, 1.0} : ZonePoint{1.0, 0.0};
  else
    d = outwardAt(s.points, k, sign);
  const double half_width = kCharWidth * kLabelHeight * static_cast<double>(label.size()) / 2;
  const double distance = kHandleSize / 2 + kLabelGap + std::abs(d.x) * half_width + std::abs(d.y) * kLabelHeight / 2;
  return {d.x * distance, d.y * distance};
}

/// A handle: a sphere that moves in the ground plane, and its label beside it (in a control of its own
/// that takes no mouse input, so only the sphere is dragged). The label is the handle's name without the
/// shape's: RViz would draw a description in white, too small and far above the handle.
visualization_msgs::InteractiveMarker handleMarker(const std::string& frame, const costmap_layers::ZoneShape& s,
                                                   std::size_t k, double sign, const ZonePoint& at)
{
  visualization_msgs::InteractiveMarker im;
  im.header.frame_id = frame;
  im.name = handleName(s, k);
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

  const std::string label = im.name.substr(s.name.size() + 1);
  visualization_msgs::InteractiveMarkerControl text;
  text.interaction_mode = visualization_msgs::InteractiveMarkerControl::NONE;
  text.always_visible = true;
  text.orientation.w = 1.0;
  const ZonePoint at_label = labelOffset(s, k, sign, label);
  text.markers.push_back(textMarker(label, at_label.x, at_label.y, kLabelHeight));
  im.controls.push_back(text);
  return im;
}

/// A shape's outline, drawn only, named "<shape>/outline": a handle's name ends in a number, "center" or
/// "radius", so no two markers share a name whatever the shape names hold ('/' included).
visualization_msgs::InteractiveMarker outlineMarker(const std::string& frame, const costmap_layers::ZoneShape& s)
{
  visualization_msgs::InteractiveMarker im;
  im.header.frame_id = frame;
  im.name = s.name + "/outline";
  im.pose.orientation.w = 1.0;
  visualization_msgs::InteractiveMarkerControl control;
  control.interaction_mode = visualization_msgs::InteractiveMarkerControl::NONE;
  control.always_visible = true;
  control.orientation.w = 1.0;
  // The outline as flat strips (a triangle list), not a LINE_STRIP: RViz 1.14 on OGRE 1.9 draws a line
  // strip as a camera-facing billboard computed for an earlier camera pose, and in the top-down view
  // whole edges of it were missing (rviz issue 1287); a flat strip needs no camera. Slightly above the
  // ground, so the masks (z = 0) do not cover it.
  visualization_msgs::Marker line;
  line.type = visualization_msgs::Marker::TRIANGLE_LIST;
  line.scale.x = line.scale.y = line.scale.z = 1.0;
  line.color.a = 1.0f;
  line.pose.orientation.w = 1.0;
  line.pose.position.z = kOutlineZ;
  std_msgs::ColorRGBA colour;  // per triangle: RViz then draws the colour as it is, unlit
  colour.r = s.value >= 100 ? 0.9f : 0.2f;
  colour.g = 0.3f;
  colour.b = s.value >= 100 ? 0.2f : 0.9f;
  colour.a = 1.0f;
  std::vector<ZonePoint> ring;
  if (s.type == ZoneShapeType::Circle)
    for (int k = 0; k < kCircleSegments; ++k)
    {
      const double a = 2.0 * M_PI * k / kCircleSegments;
      ring.push_back({s.center.x + s.radius * std::cos(a), s.center.y + s.radius * std::sin(a)});
    }
  else
    ring = s.points;
  for (std::size_t k = 0; k < ring.size(); ++k)
  {
    const ZonePoint& p = ring[k];
    const ZonePoint& q = ring[(k + 1) % ring.size()];
    const double length = std::hypot(q.x - p.x, q.y - p.y);
    if (!(length > 0.0)) continue;
    // Along the edge (ux, uy) and across it (-uy, ux), both half the width long: each strip reaches half
    // a width past its ends, so the strips of two edges meet at a corner without a notch.
    const double ux = (q.x - p.x) / length * kOutlineWidth / 2, uy = (q.y - p.y) / length * kOutlineWidth / 2;
    const ZonePoint c0{p.x - ux + uy, p.y - uy - ux}, c1{q.x + ux + uy, q.y + uy - ux};
    const ZonePoint c2{q.x + ux - uy, q.y + uy + ux}, c3{p.x - ux - uy, p.y - uy + ux};
    for (const ZonePoint& c : {c0, c1, c2, c0, c2, c3})
      line.points.push_back(toPoint(c));
    line.colors.push_back(colour);
    line.colors.push_back(colour);
  }
  control.markers.push_back(line);
  // The name at the shape (the marker's pose is the origin): a polygon's at its centroid, a circle's just
  // below its centre handle, whose label is above it.
  const ZonePoint c = costmap_layers::zoneCentroid(s);
  const double below = s.type == ZoneShapeType::Circle ? kHandleSize / 2 + kLabelGap + kNameHeight / 2 : 0.0;
  control.markers.push_back(textMarker(s.name + " (" + std::to_string(s.value) + ")", c.x, c.y - below, kNameHeight));
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
    const double sign = s.type == ZoneShapeType::Polygon ? winding(s.points) : 1.0;
    for (std::size_t k = 0; k < handles.size(); ++k)
      markers_->insert(handleMarker(l.frame_id, s, k, sign, handles[k]),
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
  if (f->event_type == visualization_msgs::InteractiveMarkerFeedback::MOUSE_UP) relabel(f->marker_name);
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

void ZoneServer::relabel(const std::string& marker)
{
  std::string name;
  std::size_t index = 0;
  visualization_msgs::InteractiveMarker held;
  // Only a handle that is offered (a shape past kMaxZoneHandles has none).
  if (!markers_ || !parseHandleName(marker, &name, &index) || !markers_->get(marker, held)) return;
  costmap_layers::ZoneShape shape;
  std::string frame;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const costmap_layers::ZoneShape* s = editor_.zones().find(name);
    if (s == nullptr) return;
    shape = *s;
    frame = editor_.zones().layout().frame_id;
  }
  const double sign = shape.type == ZoneShapeType::Polygon ? winding(shape.points) : 1.0;
  const auto handles = costmap_layers::zoneHandles(shape);
  for (std::size_t k = 0; k < handles.size(); ++k)
    markers_->insert(handleMarker(frame, shape, k, sign, handles[k]),
                     [this](const visualization_msgs::InteractiveMarkerFeedbackConstPtr& f) { onFeedback(f); });
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
