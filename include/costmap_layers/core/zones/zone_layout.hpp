// The zones' data: shapes, layouts and what makes them valid, and the grid a layout spans. The rules,
// exactly, are in zone_shapes.hpp's comment.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "costmap_layers/core/config/input_error.hpp"

namespace costmap_layers
{
struct ZonePoint
{
  double x = 0.0;  ///< [m]
  double y = 0.0;  ///< [m]
};

enum class ZoneShapeType
{
  Polygon,
  Circle
};

struct ZoneShape
{
  std::string name;
  ZoneShapeType type = ZoneShapeType::Polygon;
  std::vector<ZonePoint> points;  ///< polygon vertices, in order (the chain closes by itself)
  ZonePoint center;               ///< circle
  double radius = 0.0;            ///< circle [m]
  int value = 100;                ///< mask value, -1..100
  bool fill = true;               ///< false: outline only
};

enum class ZoneOverlay
{
  Last,
  Max,
  Min
};

/// "last", "max", "min".
const char* zoneOverlayName(ZoneOverlay overlay);

struct ZoneLayout
{
  std::string frame_id = "map";
  double resolution = 0.05;  ///< [m/cell]
  int default_value = 0;     ///< cells no shape claims, -1..100
  ZoneOverlay overlay = ZoneOverlay::Last;
  std::vector<ZoneShape> shapes;
};

/// The grid a layout rasterises into: origin [m] and size [cells].
struct ZoneGridExtent
{
  double origin_x = 0.0, origin_y = 0.0;
  uint32_t width = 1, height = 1;
};

/// "shapes/<name>" ("shapes/(unnamed)" without a name): how errors name a shape.
std::string zoneShapePath(const ZoneShape& shape);

/// A shape name as a message quotes it: at most 64 bytes, those that are not printable ASCII as '?',
/// then its length when it was longer (a peer's name, which may be anything).
std::string zoneNameText(const std::string& name);

/// The position of the first byte of `text` that does not begin a well-formed UTF-8 character (RFC
/// 3629: no overlong form, no surrogate, nothing past U+10FFFF), or std::string::npos.
std::size_t utf8ErrorAt(const std::string& text);

/// Checks one shape (see the file comment). The field names the shape and what is wrong
/// ("shapes/<name>/points", ".../radius", ".../value"; a bad name has the fixed key
/// "shapes/(bad name)/name", an empty one "shapes/(unnamed)/name").
InputError validateShape(const ZoneShape& shape);

/// Checks the layout: resolution in [kMinResolution, kMaxResolution], default_value in -1..100, the
/// frame a tf frame id (frameIdProblem(): printable ASCII, no space, 1..kMaxNameLength), at most
/// limits::kMaxZoneShapes shapes, the polygons' vertices squared summed within
/// limits::kMaxZoneVertexPairs (field "shapes"), unique names, every shape valid, the extent within
/// limits::kMaxGridCells, and the work of drawing it (each shape's bounding box in cells, plus rows
/// times vertices for a polygon) within limits::kMaxZoneRasterWork (field "extent" for both).
InputError validateLayout(const ZoneLayout& layout);

/// The extent of a layout (file comment). Throws std::invalid_argument when it exceeds
/// limits::kMaxGridCells (the message gives the size it would have).
ZoneGridExtent zoneGridExtent(const ZoneLayout& layout);

/// validateLayout() for a layout whose shapes are each known valid (a ZoneSet's, plus one that
/// validateShape() has passed): only the checks of the layout as a whole run.
InputError validateLayoutOfValidShapes(const ZoneLayout& layout);
}  // namespace costmap_layers
