// Zone files (what zone_server loads and saves): a YAML with frame_id, resolution, default_value,
// overlay and a list of shapes, read with the same bounded YAML reader as the params files
// (param_yaml.hpp: a regular file, at most kMaxZoneYamlBytes, at most kMaxZoneYamlNodes values) and
// checked by the core (core/zones/zone_shapes.hpp says every field and rule).
//
// One rule for reading and writing: every valid layout (validateLayout) is written by
// zoneLayoutToYaml() in at most kMaxZoneYamlBytes bytes and kMaxZoneYamlNodes values, and both caps
// are derived from the layout limits (limits::kMaxZoneShapes, kMaxZoneVertices, kMaxZoneVertexPairs,
// kMaxNameLength) and the writer's own text: what zone_server holds it can save, and what it saves
// it can load.
//
// Where zone_server may read and write (ZoneFolder): inside one folder, its save directory, and the
// file it loaded at start; a file is replaced only when it is a zone file, through its link when it
// is reached by one, keeping its mode and owner (safe_write.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "costmap_layers/core/zones/zone_shapes.hpp"

namespace costmap_layers
{
namespace io
{
/// The longest text of a number in a zone file: std::to_chars' shortest form that reads back to the
/// same double has at most 17 significant digits, and the scientific form is taken only when it is
/// shorter, so "-1.2345678901234567e-300" (24 characters) is the longest.
constexpr std::size_t kMaxZoneNumberChars = 24;
/// The largest zone file read: the longest text zoneLayoutToYaml() writes for any valid layout
/// (zone_file.cpp derives it; about 8.9 MB, for 1000 polygons holding the most vertices the vertex-pair
/// limit allows, every number and name at its longest).
extern const uint64_t kMaxZoneYamlBytes;
/// The most values (scalars, lists, maps) a zone file may expand to: what the largest valid layout has.
extern const uint64_t kMaxZoneYamlNodes;

/// Reads and checks a zone file. Throws std::runtime_error (unreadable file, YAML syntax) or
/// std::invalid_argument (a field), each naming the path.
ZoneLayout loadZoneFile(const std::string& path);

/// A zone file's layout when the YAML at `path` is one (a map with a `shapes` key), nullopt when it is
/// some other YAML (a map_server map file): what lets costmap_tool's --mask take either. Throws as
/// loadZoneFile() for a zone file with a bad field.
std::optional<ZoneLayout> loadIfZoneFile(const std::string& path);

/// The layout as zone-file YAML that parseZoneLayout() reads back to an equal layout, bit for bit:
/// names and the frame double-quoted with only '"' and '\' escaped (a name like "1" or "yes" stays a
/// string; UTF-8 is written as it is), every number in the shortest form that reads back to the same
/// double (std::to_chars; "-0.0" for negative zero). For a valid layout the text is within
/// kMaxZoneYamlBytes (an invalid one is not checked here: saveZoneFile() checks before writing).
std::string zoneLayoutToYaml(const ZoneLayout& layout);

/// "" when the file at `path` is a zone file: a regular file of YAML whose top level is a map of
/// zone-file keys only (frame_id, resolution, default_value, overlay, shapes), at least one; otherwise
/// why not, without quoting the file (a peer may have named it).
std::string zoneFileProblem(const std::string& path);

/// Writes the layout so that loadZoneFile() reads back an equal layout. When `path` is a symbolic link,
/// its target is written and the link kept. An existing file is replaced only when it is a zone file
/// (zoneFileProblem()), and keeps its mode and owner; the write is atomic (replaceFileAtomically()).
/// Throws std::runtime_error naming the path when the layout is invalid or the file cannot be written.
void saveZoneFile(const std::string& path, const ZoneLayout& layout);

/// Why a file name a peer sent to zone_server's save or load cannot be used, or "" (an empty name means
/// the loaded file). No control character or NUL, at most PATH_MAX characters and NAME_MAX per part, no
/// ".." part, and ending in .yaml or .yml: the server must not read or write any other file. The
/// name is quoted clipped, with bytes that are not printable ASCII shown as '?'.
std::string zoneFilenameProblem(const std::string& name);

/// Where zone_server's save and load may go: files inside `directory` (named relative to it, or by an
/// absolute path inside it), and the file loaded at start (an empty name). Folders and links are
/// resolved (realpath) before the check, so neither a link to a folder elsewhere nor a link to a file
/// elsewhere escapes it; a link to the loaded file is the loaded file.
class ZoneFolder
{
public:
  /// @param loaded_file  the zone file loaded at start (made absolute against the working directory)
  /// @param directory    where named files may be; empty: the folder of loaded_file
  explicit ZoneFolder(const std::string& loaded_file, const std::string& directory = "");

  const std::string& directory() const { return directory_; }
  const std::string& loadedFile() const { return loaded_; }

  /// The real path of the file `name` means (through a link, its target; the file itself need not
  /// exist, its folder must: whether it reads is loadZoneFile()'s to say). Throws std::invalid_argument
  /// naming the file name (clipped) and the problem: zoneFilenameProblem(), a folder or link that does
  /// not resolve, outside the save directory.
  std::string fileToLoad(const std::string& name) const;
  /// The real path a save of `name` writes, by the same rule (saveZoneFile() then replaces only a zone
  /// file).
  std::string fileToSave(const std::string& name) const;

private:
  std::string resolve(const std::string& name) const;

  std::string loaded_;       ///< absolute
  std::string loaded_real_;  ///< its real path at start ("" when it had none)
  std::string directory_;    ///< absolute
};
}  // namespace io
}  // namespace costmap_layers
