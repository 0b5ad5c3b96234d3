// No library or program of this package may name a plugin library (one that a package's plugin XML
// exports for pluginlib, such as costmap_2d's liblayers) in its DT_NEEDED. A plugin library the dynamic
// linker maps as a dependency is one class_loader later finds already open: it never registers its
// factories, and every plugin of that library fails to load ("no factory exists for it"), or loads
// depending on which plugin came first (issue 33: move_base could not create costmap_2d::ObstacleLayer
// once a bridged plugin had pulled liblayers in).
//
// COSTMAP_LAYERS_LINK_TARGETS names a file that CMake writes, one built file of this package per line.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{
/// The navigation stack's plugin libraries (costmap_2d, the planners, the recoveries) and this package's
/// own, named even when their XMLs are not installed where the scan below looks.
const std::set<std::string> kKnownPluginLibraries = {"liblayers.so",
                                                     "libnavfn.so",
                                                     "libglobal_planner.so",
                                                     "libcarrot_planner.so",
                                                     "libtrajectory_planner_ros.so",
                                                     "libdwa_local_planner.so",
                                                     "libclear_costmap_recovery.so",
                                                     "librotate_recovery.so",
                                                     "libmove_slow_and_clear.so",
                                                     "libcostmap_layers_plugins.so",
                                                     "libcostmap_layers_move_base.so"};

/// Plugin libraries a program may link because it calls their classes directly and never has pluginlib
/// load that library: test_bridge drives clear_costmap_recovery's ClearCostmapRecovery itself, and
/// bench_sensor_path derives from costmap_2d's ObstacleLayer and VoxelLayer (to time them beside this
/// package's layers on the same messages) and loads no plugin at all.
const std::map<std::string, std::set<std::string>> kAllowed = {{"test_bridge", {"libclear_costmap_recovery.so"}},
                                                               {"bench_sensor_path", {"liblayers.so"}}};

std::string readFile(const fs::path& path)
{
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// "lib/libnavfn" -> "libnavfn.so", "liblayers" -> "liblayers.so" (pluginlib adds the suffix).
std::string soName(const std::string& library_path)
{
  return fs::path(library_path).filename().string() + ".so";
}

/// The libraries that the plugin XMLs in dir (a package's share folder or this source tree) export.
void scanPluginXmls(const fs::path& dir, std::set<std::string>& libraries, std::set<std::string>& xmls)
{
  static const std::regex library(R"(<library\s+path\s*=\s*"([^"]+)\")");
  std::error_code ec;
  for (const auto& file : fs::directory_iterator(dir, ec))
  {
    if (file.path().extension() != ".xml") continue;
    const std::string text = readFile(file.path());
    bool any = false;
    for (std::sregex_iterator m(text.begin(), text.end(), library), end; m != end; ++m)
    {
      libraries.insert(soName((*m)[1]));
      any = true;
    }
    if (any) xmls.insert(file.path().string());
  }
}

/// Every plugin library this machine's ROS environment exports: the XMLs in <prefix>/share/<package>/ of
/// each prefix on CMAKE_PREFIX_PATH (the navigation underlay's packages are there), and this package's own.
std::set<std::string> scannedPluginLibraries(std::set<std::string>& xmls)
{
  std::set<std::string> libraries;
  scanPluginXmls(COSTMAP_LAYERS_SOURCE_DIR, libraries, xmls);
  const char* prefixes = std::getenv("CMAKE_PREFIX_PATH");
  std::istringstream list(prefixes != nullptr ? prefixes : "");
  std::string prefix;
  while (std::getline(list, prefix, ':'))
  {
    std::error_code ec;
    for (const auto& package : fs::directory_iterator(fs::path(prefix) / "share", ec))
      if (package.is_directory(ec)) scanPluginXmls(package.path(), libraries, xmls);
  }
  return libraries;
}

/// What the scan found, and the libraries named above.
std::set<std::string> pluginLibraries(std::set<std::string>& xmls)
{
  std::set<std::string> libraries = scannedPluginLibraries(xmls);
  libraries.insert(kKnownPluginLibraries.begin(), kKnownPluginLibraries.end());
  return libraries;
}

/// DT_NEEDED of file, as readelf -d reports it; fails the test when readelf does.
std::vector<std::string> needed(const std::string& file)
{
  std::vector<std::string> names;
  const std::string command = "readelf -d --wide '" + file + "' 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr)
  {
    ADD_FAILURE() << "cannot run " << command;
    return names;
  }
  std::string out;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr)
    out += buffer;
  const int status = pclose(pipe);
  EXPECT_EQ(status, 0) << command << ":\n" << out;
  static const std::regex line(R"(\(NEEDED\)\s+Shared library: \[([^\]]+)\])");
  for (std::sregex_iterator m(out.begin(), out.end(), line), end; m != end; ++m)
    names.push_back((*m)[1]);
  return names;
}

std::vector<std::string> builtFiles()
{
  std::vector<std::string> files;
  std::istringstream lines(readFile(COSTMAP_LAYERS_LINK_TARGETS));
  std::string file;
  while (std::getline(lines, file))
    if (!file.empty()) files.push_back(file);
  return files;
}
}  // namespace

TEST(PluginLinks, TheScanFindsCostmap2dsPluginLibrary)
{
  // The scan reads the XMLs of the environment this test runs in (costmap_2d is there: this test is
  // built only where it is), so it also finds plugin libraries the list above does not name.
  std::set<std::string> xmls;
  const std::set<std::string> libraries = scannedPluginLibraries(xmls);
  EXPECT_EQ(libraries.count("liblayers.so"), 1u);
  EXPECT_EQ(libraries.count("libcostmap_layers_move_base.so"), 1u);
  std::cout << "plugin XMLs read:\n";
  for (const auto& x : xmls)
    std::cout << "  " << x << "\n";
}

TEST(PluginLinks, NoFileOfThisPackageNeedsAPluginLibrary)
{
  std::set<std::string> xmls;
  const std::set<std::string> plugin_libraries = pluginLibraries(xmls);
  const std::vector<std::string> files = builtFiles();
  ASSERT_FALSE(files.empty()) << COSTMAP_LAYERS_LINK_TARGETS;
  int checked = 0;
  for (const auto& file : files)
  {
    const fs::path path(file);
    const bool library = path.extension() == ".so";
    if (!fs::exists(path))
    {
      // Libraries are built before this test (a dependency in CMake); a program that is not built yet
      // (a test executable built only by `make tests`) is said, not failed.
      EXPECT_FALSE(library) << file << " is not built";
      std::cout << "not built, not checked: " << file << "\n";
      continue;
    }
    ++checked;
    const std::string self = path.filename().string();
    const auto allowed = kAllowed.find(path.stem().string());
    for (const auto& name : needed(file))
    {
      if (name == self || plugin_libraries.count(name) == 0) continue;
      if (allowed != kAllowed.end() && allowed->second.count(name) != 0) continue;
      ADD_FAILURE() << file << " has the plugin library " << name
                    << " in its DT_NEEDED: pluginlib could then not load that library's classes (issue 33); "
                       "link the package's core library instead";
    }
  }
  std::cout << checked << " of " << files.size() << " files checked against " << plugin_libraries.size()
            << " plugin libraries\n";
  EXPECT_GT(checked, 0);
}
