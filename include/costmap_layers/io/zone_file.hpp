// Zone files (what zone_server loads and saves): a YAML with frame_id, resolution, default_value,
// overlay and a list of shapes, read with the same bounded YAML reader as the params files
// (param_yaml.hpp: a regular file, at most kMaxParamsYamlBytes) and checked by the core
// (core/zones/zone_shapes.hpp says every field and rule).
#pragma once

#include <optional>
#include <string>

#include "costmap_layers/core/zones/zone_shapes.hpp"

namespace costmap_layers
{
namespace io
{
/// Reads and checks a zone file. Throws std::runtime_error (unreadable file, YAML syntax) or
/// std::invalid_argument (a field), each naming the path.
ZoneLayout loadZoneFile(const std::string& path);

/// A zone file's layout when the YAML at `path` is one (a map with a `shapes` key), nullopt when it is
/// some other YAML (a map_server map file): what lets costmap_tool's --mask take either. Throws as
/// loadZoneFile() for a zone file with a bad field.
std::optional<ZoneLayout> loadIfZoneFile(const std::string& path);

/// The layout as zone-file YAML (written with yaml-cpp's emitter) that parseZoneLayout() reads back to an
/// equal layout: names and the frame double-quoted (a name like "1" or "yes" stays a string), numbers
/// with 17 significant digits, so that every double reads back to itself.
std::string zoneLayoutToYaml(const ZoneLayout& layout);

/// Writes the layout so that loadZoneFile() reads back an equal layout: to a temporary file next to
/// `path`, then renamed over it, so that a reader never sees half a file. Throws std::runtime_error
/// naming the path when it cannot be written.
void saveZoneFile(const std::string& path, const ZoneLayout& layout);
}  // namespace io
}  // namespace costmap_layers
