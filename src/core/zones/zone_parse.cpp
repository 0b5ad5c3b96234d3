#include "costmap_layers/core/zones/zone_parse.hpp"

#include <algorithm>
#include <stdexcept>

#include "costmap_layers/core/rules/limits.hpp"

namespace costmap_layers
{
namespace
{
/// A number from a tree node, or a clear error.
double number(const ParamValue& v, const std::string& what)
{
  if (!v.isNumber()) throw std::invalid_argument(what + " must be a number (got " + v.toString() + ")");
  return v.asDouble();
}

ZonePoint point(const ParamValue& v, const std::string& what)
{
  if (!v.isList() || v.asList().size() != 2)
    throw std::invalid_argument(what + " must be a list [x, y] (got " + v.toString() + ")");
  return {number(v.asList()[0], what + "[0]"), number(v.asList()[1], what + "[1]")};
}

int maskValue(const ParamValue& v, const std::string& what)
{
  if (v.type() != ParamValue::Type::Int || v.asInt() < -1 || v.asInt() > 100)
    throw std::invalid_argument(what + " must be an integer in -1..100 (got " + v.toString() + ")");
  return static_cast<int>(v.asInt());
}

void checkKeys(const ParamValue& map, const std::vector<std::string>& known, const std::string& what)
{
  for (const auto& [key, value] : map.entries())
    if (std::find(known.begin(), known.end(), key) == known.end())
    {
      std::string list;
      for (const auto& k : known)
        list += (list.empty() ? "" : ", ") + k;
      throw std::invalid_argument(what + ": unknown field '" + key + "' (known: " + list + ")");
    }
}
}  // namespace

ZoneShape parseZoneShape(const ParamValue& v, const std::string& what)
{
  if (!v.isMap()) throw std::invalid_argument(what + " must be a map (got " + v.toString() + ")");
  ZoneShape s;
  const ParamValue* name = v.find("name");
  if (!name || name->type() != ParamValue::Type::String)
    throw std::invalid_argument(what + ": 'name' must be set to a string");
  s.name = name->asString();
  const std::string at = what + " (" + zoneNameText(s.name) + ")";  // clipped: the name is not checked yet
  const ParamValue* type = v.find("type");
  if (!type || type->type() != ParamValue::Type::String ||
      (type->asString() != "polygon" && type->asString() != "circle"))
    throw std::invalid_argument(at + ": 'type' must be \"polygon\" or \"circle\" (got " +
                                (type ? type->toString() : std::string("nothing")) + ")");
  s.type = type->asString() == "circle" ? ZoneShapeType::Circle : ZoneShapeType::Polygon;
  if (s.type == ZoneShapeType::Polygon)
    checkKeys(v, {"name", "type", "value", "fill", "points"}, at);
  else
    checkKeys(v, {"name", "type", "value", "fill", "center", "radius"}, at);
  const ParamValue* value = v.find("value");
  if (!value) throw std::invalid_argument(at + ": 'value' (the mask value, -1..100) must be set");
  s.value = maskValue(*value, at + ": value");
  if (const ParamValue* fill = v.find("fill"))
  {
    if (fill->type() != ParamValue::Type::Bool)
      throw std::invalid_argument(at + ": fill must be true or false (got " + fill->toString() + ")");
    s.fill = fill->asBool();
  }
  if (s.type == ZoneShapeType::Polygon)
  {
    const ParamValue* pts = v.find("points");
    if (!pts || !pts->isList())
      throw std::invalid_argument(at + ": 'points' must be a list of [x, y] (got " +
                                  (pts ? pts->toString() : std::string("nothing")) + ")");
    if (pts->asList().size() > limits::kMaxZoneVertices)
      throw std::invalid_argument(at + ": at most " + std::to_string(limits::kMaxZoneVertices) + " points (got " +
                                  std::to_string(pts->asList().size()) + ")");
    for (std::size_t k = 0; k < pts->asList().size(); ++k)
      s.points.push_back(point(pts->asList()[k], at + ": points[" + std::to_string(k) + "]"));
  }
  else
  {
    const ParamValue* c = v.find("center");
    const ParamValue* r = v.find("radius");
    if (!c || !r) throw std::invalid_argument(at + ": a circle needs 'center' [x, y] and 'radius'");
    s.center = point(*c, at + ": center");
    s.radius = number(*r, at + ": radius");
  }
  const InputError e = validateShape(s);
  if (!e.ok()) throw std::invalid_argument(what + ": " + e.message);
  return s;
}

ZoneLayout parseZoneLayout(const ParamValue& tree, const std::string& what)
{
  // A file that is not meant as a zone file is not quoted: zone_server loads files a peer names, and the
  // answer goes back to that peer.
  if (!tree.isMap()) throw std::invalid_argument(what + ": not a zone file (its top level is not a map)");
  const std::vector<std::string> known = {"frame_id", "resolution", "default_value", "overlay", "shapes"};
  if (std::none_of(known.begin(), known.end(), [&](const std::string& k) { return tree.find(k) != nullptr; }))
    throw std::invalid_argument(what +
                                ": not a zone file (none of frame_id, resolution, default_value, overlay, "
                                "shapes at its top level)");
  checkKeys(tree, known, what);
  ZoneLayout l;
  if (const ParamValue* f = tree.find("frame_id"))
  {
    if (f->type() != ParamValue::Type::String) throw std::invalid_argument(what + ": frame_id must be a string");
    l.frame_id = f->asString();
  }
  if (const ParamValue* r = tree.find("resolution")) l.resolution = number(*r, what + ": resolution");
  if (const ParamValue* d = tree.find("default_value")) l.default_value = maskValue(*d, what + ": default_value");
  if (const ParamValue* o = tree.find("overlay"))
  {
    const std::string name = o->type() == ParamValue::Type::String ? o->asString() : "";
    if (name == "last")
      l.overlay = ZoneOverlay::Last;
    else if (name == "max")
      l.overlay = ZoneOverlay::Max;
    else if (name == "min")
      l.overlay = ZoneOverlay::Min;
    else
      throw std::invalid_argument(what + ": overlay must be \"last\", \"max\" or \"min\" (got " + o->toString() + ")");
  }
  if (const ParamValue* shapes = tree.find("shapes"))
  {
    if (!shapes->isList() && !shapes->isNull())
      throw std::invalid_argument(what + ": shapes must be a list (got " + shapes->toString() + ")");
    if (shapes->isList())
    {
      if (shapes->asList().size() > limits::kMaxZoneShapes)
        throw std::invalid_argument(what + ": at most " + std::to_string(limits::kMaxZoneShapes) + " shapes (got " +
                                    std::to_string(shapes->asList().size()) + ")");
      for (std::size_t k = 0; k < shapes->asList().size(); ++k)
        l.shapes.push_back(parseZoneShape(shapes->asList()[k], what + ": shapes[" + std::to_string(k) + "]"));
    }
  }
  const InputError e = validateLayout(l);
  if (!e.ok()) throw std::invalid_argument(what + ": " + e.message);
  return l;
}
}  // namespace costmap_layers
