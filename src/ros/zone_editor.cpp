#include "costmap_layers/ros/zone_editor.hpp"

#include <exception>
#include <stdexcept>
#include <utility>

#include "costmap_layers/io/zone_file.hpp"

namespace costmap_layers_ros
{
using costmap_layers::InputError;
using costmap_layers::ZoneShapeType;

costmap_layers::ZoneShape fromMsg(const costmap_layers::ZoneShapeDescription& msg)
{
  costmap_layers::ZoneShape s;
  s.name = msg.name;
  if (msg.type == "polygon")
    s.type = ZoneShapeType::Polygon;
  else if (msg.type == "circle")
    s.type = ZoneShapeType::Circle;
  else
    throw std::invalid_argument("shape '" + msg.name.substr(0, 64) +
                                "': type must be \"polygon\" or \"circle\" (got \"" + msg.type.substr(0, 64) + "\")");
  s.value = msg.value;
  s.fill = msg.fill;
  if (s.type == ZoneShapeType::Polygon)
    for (const auto& p : msg.points)
      s.points.push_back({p.x, p.y});
  s.center = {msg.center.x, msg.center.y};
  s.radius = msg.radius;
  return s;
}

bool parseHandleName(const std::string& marker, std::string* shape, std::size_t* index)
{
  const auto slash = marker.rfind('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 >= marker.size()) return false;
  *shape = marker.substr(0, slash);
  const std::string tail = marker.substr(slash + 1);
  if (tail == "center")
  {
    *index = 0;
    return true;
  }
  if (tail == "radius")
  {
    *index = 1;
    return true;
  }
  if (tail.size() > 6) return false;  // no polygon has a million vertices
  for (const char c : tail)
    if (c < '0' || c > '9') return false;
  *index = static_cast<std::size_t>(std::stoul(tail));
  return true;
}

ZoneEditor::ZoneEditor(costmap_layers::ZoneSet zones, const std::string& yaml_filename,
                       const std::string& save_directory)
    : zones_(std::move(zones)), folder_(yaml_filename, save_directory)
{
}

ZoneEdit ZoneEditor::set(const costmap_layers::ZoneShapeDescription& shape)
{
  ZoneEdit r;
  try
  {
    r.error = zones_.upsert(fromMsg(shape));
  }
  catch (const std::invalid_argument& e)
  {
    r.error = InputError::of("shapes/type", e.what());
  }
  r.success = r.error.ok();
  r.message = r.error.ok() ? "shape '" + shape.name + "' in force" : r.error.message;
  return r;
}

ZoneEdit ZoneEditor::remove(const std::string& name)
{
  ZoneEdit r;
  r.error = zones_.remove(name);
  r.success = r.error.ok();
  r.message = r.error.ok() ? "shape '" + name + "' removed" : r.error.message;
  return r;
}

ZoneEdit ZoneEditor::save(const std::string& filename) const
{
  ZoneEdit r;
  std::string path;
  try
  {
    path = folder_.fileToSave(filename);
  }
  catch (const std::exception& e)
  {
    r.error = InputError::of("save/filename", e.what());
  }
  if (r.error.ok()) try
    {
      costmap_layers::io::saveZoneFile(path, zones_.layout());
      r.success = true;
    }
    catch (const std::exception& e)
    {
      r.error = InputError::of("save", e.what());
    }
  r.message = r.success ? path : r.error.message;
  return r;
}

ZoneEdit ZoneEditor::load(const std::string& filename)
{
  ZoneEdit r;
  std::string path;
  try
  {
    path = folder_.fileToLoad(filename);
  }
  catch (const std::exception& e)
  {
    r.error = InputError::of("load/filename", e.what());
  }
  if (r.error.ok()) try
    {
      r.error = zones_.replace(costmap_layers::io::loadZoneFile(path));
    }
    catch (const std::exception& e)
    {
      r.error = InputError::of("load", e.what());
    }
  r.success = r.error.ok();
  r.message = r.success ? "loaded " + path : r.error.message;
  return r;
}

ZoneDrag ZoneEditor::drag(const std::string& marker, const std::string& frame_id, double x, double y)
{
  ZoneDrag d;
  std::string shape;
  if (!parseHandleName(marker, &shape, &d.index)) return d;
  const costmap_layers::ZoneShape* before = zones_.find(shape);
  if (!before) return d;
  d.applies = true;
  const std::vector<costmap_layers::ZonePoint> old_handles = costmap_layers::zoneHandles(*before);
  d.frame = zones_.layout().frame_id;
  if (const std::string why = costmap_layers::frameIdProblem(frame_id); !why.empty())
    d.error = InputError::of("feedback/header.frame_id", "marker feedback for " + marker + ": header.frame_id " + why);
  else if (frame_id != d.frame)
    d.error = InputError::of("feedback/header.frame_id", "marker feedback for " + marker + " is in frame '" +
                                                             costmap_layers::shownText(frame_id) +
                                                             "', the zones are in '" + d.frame + "'");
  else
    d.error = zones_.moveHandle(shape, d.index, x, y);
  if (!d.error.ok())
  {
    if (d.index < old_handles.size()) d.put_back = old_handles[d.index];
  }
  else
    d.moved = *zones_.find(shape);
  return d;
}
}  // namespace costmap_layers_ros
