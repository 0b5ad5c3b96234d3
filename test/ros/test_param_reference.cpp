// The generated parameter reference (costmap_tool --describe-params): docs/parameters.md must be what
// the code declares today, and what it declares must be the parse functions' own names, defaults and
// ranges. Expected rows are written here by hand from costmap_2d's and Nav2's documented defaults.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "tool_runner.hpp"

using costmap_layers_test::readFile;
using costmap_layers_test::runTool;
using costmap_layers_test::TempDir;

namespace
{
/// The first line where a and b differ, numbered from 1, with both texts; "" when equal.
std::string firstDifference(const std::string& a, const std::string& b)
{
  std::istringstream ia(a), ib(b);
  std::string la, lb;
  for (int n = 1;; ++n)
  {
    const bool ra = static_cast<bool>(std::getline(ia, la)), rb = static_cast<bool>(std::getline(ib, lb));
    if (!ra && !rb) return "";
    if (!ra || !rb || la != lb)
      return "line " + std::to_string(n) + ":\n  committed: " + (ra ? la : "(end of file)") +
             "\n  generated: " + (rb ? lb : "(end of output)");
  }
}
}  // namespace

TEST(ParamReference, TheCommittedReferenceIsWhatTheCodeDeclares)
{
  TempDir dir;
  const auto r = runTool({"--describe-params", "--markdown"}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string committed = readFile(std::string(COSTMAP_LAYERS_SOURCE_DIR) + "/docs/parameters.md");
  ASSERT_FALSE(committed.empty()) << "docs/parameters.md is missing";
  EXPECT_EQ(firstDifference(committed, r.out), "")
      << "docs/parameters.md differs from what the parse functions declare: regenerate it with "
         "scripts/dev/make_reference.sh (costmap_tool --describe-params --markdown > docs/parameters.md)";
}

TEST(ParamReference, RowsComeFromTheParseFunctions)
{
  TempDir dir;
  const auto r = runTool({"--describe-params", "--markdown"}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // costmap_2d's defaults (inflation 0.55 m, factor 10; a static layer on "map" with lethal 100), Nav2's
  // filter mask default of this package (/map_filter), and a source parameter of the obstacle layer.
  for (const char* row : {
           "| `inflation_radius` | double | 0.55 | [0, 10000] |",
           "| `cost_scaling_factor` | double | 10 | >= 0 |",
           "| `map_topic` | topic | \"map\" |  |",
           "| `lethal_cost_threshold` | int | 100 |  |",
           "| `global_frame` | frame id | \"map\" |  |",
           "| `<source>/data_type` | string | \"PointCloud2\" | one of LaserScan, PointCloud2, PointCloud |",
           "| `<source>/raytrace_max_range` | double | 3 | [0, 10000] |",
           "| `z_voxels` | int | 10 | [1, 16] |",
           "| subscribes | mask | `/map_filter` | `nav_msgs/OccupancyGrid` |",
           "| publishes | speed limit in force | `/max_speed` | `costmap_layers/MaxSpeed` |",
           "| subscribes | point clouds | each source's `topic` | `sensor_msgs/PointCloud2` |",
       })
    EXPECT_NE(r.out.find(row), std::string::npos) << "missing row: " << row;
  // Every plugin of the plugin description file has its section, and every filter its switch.
  for (const char* type :
       {"AsymmetricInflationLayer", "BinaryFilter", "DenoiseLayer", "GradientLayer", "InflationLayer", "KeepoutFilter", "LanesFilter", "ObstacleLayer", "PluginContainerLayer",
        "RangeSensorLayer", "SpeedFilter", "StaticLayer", "VoxelLayer", "ZoneParameterFilter"})
    EXPECT_NE(r.out.find(std::string("\n## costmap_layers/") + type + "\n"), std::string::npos) << type;
  std::size_t toggles = 0;
  for (std::size_t at = r.out.find("`~<name>/toggle_filter`"); at != std::string::npos;
       at = r.out.find("`~<name>/toggle_filter`", at + 1))
    ++toggles;
  EXPECT_EQ(toggles, 5u);  // Binary, Keepout, Lanes, Speed, ZoneParameter
}

TEST(ParamReference, TextFormAndBadArguments)
{
  TempDir dir;
  const auto text = runTool({"--describe-params"}, dir);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("  inflation_radius (double) default 0.55, [0, 10000]\n"), std::string::npos);
  for (const std::vector<std::string>& args : {std::vector<std::string>{"--describe-params", "--html"},
                                               std::vector<std::string>{"--describe-params", "--markdown", "extra"}})
  {
    const auto bad = runTool(args, dir);
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_EQ(bad.err.find("costmap_tool: --describe-params takes only --markdown"), 0u) << bad.err;
    EXPECT_EQ(bad.out, "");
  }
}
