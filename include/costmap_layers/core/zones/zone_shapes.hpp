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
// What a valid shape is (validateShape()): a name by labelProblem() (1..kMaxNameLength bytes, no
// control character) that is UTF-8 (a zone file is YAML, Unicode text); a value in -1..100; every coordinate finite and
// within limits::kMaxCoordinate; a polygon has 3..limits::kMaxZoneVertices vertices, no zero-length
// edge, a non-zero area and no self-intersection (no two edges meet except neighbours at their shared
// vertex, and neighbours do not fold back over each other); a circle's radius is finite, > 0 and at
// most limits::kMaxCoordinate.
//
// The parts, one idea each: zone_layout.hpp (the shapes, the layout, validation and extent),
// zone_raster.hpp (the rasteriser), zone_parse.hpp (reading a parameter tree), zone_set.hpp (the
// editing model). This header includes them all; the YAML writer is io::zoneLayoutToYaml().
#pragma once

#include "costmap_layers/core/zones/zone_layout.hpp"
#include "costmap_layers/core/zones/zone_parse.hpp"
#include "costmap_layers/core/zones/zone_raster.hpp"
#include "costmap_layers/core/zones/zone_set.hpp"
