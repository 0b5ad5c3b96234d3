// Zones drawn as shapes (what zone_server serves): polygons and circles in one frame, each with a
// mask value, filled or outline only, rasterised into an occupancy-grid mask. ROS-free: the node
// reads files, services and marker feedback into these types and publishes the mask.
//
// The rules, exactly (R = resolution, cells on the lattice of multiples of R in the layout's frame):
//  - Extent: the union of the shapes' bounding boxes (a circle's is centre +- radius), widened to
//    whole lattice cells plus one cell on every side: columns floor(min_x / R) - 1 ..
//    floor(max_x / R) + 1, the same for rows; origin = first column * R. A layout without shapes is
//    the single cell [0, R) x [0, R). The grid may have at most limits::kMaxGridCells cells.
//  - Filled shape: a cell is in when its centre ((i + 0.5) R + origin) is inside. Polygon: the
//    even-odd crossing test with a half-open rule (an edge counts when exactly one of its end points
//    lies above the centre's y, "above" meaning y > y_c, and the crossing lies right of the centre,
//    x_cross > x_c), so two polygons sharing an edge never both claim a centre on it. Circle:
//    (x_c - cx)^2 + (y_c - cy)^2 <= radius^2.
//  - Outline only (fill: false): a cell is in when the outline (the polygon's closed chain of edges,
//    or the circle's curve) meets the cell's closed square, edges and corners included. The outline
//    is therefore 4-connected (nothing slips through diagonally); an edge lying exactly on a cell
//    border marks the cells on both sides of it.
//  - Overlay: shapes are applied in list order. The first shape that claims a cell sets it; each later
//    one combines with what is there by the layout's overlay rule: `last` (the later shape wins), `max`
//    or `min` of the two values. A cell no shape claims holds default_value (which takes no part in
//    max / min, unlike Nav2's vector object server).
//
// What a valid shape is (validateShape()): a name of 1..64 characters from [A-Za-z0-9_.-] (so that a
// marker name "<shape>/<k>" splits unambiguously); a value in -1..100; every coordinate finite and
// within limits::kMaxCoordinate; a polygon has 3..limits::kMaxZoneVertices vertices, no zero-length
// edge, a non-zero area and no self-intersection (no two edges meet except neighbours at their shared
// vertex, and neighbours do not fold back over each other); a circle's radius is finite, > 0 and at
// most limits::kMaxCoordinate.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "costmap_layers/core/data/grid_data.hpp"
#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/core/config/param_value.hpp"

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

/// Checks one shape (see the file comment). The field names the shape and what is wrong
/// ("shapes/<name>/points", ".../radius", ".../value", ".../name").
InputError validateShape(const ZoneShape& shape);

/// Checks the layout: resolution in [kMinResolution, kMaxResolution], default_value in -1..100, frame
/// not empty, at most limits::kMaxZoneShapes shapes, the polygons' vertices squared summed within
/// limits::kMaxZoneVertexPairs (field "shapes"), unique names, every shape valid, the extent
/// within limits::kMaxGridCells, and the work of drawing it (each shape's bounding box in cells, plus
/// rows times vertices for a polygon) within limits::kMaxZoneRasterWork (field "extent" for both).
InputError validateLayout(const ZoneLayout& layout);

/// The extent of a layout (file comment). Throws std::invalid_argument when it exceeds
/// limits::kMaxGridCells (the message gives the size it would have).
ZoneGridExtent zoneGridExtent(const ZoneLayout& layout);

/// The mask of a valid layout (frame_id, resolution, extent, values). Throws std::invalid_argument for
/// an invalid one (validateLayout()'s message).
OccupancyGridData rasterizeZones(const ZoneLayout& layout);

/// Whether a point is inside a polygon by the half-open crossing rule (file comment).
bool pointInZonePolygon(const std::vector<ZonePoint>& polygon, double x, double y);

/// Reads a layout from a parameter tree (a zone file, see io/zone_file.hpp):
///   frame_id (map), resolution (0.05), default_value (0), overlay (last | max | min),
///   shapes: a list of maps {name, type: polygon | circle, value, fill (true), points: [[x, y], ...]
///   (polygon) or center: [x, y] and radius (circle)}.
/// Throws std::invalid_argument naming the field (e.g. "shapes[2] (dock): points[1][0] ...") for an
/// unknown key, a wrong type or an invalid shape or layout.
ZoneLayout parseZoneLayout(const ParamValue& tree, const std::string& what);

/// Parses one shape map as in a zone file (what parseZoneLayout() does per entry), validated.
ZoneShape parseZoneShape(const ParamValue& shape, const std::string& what);

/// The layout as YAML text that parseZoneLayout() reads back to an equal layout (numbers with 17
/// significant digits, so every double survives the round trip).
std::string zoneLayoutToYaml(const ZoneLayout& layout);

/// A layout that changes only by checked steps: every change is validated (the shape it changes, and
/// the layout as a whole: names, extent, work) and applied only when valid, so the last good layout
/// always stays in force. The shapes it holds are valid, so an edit checks only the one it changes.
class ZoneSet
{
public:
  /// Throws std::invalid_argument when layout is not valid.
  explicit ZoneSet(ZoneLayout layout);

  const ZoneLayout& layout() const { return layout_; }
  /// The shape of that name, or nullptr.
  const ZoneShape* find(const std::string& name) const;

  /// Adds the shape, or replaces the one of the same name in its place. @return the error, or ok()
  InputError upsert(const ZoneShape& shape);
  /// Removes the shape of that name (an error when there is none).
  InputError remove(const std::string& name);
  /// Moves one handle of a shape to (x, y): polygon vertex `index` (0-based); for a circle, handle 0
  /// moves the centre (keeping the radius) and handle 1 sets the radius to the distance from the
  /// centre. @return the error (unknown shape or handle, or the shape it would make is invalid)
  InputError moveHandle(const std::string& name, std::size_t index, double x, double y);
  /// Replaces the whole layout (a reload). @return the error, or ok()
  InputError replace(const ZoneLayout& layout);
  /// The mask of the layout (rasterizeZones() without checking it again).
  OccupancyGridData rasterize() const;

private:
  /// @param shapes_valid  every shape of next has been validated (only the layout-wide checks run)
  InputError commit(ZoneLayout next, bool shapes_valid);
  ZoneLayout layout_;
};

/// The handle positions of a shape, in the order moveHandle() numbers them: a polygon's vertices; a
/// circle's centre, then the point at radius along +x from the centre.
std::vector<ZonePoint> zoneHandles(const ZoneShape& shape);
}  // namespace costmap_layers
