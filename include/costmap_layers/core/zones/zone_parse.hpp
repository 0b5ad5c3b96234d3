// Zone layouts read from a parameter tree (what io/zone_file.hpp loads from YAML); the writer is
// io::zoneLayoutToYaml() in io/zone_file.hpp.
#pragma once

#include <string>

#include "costmap_layers/core/config/param_value.hpp"
#include "costmap_layers/core/zones/zone_layout.hpp"

namespace costmap_layers
{
/// Reads a layout from a parameter tree (a zone file, see io/zone_file.hpp):
///   frame_id (map), resolution (0.05), default_value (0), overlay (last | max | min),
///   shapes: a list of maps {name, type: polygon | circle, value, fill (true), points: [[x, y], ...]
///   (polygon) or center: [x, y] and radius (circle)}.
/// Throws std::invalid_argument naming the field (e.g. "shapes[2] (dock): points[1][0] ...") for an
/// unknown key, a wrong type or an invalid shape or layout.
ZoneLayout parseZoneLayout(const ParamValue& tree, const std::string& what);

/// Parses one shape map as in a zone file (what parseZoneLayout() does per entry), validated.
ZoneShape parseZoneShape(const ParamValue& shape, const std::string& what);

}  // namespace costmap_layers
