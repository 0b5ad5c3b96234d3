#include "costmap_layers/io/zone_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "costmap_layers/io/param_yaml.hpp"

namespace costmap_layers
{
namespace io
{
namespace
{
/// One point as a flow pair [x, y].
void emitPoint(YAML::Emitter& out, const ZonePoint& p)
{
  out << YAML::Flow << YAML::BeginSeq << p.x << p.y << YAML::EndSeq;
}
}  // namespace

std::string zoneLayoutToYaml(const ZoneLayout& l)
{
  YAML::Emitter out;
  // 17 significant digits: every double reads back to itself (yaml-cpp's default too; said here
  // because the round trip depends on it).
  out.SetDoublePrecision(17);
  out << YAML::Comment("zone_server shapes (written by zone_server's save service)");
  out << YAML::BeginMap;
  // Frame ids and names are quoted: a name like "1" or "yes" must read back as a string.
  out << YAML::Key << "frame_id" << YAML::Value << YAML::DoubleQuoted << l.frame_id;
  out << YAML::Key << "resolution" << YAML::Value << l.resolution;
  out << YAML::Key << "default_value" << YAML::Value << l.default_value;
  out << YAML::Key << "overlay" << YAML::Value << zoneOverlayName(l.overlay);
  out << YAML::Key << "shapes" << YAML::Value;
  if (l.shapes.empty())
    out << YAML::Flow << YAML::BeginSeq << YAML::EndSeq;
  else
  {
    out << YAML::BeginSeq;
    for (const auto& s : l.shapes)
    {
      out << YAML::BeginMap;
      out << YAML::Key << "name" << YAML::Value << YAML::DoubleQuoted << s.name;
      out << YAML::Key << "type" << YAML::Value << (s.type == ZoneShapeType::Circle ? "circle" : "polygon");
      out << YAML::Key << "value" << YAML::Value << s.value;
      out << YAML::Key << "fill" << YAML::Value << s.fill;
      if (s.type == ZoneShapeType::Circle)
      {
        out << YAML::Key << "center" << YAML::Value;
        emitPoint(out, s.center);
        out << YAML::Key << "radius" << YAML::Value << s.radius;
      }
      else
      {
        out << YAML::Key << "points" << YAML::Value << YAML::BeginSeq;
        for (const auto& p : s.points)
          emitPoint(out, p);
        out << YAML::EndSeq;
      }
      out << YAML::EndMap;
    }
    out << YAML::EndSeq;
  }
  out << YAML::EndMap;
  if (!out.good()) throw std::logic_error("zoneLayoutToYaml: the YAML emitter failed: " + out.GetLastError());
  return std::string(out.c_str()) + "\n";
}

ZoneLayout loadZoneFile(const std::string& path)
{
  return parseZoneLayout(loadOwnFormatYamlFile(path), "'" + path + "'");
}

std::optional<ZoneLayout> loadIfZoneFile(const std::string& path)
{
  std::vector<std::string> repeated;
  const ParamValue tree = loadParamsYamlFile(path, kMaxParamsYamlBytes, false, &repeated);
  if (!tree.isMap() || tree.find("shapes") == nullptr) return std::nullopt;
  refuseRepeatedKeys(repeated);  // this package's own format: a lost value refuses the file
  return parseZoneLayout(tree, "'" + path + "'");
}

void saveZoneFile(const std::string& path, const ZoneLayout& layout)
{
  const InputError error = validateLayout(layout);
  if (!error.ok()) throw std::runtime_error("'" + path + "': not saved: " + error.message);
  const std::string text = zoneLayoutToYaml(layout);
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("'" + tmp + "': cannot be written: " + std::strerror(errno));
    out << text;
    out.flush();
    if (!out)
    {
      std::remove(tmp.c_str());
      throw std::runtime_error("'" + tmp + "': writing failed: " + std::strerror(errno));
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
  {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    throw std::runtime_error("'" + path + "': cannot be replaced: " + why);
  }
}
}  // namespace io
}  // namespace costmap_layers
