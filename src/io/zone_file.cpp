#include "costmap_layers/io/zone_file.hpp"

#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/io/param_yaml.hpp"
#include "costmap_layers/io/safe_write.hpp"

namespace costmap_layers
{
namespace io
{
namespace
{
// The writer's fixed text, used both to write a file and to bound what it writes (kMaxZoneYamlBytes).
constexpr std::string_view kHeader = "# zone_server shapes (written by zone_server's save service)\n";
constexpr std::string_view kFrameKey = "frame_id: ";
constexpr std::string_view kResolutionKey = "resolution: ";
constexpr std::string_view kDefaultKey = "default_value: ";
constexpr std::string_view kOverlayKey = "overlay: ";
constexpr std::string_view kNoShapes = "shapes: []\n";
constexpr std::string_view kShapesKey = "shapes:\n";
constexpr std::string_view kNameKey = "  - name: ";
constexpr std::string_view kTypeKey = "    type: ";
constexpr std::string_view kValueKey = "    value: ";
constexpr std::string_view kFillKey = "    fill: ";
constexpr std::string_view kPointsKey = "    points:\n";
constexpr std::string_view kPointOpen = "      - [";
constexpr std::string_view kCenterKey = "    center: [";
constexpr std::string_view kRadiusKey = "    radius: ";
constexpr std::string_view kPairSep = ", ";
constexpr std::string_view kPairClose = "]\n";
constexpr uint64_t kMaxIntChars = 3;                              ///< a mask value: -1..100
constexpr uint64_t kMaxOverlayChars = 4;                          ///< "last"
constexpr uint64_t kMaxTypeChars = 7;                             ///< "polygon"
constexpr uint64_t kMaxFillChars = 5;                             ///< "false"
constexpr uint64_t kMaxQuotedNameChars = 2 + 2 * kMaxNameLength;  ///< every byte escaped, and the quotes

constexpr uint64_t isqrt(uint64_t n)
{
  uint64_t r = 0;
  while ((r + 1) * (r + 1) <= n)
    ++r;
  return r;
}

/// The most vertices a valid layout holds: at most kMaxZoneShapes polygons, their vertex counts squared
/// summing to at most kMaxZoneVertexPairs; by Cauchy-Schwarz, (sum n)^2 <= shapes * sum n^2.
constexpr uint64_t kMaxLayoutVertices =
    std::min<uint64_t>(uint64_t{limits::kMaxZoneShapes} * limits::kMaxZoneVertices,
                       isqrt(uint64_t{limits::kMaxZoneShapes} * static_cast<uint64_t>(limits::kMaxZoneVertexPairs)));

constexpr uint64_t pairBytes()
{
  return 2 * kMaxZoneNumberChars + kPairSep.size() + kPairClose.size();
}

constexpr uint64_t maxYamlBytes()
{
  const uint64_t header = kHeader.size() + kFrameKey.size() + kMaxQuotedNameChars + 1 + kResolutionKey.size() +
                          kMaxZoneNumberChars + 1 + kDefaultKey.size() + kMaxIntChars + 1 + kOverlayKey.size() +
                          kMaxOverlayChars + 1 + std::max(kNoShapes.size(), kShapesKey.size());
  const uint64_t circle = kCenterKey.size() + pairBytes() + kRadiusKey.size() + kMaxZoneNumberChars + 1;
  const uint64_t shape = kNameKey.size() + kMaxQuotedNameChars + 1 + kTypeKey.size() + kMaxTypeChars + 1 +
                         kValueKey.size() + kMaxIntChars + 1 + kFillKey.size() + kMaxFillChars + 1 +
                         std::max<uint64_t>(kPointsKey.size(), circle);
  const uint64_t point = kPointOpen.size() + pairBytes();
  return header + limits::kMaxZoneShapes * shape + kMaxLayoutVertices * point;
}

/// Values: the top map, its four scalars and the shape list; per shape at most a map, four scalars and
/// a circle's centre list of two and radius; per vertex a list of two.
constexpr uint64_t maxYamlNodes()
{
  return 6 + limits::kMaxZoneShapes * 9 + kMaxLayoutVertices * 3;
}

void number(std::string& out, double v)
{
  if (v == 0.0 && std::signbit(v))
  {
    out += "-0.0";  // "-0" would read back as the integer 0
    return;
  }
  char buf[64];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof(buf), v);
  if (r.ec != std::errc() || static_cast<std::size_t>(r.ptr - buf) > kMaxZoneNumberChars)
    throw std::logic_error("zoneLayoutToYaml: a number's shortest text is longer than kMaxZoneNumberChars");
  out.append(buf, r.ptr);
}

/// A double-quoted YAML scalar: only '"' and '\' are escaped. The layout's rules leave no control
/// character in a name or frame, and a name is valid UTF-8, which YAML reads back as it is (yaml-cpp's
/// own emitter would turn the noncharacters U+FDD0..U+FDEF and U+xFFFE/F into U+FFFD).
void quoted(std::string& out, const std::string& text)
{
  out += '"';
  for (const char c : text)
  {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  out += '"';
}

void pair(std::string& out, const ZonePoint& p)
{
  number(out, p.x);
  out += kPairSep;
  number(out, p.y);
  out += kPairClose;
}

/// Shown in a message: at most 64 bytes, those that are not printable ASCII as '?'.
std::string shown(const std::string& name)
{
  std::string s;
  for (const char c : name.substr(0, 64))
    s += c >= ' ' && c < 127 ? c : '?';
  return name.size() > 64 ? s + "..." : s;
}

std::string absolutePath(const std::string& path)
{
  if (!path.empty() && path[0] == '/') return path;
  std::unique_ptr<char, decltype(&std::free)> cwd(::getcwd(nullptr, 0), &std::free);
  if (!cwd) throw std::runtime_error("the working directory cannot be found: " + std::string(std::strerror(errno)));
  return std::string(cwd.get()) + "/" + path;
}

/// realpath(), or "" with realpath's errno.
std::string realPath(const std::string& path)
{
  char* real = ::realpath(path.c_str(), nullptr);
  if (real == nullptr) return std::string();
  std::string out(real);
  std::free(real);
  return out;
}

std::string folderOf(const std::string& path)
{
  const std::size_t slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

bool inside(const std::string& root, const std::string& path)
{
  if (root == "/") return path.size() > 1 && path[0] == '/';
  return path.size() > root.size() + 1 && path.compare(0, root.size(), root) == 0 && path[root.size()] == '/';
}
}  // namespace

const uint64_t kMaxZoneYamlBytes = maxYamlBytes();
const uint64_t kMaxZoneYamlNodes = maxYamlNodes();

std::string zoneLayoutToYaml(const ZoneLayout& l)
{
  std::string out;
  out += kHeader;
  out += kFrameKey;
  quoted(out, l.frame_id);
  out += '\n';
  out += kResolutionKey;
  number(out, l.resolution);
  out += '\n';
  out += kDefaultKey;
  out += std::to_string(l.default_value);
  out += '\n';
  out += kOverlayKey;
  out += zoneOverlayName(l.overlay);
  out += '\n';
  if (l.shapes.empty())
  {
    out += kNoShapes;
    return out;
  }
  out += kShapesKey;
  for (const auto& s : l.shapes)
  {
    out += kNameKey;
    quoted(out, s.name);
    out += '\n';
    out += kTypeKey;
    out += s.type == ZoneShapeType::Circle ? "circle" : "polygon";
    out += '\n';
    out += kValueKey;
    out += std::to_string(s.value);
    out += '\n';
    out += kFillKey;
    out += s.fill ? "true" : "false";
    out += '\n';
    if (s.type == ZoneShapeType::Circle)
    {
      out += kCenterKey;
      pair(out, s.center);
      out += kRadiusKey;
      number(out, s.radius);
      out += '\n';
    }
    else
    {
      out += kPointsKey;
      for (const auto& p : s.points)
      {
        out += kPointOpen;
        pair(out, p);
      }
    }
  }
  return out;
}

ZoneLayout loadZoneFile(const std::string& path)
{
  return parseZoneLayout(loadOwnFormatYamlFile(path, kMaxZoneYamlBytes, kMaxZoneYamlNodes), "'" + path + "'");
}

std::optional<ZoneLayout> loadIfZoneFile(const std::string& path)
{
  std::vector<std::string> repeated;
  const ParamValue tree = loadParamsYamlFile(path, kMaxZoneYamlBytes, false, &repeated, kMaxZoneYamlNodes);
  if (!tree.isMap() || tree.find("shapes") == nullptr) return std::nullopt;
  refuseRepeatedKeys(repeated);  // this package's own format: a lost value refuses the file
  return parseZoneLayout(tree, "'" + path + "'");
}

std::string zoneFileProblem(const std::string& path)
{
  struct stat st
  {
  };
  if (::stat(path.c_str(), &st) != 0) return "'" + path + "' cannot be examined: " + std::strerror(errno);
  if (!S_ISREG(st.st_mode)) return "'" + path + "' is not a regular file";
  ParamValue tree;
  try
  {
    tree = loadParamsYamlFile(path, kMaxZoneYamlBytes, false, nullptr, kMaxZoneYamlNodes);
  }
  catch (const std::exception&)
  {
    // The reader's message may quote a line of the file: not passed on.
    return "'" + path + "' is not a zone file (not YAML within " + std::to_string(kMaxZoneYamlBytes) + " bytes)";
  }
  static const std::vector<std::string> kKeys = {"frame_id", "resolution", "default_value", "overlay", "shapes"};
  const bool zone =
      tree.isMap() && !tree.entries().empty() &&
      std::all_of(tree.entries().begin(), tree.entries().end(),
                  [](const auto& entry) { return std::find(kKeys.begin(), kKeys.end(), entry.first) != kKeys.end(); });
  if (!zone)
    return "'" + path +
           "' is not a zone file (its top level is not a map of frame_id, resolution, default_value, overlay, shapes)";
  return "";
}

void saveZoneFile(const std::string& path, const ZoneLayout& layout)
{
  const InputError error = validateLayout(layout);
  if (!error.ok()) throw std::runtime_error("'" + path + "': not saved: " + error.message);
  const std::string text = zoneLayoutToYaml(layout);
  // Cannot happen for a valid layout (the cap is derived from the limits); checked so that a writer
  // change that broke the derivation fails here, before a file that would not load is written.
  if (text.size() > kMaxZoneYamlBytes)
    throw std::logic_error("'" + path + "': not saved: the text has " + std::to_string(text.size()) +
                           " bytes, more than the " + std::to_string(kMaxZoneYamlBytes) + " a zone file may have");
  std::string target = path;
  struct stat st
  {
  };
  if (::lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode))
  {
    target = realPath(path);
    if (target.empty())
      throw std::runtime_error("'" + path + "': a link whose target cannot be resolved: " + std::strerror(errno));
  }
  if (::stat(target.c_str(), &st) == 0)
  {
    const std::string why = zoneFileProblem(target);
    if (!why.empty()) throw std::runtime_error("not saved: " + why + ", and only a zone file is replaced");
  }
  replaceFileAtomically(target, text);
}

std::string zoneFilenameProblem(const std::string& name)
{
  if (name.empty()) return "";
  const std::string quote = "filename '" + shown(name) + "'";
  if (name.size() > static_cast<std::size_t>(PATH_MAX))
    return "filename '" + shown(name.substr(0, 64)) + "...' has " + std::to_string(name.size()) +
           " characters, more than " + std::to_string(PATH_MAX) + " (PATH_MAX)";
  for (std::size_t k = 0; k < name.size(); ++k)
  {
    const auto c = static_cast<unsigned char>(name[k]);
    if (c < ' ' || c == 127)
      return quote + " has character code " + std::to_string(c) + " at position " + std::to_string(k) +
             ": a file name holds no control characters";
  }
  for (std::size_t start = 0; start <= name.size();)
  {
    const std::size_t end = std::min(name.find('/', start), name.size());
    const std::size_t length = end - start;
    if (length == 2 && name.compare(start, 2, "..") == 0)
      return quote + " has a '..' part: zone files are named inside the save directory (save_directory)";
    if (length > static_cast<std::size_t>(NAME_MAX))
      return quote + " has a part of " + std::to_string(length) + " characters, more than " + std::to_string(NAME_MAX) +
             " (NAME_MAX)";
    start = end + 1;
  }
  auto ends_with = [&](const std::string& tail)
  { return name.size() > tail.size() && name.compare(name.size() - tail.size(), tail.size(), tail) == 0; };
  if (!ends_with(".yaml") && !ends_with(".yml"))
    return quote + " does not end in .yaml or .yml: zone files are YAML, and no other file is read or written";
  if (name[name.size() - (ends_with(".yml") ? 5 : 6)] == '/') return quote + " has nothing before its extension";
  return "";
}

ZoneFolder::ZoneFolder(const std::string& loaded_file, const std::string& directory)
    : loaded_(absolutePath(loaded_file)),
      loaded_real_(realPath(loaded_)),
      directory_(directory.empty() ? folderOf(loaded_) : absolutePath(directory))
{
}

std::string ZoneFolder::resolve(const std::string& name) const
{
  if (const std::string why = zoneFilenameProblem(name); !why.empty()) throw std::invalid_argument(why);
  const std::string quote =
      name.empty() ? "the loaded file '" + shown(loaded_) + "'" : "filename '" + shown(name) + "'";
  // A named file needs the save directory (the empty name, the loaded file, does not).
  const std::string real_dir = name.empty() ? std::string() : realPath(directory_);
  if (!name.empty() && real_dir.empty())
    throw std::invalid_argument(quote + ": the save directory '" + shown(directory_) +
                                "' (save_directory) cannot be resolved: " + std::strerror(errno));
  const std::string path = name.empty() ? loaded_ : (name[0] == '/' ? name : directory_ + "/" + name);
  const std::size_t slash = path.rfind('/');
  const std::string parent = realPath(slash == 0 ? "/" : path.substr(0, slash));
  if (parent.empty()) throw std::invalid_argument(quote + ": its folder cannot be resolved: " + std::strerror(errno));
  std::string target = (parent == "/" ? "" : parent) + "/" + path.substr(slash + 1);
  struct stat st
  {
  };
  if (::lstat(target.c_str(), &st) != 0)
  {
    if (errno != ENOENT) throw std::invalid_argument(quote + ": " + std::strerror(errno));
  }
  else if (S_ISLNK(st.st_mode))
  {
    target = realPath(target);
    if (target.empty())
      throw std::invalid_argument(quote + ": a link whose target cannot be resolved: " + std::strerror(errno));
  }
  // The loaded file (no name; or a name that resolves to it as it was at start, or as its name now
  // resolves: a link re-pointed since) is always allowed; anything else must be inside the save
  // directory. Whether the file exists is the reader's to say: a peer learns nothing of files elsewhere.
  const bool loaded = name.empty() || target == loaded_real_ || target == realPath(loaded_);
  if (!loaded && !inside(real_dir, target))
    throw std::invalid_argument(quote + " is outside the save directory '" + shown(real_dir) +
                                "' (save_directory): zone files are read and written only there");
  return target;
}

std::string ZoneFolder::fileToLoad(const std::string& name) const
{
  return resolve(name);
}

std::string ZoneFolder::fileToSave(const std::string& name) const
{
  return resolve(name);
}
}  // namespace io
}  // namespace costmap_layers
