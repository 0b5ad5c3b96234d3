#include "costmap_layers/io/zone_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "costmap_layers/io/param_yaml.hpp"

namespace costmap_layers
{
namespace io
{
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
