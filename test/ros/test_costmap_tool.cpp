// costmap_tool through its real command line: the gradient on any map, the JSON line, the raw output,
// namespaces, masks, repeats, and one clear line for each kind of bad input.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>

#include "tool_runner.hpp"

using namespace costmap_layers_test;

namespace
{
const std::string kGradientParams = R"(
plugins:
  - {name: gradient_layer, type: costmap_layers/GradientLayer}
)";

/// The tutorial's rule, written out independently: along each row from the window's first column,
/// k = 0, 1, ..., size + 1, 0, ...; cost = (254 - k * factor) % 255 in C int arithmetic.
std::vector<uint8_t> expectedGradient(int w, int h, int size, int factor)
{
  std::vector<uint8_t> cells;
  for (int j = 0; j < h; ++j)
  {
    int k = 0;
    for (int i = 0; i < w; ++i)
    {
      const int c = (254 - k * factor) % 255;
      cells.push_back(static_cast<uint8_t>(c));
      k = (k == size + 1) ? 0 : k + 1;
    }
  }
  return cells;
}

/// The tool's JSON line, parsed (a parse error fails the test with the line).
nlohmann::json jsonOf(const ToolResult& r)
{
  const std::string line = r.lastLine();
  nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
  EXPECT_FALSE(j.is_discarded()) << "not JSON: " << line;
  EXPECT_TRUE(j.is_object()) << line;
  return j.is_object() ? j : nlohmann::json::object();
}

std::vector<uint8_t> rawCells(const std::string& path)
{
  const std::string bytes = readFile(path);
  return std::vector<uint8_t>(bytes.begin(), bytes.end());
}

/// Real maps copied into the repository (sources and licences in test/data/README.md).
std::string realMaps()
{
  return std::string(COSTMAP_LAYERS_SOURCE_DIR) + "/test/data/maps";
}
}  // namespace

TEST(CostmapTool, GradientOnGeneratedMapIsExact)
{
  TempDir dir;
  const std::string map = writeMap(dir, "map", 57, 31, std::vector<uint8_t>(57 * 31, 254), 0.1, -1.0, 2.0);
  const std::string params = dir.write("params.yaml", kGradientParams);
  const ToolResult r = runTool({"--map", map, "--params", params, "--out-raw", dir.file("out.raw")}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(rawCells(dir.file("out.raw")), expectedGradient(57, 31, 20, 10));
  const nlohmann::json j = jsonOf(r);
  EXPECT_EQ(j.value("width", -1), 57);
  EXPECT_EQ(j.value("height", -1), 31);
  EXPECT_DOUBLE_EQ(j.value("resolution", 0.0), 0.1);
  EXPECT_DOUBLE_EQ(j.value("origin_x", 0.0), -1.0);
  EXPECT_DOUBLE_EQ(j.value("origin_y", 0.0), 2.0);
  ASSERT_TRUE(j.contains("update_ms_median") && j["update_ms_median"].is_number()) << j;
  ASSERT_TRUE(j.contains("update_ms_min") && j["update_ms_min"].is_number()) << j;
  EXPECT_LE(j["update_ms_min"].get<double>(), j["update_ms_median"].get<double>());
  EXPECT_EQ(j.value("repeats", -1), 1);
  EXPECT_EQ(j["max_speed"], nlohmann::json::object());
}

TEST(CostmapTool, GradientOnRealMapsIsExact)
{
  for (const std::string name : {"turtlebot3_world", "depot", "willow-full-0.1"})
  {
    const std::string map = realMaps() + "/" + name + ".yaml";
    ASSERT_TRUE(std::filesystem::exists(map)) << map;
    TempDir dir;
    const std::string params = dir.write("params.yaml", kGradientParams +
                                                            "gradient_layer: {gradient_size: 7, "
                                                            "gradient_factor: 30}\n");
    const ToolResult r = runTool({"--map", map, "--params", params, "--out-raw", dir.file("out.raw")}, dir);
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    const nlohmann::json j = jsonOf(r);
    const int w = j.value("width", -1), h = j.value("height", -1);
    EXPECT_GT(w, 100) << name;
    EXPECT_EQ(rawCells(dir.file("out.raw")), expectedGradient(w, h, 7, 30)) << name;
  }
}

TEST(CostmapTool, RepeatReportsTimesAndKeepsTheResult)
{
  TempDir dir;
  const std::string map = writeMap(dir, "map", 40, 20, std::vector<uint8_t>(800, 254), 0.05, 0.0, 0.0);
  const std::string params = dir.write("params.yaml", kGradientParams);
  const ToolResult r =
      runTool({"--map", map, "--params", params, "--repeat", "5", "--out-raw", dir.file("out.raw")}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = jsonOf(r);
  EXPECT_EQ(j.value("repeats", -1), 5);
  EXPECT_GT(j.value("update_ms_median", -1.0), 0.0);
  EXPECT_LE(j.value("update_ms_min", 1e9), j.value("update_ms_median", -1.0));
  EXPECT_EQ(rawCells(dir.file("out.raw")), expectedGradient(40, 20, 20, 10));
}

TEST(CostmapTool, NamespacePicksASubKeyAndPngIsWritten)
{
  TempDir dir;
  const std::string map = writeMap(dir, "map", 30, 10, std::vector<uint8_t>(300, 254), 1.0, 0.0, 0.0);
  const std::string params = dir.write("params.yaml", R"(
local_costmap:
  costmap:
    plugins: [{name: g, type: costmap_layers/GradientLayer}]
    g: {gradient_size: 2, gradient_factor: 100}
)");
  const ToolResult r = runTool({"--map", map, "--params", params, "--namespace", "local_costmap/costmap", "--out-raw",
                                dir.file("out.raw"), "--out-png", dir.file("out.png")},
                               dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // k = 0..3: 254, 154, 54, (254 - 300) % 255 = -46 -> 210 as an unsigned char.
  const auto cells = rawCells(dir.file("out.raw"));
  ASSERT_EQ(cells.size(), 300u);
  EXPECT_EQ(std::vector<uint8_t>(cells.begin(), cells.begin() + 5), (std::vector<uint8_t>{254, 154, 54, 210, 254}));
  EXPECT_EQ(cells, expectedGradient(30, 10, 2, 100));
  const std::string png = readFile(dir.file("out.png"));
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST(CostmapTool, KeepoutMaskIsAppliedToTheNamedFilter)
{
  TempDir dir;
  const std::string map = writeMap(dir, "map", 10, 10, std::vector<uint8_t>(100, 254), 1.0, 0.0, 0.0);
  // Mask: image top row is the highest y. Black (0) = occupied 100 in trinary mode.
  std::vector<uint8_t> mask_pixels(100, 254);
  mask_pixels[(9 - 3) * 10 + 4] = 0;  // cell (4, 3)
  const std::string mask = writeMap(dir, "mask", 10, 10, mask_pixels, 1.0, 0.0, 0.0);
  const std::string params = dir.write("params.yaml", R"(
plugins: [{name: g, type: costmap_layers/GradientLayer}]
filters: [{name: keepout, type: costmap_layers/KeepoutFilter}]
g: {gradient_factor: 0}
)");
  const ToolResult r =
      runTool({"--map", map, "--params", params, "--mask", "keepout=" + mask, "--out-raw", dir.file("out.raw")}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto cells = rawCells(dir.file("out.raw"));
  ASSERT_EQ(cells.size(), 100u);
  for (int k = 0; k < 100; ++k)
    EXPECT_EQ(cells[static_cast<std::size_t>(k)], 254) << k;  // gradient factor 0: all 254
  // Now with a gradient that leaves room to see the filter: factor 10 puts 214 at x = 4.
  dir.write("params.yaml", R"(
plugins: [{name: g, type: costmap_layers/GradientLayer}]
filters: [{name: keepout, type: costmap_layers/KeepoutFilter}]
)");
  const ToolResult r2 =
      runTool({"--map", map, "--params", params, "--mask", "keepout=" + mask, "--out-raw", dir.file("out.raw")}, dir);
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  const auto cells2 = rawCells(dir.file("out.raw"));
  auto expected = expectedGradient(10, 10, 20, 10);
  expected[3 * 10 + 4] = 254;
  EXPECT_EQ(cells2, expected);
}

TEST(CostmapTool, FilterInNav2FormTakesItsInfoFromTheCommandLine)
{
  TempDir dir;
  const std::string map = writeMap(dir, "map", 10, 10, std::vector<uint8_t>(100, 254), 1.0, 0.0, 0.0);
  std::vector<uint8_t> mask_pixels(100, 254);
  mask_pixels[(9 - 3) * 10 + 4] = 0;  // cell (4, 3)
  const std::string mask = writeMap(dir, "mask", 10, 10, mask_pixels, 1.0, 0.0, 0.0);
  const std::string params = dir.write("params.yaml", R"(
plugins: [{name: g, type: costmap_layers/GradientLayer}]
filters: ["keepout"]
keepout: {plugin: "nav2_costmap_2d::KeepoutFilter", filter_info_topic: /costmap_filter_info}
)");
  const ToolResult r = runTool({"--map", map, "--params", params, "--filter-info", "keepout=0,0,1", "--mask",
                                "keepout=" + mask, "--out-raw", dir.file("out.raw")},
                               dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto expected = expectedGradient(10, 10, 20, 10);
  expected[3 * 10 + 4] = 254;
  EXPECT_EQ(rawCells(dir.file("out.raw")), expected);

  // Without the info the mask means nothing to this filter: refused, saying what is missing.
  const ToolResult no_info =
      runTool({"--map", map, "--params", params, "--mask", "keepout=" + mask, "--out-raw", dir.file("out.raw")}, dir);
  EXPECT_NE(no_info.exit_code, 0);
  EXPECT_NE(no_info.err.find("--filter-info keepout=TYPE,BASE,MULTIPLIER"), std::string::npos) << no_info.err;
  // An info the filter cannot use (a speed type) is reported, and the tool fails on reported errors.
  const ToolResult wrong = runTool({"--map", map, "--params", params, "--filter-info", "keepout=1,100,-1", "--mask",
                                    "keepout=" + mask, "--out-raw", dir.file("out.raw")},
                                   dir);
  EXPECT_NE(wrong.exit_code, 0);
  EXPECT_NE(wrong.err.find("type 1"), std::string::npos) << wrong.err;
}

TEST(CostmapTool, ZoomAndLabelsShapeThePictureAndBadOnesAreRefused)
{
  TempDir dir;
  const std::string map = writeMap(dir, "map", 120, 10, std::vector<uint8_t>(1200, 254), 0.5, -2.0, 1.0);
  const std::string params = dir.write("params.yaml", kGradientParams);
  // The map spans x -2..58 and y 1..6 m; a label at each corner and one with commas in its text.
  const ToolResult ok = runTool({"--map", map, "--params", params, "--out-png", dir.file("z.png"), "--zoom", "3",
                                 "--label", "-2,1,low left", "--label", "58,6,high right", "--label",
                                 "5.5,3.5,a, b, c"},
                                dir);
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const std::string png = readFile(dir.file("z.png"));
  ASSERT_GT(png.size(), 24u);
  auto be32 = [&](size_t at)
  {
    return (static_cast<uint32_t>(static_cast<uint8_t>(png[at])) << 24) |
           (static_cast<uint32_t>(static_cast<uint8_t>(png[at + 1])) << 16) |
           (static_cast<uint32_t>(static_cast<uint8_t>(png[at + 2])) << 8) | static_cast<uint8_t>(png[at + 3]);
  };
  EXPECT_EQ(be32(16), 360u);  // IHDR width: 120 cells at zoom 3 (the legend fits in that width)
  EXPECT_GT(be32(20), 30u);   // IHDR height: 10 cells at zoom 3, and the legend band below
  struct Case
  {
    std::vector<std::string> args;
    std::string needle;
  };
  const std::vector<Case> cases = {
      {{"--zoom", "2"}, "give --out-png FILE too"},
      {{"--label", "1,2,x"}, "give --out-png FILE too"},
      {{"--out-png", dir.file("a.png"), "--zoom", "9"}, "--zoom expects a whole number in 1..8 (got \"9\")"},
      {{"--out-png", dir.file("a.png"), "--zoom", "2.5"}, "(got \"2.5\")"},
      {{"--out-png", dir.file("a.png"), "--label", "1,2"}, "--label expects X,Y,TEXT"},
      {{"--out-png", dir.file("a.png"), "--label", "1,2,"}, "--label expects X,Y,TEXT"},
      {{"--out-png", dir.file("a.png"), "--label", "nan,2,x"}, "--label expects X,Y,TEXT"},
      {{"--out-png", dir.file("a.png"), "--label", "1e8,2,x"}, "--label expects X,Y,TEXT"},
      {{"--out-png", dir.file("a.png"), "--label", "58.1,3,east"},
       "--label \"east\": (58.1, 3) is outside the costmap, which spans x -2..58 and y 1..6 m"},
      {{"--out-png", dir.file("a.png"), "--label", "0,0.9,south"}, "is outside the costmap"},
      {{"--out-png", dir.file("a.png"), "--label", "1,2,dock #1"}, "the character '#' has no glyph"},
  };
  for (const auto& c : cases)
  {
    std::vector<std::string> args = {"--map", map, "--params", params};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const ToolResult r = runTool(args, dir);
    EXPECT_NE(r.exit_code, 0) << c.needle;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << "stderr was: " << r.err;
    EXPECT_EQ(r.out, "") << c.needle;
    EXPECT_FALSE(std::filesystem::exists(dir.file("a.png"))) << c.needle;
  }
}

TEST(CostmapTool, BadInputGivesOneClearLineAndNonZeroExit)
{
  TempDir dir;
  const std::string map = writeMap(dir, "map", 10, 10, std::vector<uint8_t>(100, 254), 1.0, 0.0, 0.0);
  const std::string params = dir.write("params.yaml", kGradientParams);
  const std::string bad_yaml = dir.write("bad.yaml", "plugins: [ {name: a, type: \n  - : :\n");
  const std::string unknown = dir.write("unknown.yaml", "plugins: [{name: x, type: costmap_layers/NoSuchLayer}]\n");
  const std::string bad_image = dir.write(
      "bad_image.yaml",
      "image: nothing.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
  dir.write("nothing.pgm", "P5\n10 10\n255\nabc");

  struct Case
  {
    std::vector<std::string> args;
    std::string needle;
  };
  const std::vector<Case> cases = {
      {{"--map", dir.file("missing.yaml"), "--params", params}, "missing.yaml"},
      {{"--map", map, "--params", dir.file("missing_params.yaml")}, "missing_params.yaml"},
      {{"--map", map, "--params", bad_yaml}, "bad.yaml"},
      {{"--map", map, "--params", unknown}, "unknown plugin type 'costmap_layers/NoSuchLayer'"},
      {{"--map", bad_image, "--params", params}, "nothing.pgm"},
      {{"--map", map, "--params", params, "--pose", "1,2"}, "--pose"},
      {{"--map", map, "--params", params, "--repeat", "0"}, "--repeat"},
      {{"--map", map, "--params", params, "--mask", "nobody=" + map}, "nobody"},
      {{"--map", map, "--params", params, "--namespace", "nowhere"}, "nowhere"},
      {{"--map", map}, "--params is required"},
      {{"--map", map, "--params", params, "--frobnicate", "1"}, "unknown option --frobnicate"},
  };
  for (const auto& c : cases)
  {
    const ToolResult r = runTool(c.args, dir);
    EXPECT_NE(r.exit_code, 0) << c.needle;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << "stderr was: " << r.err;
    EXPECT_EQ(r.err.find("costmap_tool"), 0u) << r.err;
    EXPECT_EQ(r.out, "") << c.needle;  // no JSON line on failure
  }
  // The unknown type's error lists what is available.
  const ToolResult r = runTool({"--map", map, "--params", unknown}, dir);
  EXPECT_NE(r.err.find("costmap_layers/GradientLayer"), std::string::npos) << r.err;
}

// Numbers at the edge and inputs a layer refuses: every path that prints an error exits non-zero and
// writes no result. The limits are written as numbers here: resolution [1e-4, 1e3] m/pixel,
// |pose x/y| <= 1e7 m, |yaw| <= 1e3 rad, update_frequency [1e-3, 1e3] Hz.
TEST(CostmapTool, NumbersAtTheEdgeAndRefusedInputsExitNonZero)
{
  TempDir dir;
  const std::string map = writeMap(dir, "map", 10, 10, std::vector<uint8_t>(100, 254), 1.0, 0.0, 0.0);
  const std::string params = dir.write("params.yaml", kGradientParams);
  const std::string tiny = writeMap(dir, "tiny", 4, 4, std::vector<uint8_t>(16, 254), 1e-300, 0.0, 0.0);
  const std::string huge_res = writeMap(dir, "huge_res", 4, 4, std::vector<uint8_t>(16, 254), 1e300, 0.0, 0.0);
  const std::string far = writeMap(dir, "far", 4, 4, std::vector<uint8_t>(16, 254), 0.05, 1e300, 0.0);
  const std::string slow = dir.write("slow.yaml", kGradientParams + "update_frequency: 1e-10\n");
  const std::string speed_params = dir.write("speed.yaml", R"(
plugins: [{name: g, type: costmap_layers/GradientLayer}]
filters: [{name: speed, type: costmap_layers/SpeedFilter}]
)");
  // An entry the SpeedFilter drops (max_speed < 0): reported as an error, so the tool must fail.
  const std::string bad_limits = dir.write("limits.yaml", "limits: [{area_id: 1, max_speed: -1.0}]\n");
  const std::string good_limits = dir.write("good_limits.yaml", "limits: [{area_id: 1, max_speed: 0.5}]\n");
  std::filesystem::create_directory(dir.file("adir"));

  struct Case
  {
    std::vector<std::string> args;
    std::string needle;
  };
  const std::vector<Case> cases = {
      {{"--map", tiny, "--params", params}, "resolution"},
      {{"--map", huge_res, "--params", params}, "resolution"},
      {{"--map", far, "--params", params}, "origin x"},
      {{"--map", map, "--params", speed_params, "--mask", "speed=" + tiny}, "resolution"},
      {{"--map", map, "--params", slow}, "update_frequency"},
      {{"--map", map, "--params", params, "--pose", "1e300,0,0"}, "--pose"},
      {{"--map", map, "--params", params, "--pose", "0,-10000001,0"}, "--pose"},
      {{"--map", map, "--params", params, "--pose", "0,0,1e300"}, "--pose"},
      {{"--map", map, "--params", dir.file("adir")}, "directory"},
      {{"--map", map, "--params", "/dev/zero"}, "character device"},
      {{"--map", map, "--params", speed_params, "--features", "speed=" + bad_limits}, "max_speed"},
  };
  for (const auto& c : cases)
  {
    const ToolResult r = runTool(c.args, dir);
    EXPECT_NE(r.exit_code, 0) << c.needle << ": " << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << "stderr was: " << r.err;
    EXPECT_EQ(r.err.find("costmap_tool"), 0u) << r.err;
    EXPECT_EQ(r.out, "") << c.needle;  // no JSON line on failure
  }
  // The error summary says why nothing was written.
  const ToolResult dropped = runTool(
      {"--map", map, "--params", speed_params, "--features", "speed=" + bad_limits, "--out-raw", dir.file("o.raw")},
      dir);
  EXPECT_EQ(dropped.exit_code, 1) << dropped.err;
  EXPECT_NE(dropped.err.find("no result written"), std::string::npos) << dropped.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("o.raw")));
  // The ends of the ranges are accepted, and valid limits leave the exit status at 0.
  const std::string edge = writeMap(dir, "edge", 4, 4, std::vector<uint8_t>(16, 254), 1e-4, 1e7, -1e7);
  const ToolResult ok = runTool({"--map", edge, "--params", params, "--pose", "1e7,-1e7,1000"}, dir);
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  const ToolResult ok2 = runTool({"--map", map, "--params", speed_params, "--features", "speed=" + good_limits}, dir);
  EXPECT_EQ(ok2.exit_code, 0) << ok2.err;
}

#include <cmath>

#include "costmap_layers/io/map_file.hpp"

namespace
{
/// costmap_2d's static interpretation (default parameters, tracking unknown space) followed by the
/// inflation rule applied naively: for every cell, the nearest lethal cell within the radius found by
/// looking at every cell of the disc around it.
std::vector<uint8_t> bruteForceStaticInflation(const costmap_layers::OccupancyGridData& map, double radius,
                                               double factor, double inscribed)
{
  const int w = static_cast<int>(map.width), h = static_cast<int>(map.height);
  std::vector<uint8_t> master(map.data.size());
  for (std::size_t k = 0; k < master.size(); ++k)
  {
    const int v = map.data[k];
    master[k] = v == -1 ? 255 : (v >= 100 ? 254 : 0);  // trinary: below the threshold is free
  }
  const int r = static_cast<int>(std::ceil(radius / map.resolution));
  std::vector<uint8_t> out = master;
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      int best = -1;
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx)
        {
          const int sx = x + dx, sy = y + dy;
          if (sx < 0 || sy < 0 || sx >= w || sy >= h || master[static_cast<std::size_t>(sy * w + sx)] != 254) continue;
          const int d2 = dx * dx + dy * dy;
          if (d2 <= r * r && (best < 0 || d2 < best)) best = d2;
        }
      if (best < 0) continue;
      const double d = std::sqrt(static_cast<double>(best));
      uint8_t cost;
      if (best == 0)
        cost = 254;
      else if (d * map.resolution <= inscribed)
        cost = 253;
      else
        cost = static_cast<uint8_t>(252 * std::exp(-factor * (d * map.resolution - inscribed)));
      uint8_t& cell = out[static_cast<std::size_t>(y * w + x)];
      if (cell == 255)
        cell = cost >= 253 ? cost : cell;
      else
        cell = std::max(cell, cost);
    }
  }
  return out;
}
}  // namespace

TEST(CostmapTool, StaticPlusInflationOnRealMapsEqualsBruteForce)
{
  const std::string params_text = R"(
track_unknown_space: true
footprint: [[0.22, 0.22], [0.22, -0.22], [-0.22, -0.22], [-0.22, 0.22]]
footprint_padding: 0.0
plugins:
  - {name: static_layer, type: costmap_layers/StaticLayer}
  - {name: inflation_layer, type: costmap_layers/InflationLayer}
inflation_layer: {inflation_radius: 0.55, cost_scaling_factor: 10.0}
)";
  for (const std::string name : {"turtlebot3_world", "tb3_sandbox", "depot", "willow-full-0.1"})
  {
    const std::string map = realMaps() + "/" + name + ".yaml";
    ASSERT_TRUE(std::filesystem::exists(map)) << map;
    TempDir dir;
    const std::string params = dir.write("params.yaml", params_text);
    const ToolResult r = runTool({"--map", map, "--params", params, "--out-raw", dir.file("out.raw")}, dir);
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    const auto grid = costmap_layers::io::loadMapFile(map);
    const auto expected = bruteForceStaticInflation(grid, 0.55, 10.0, 0.22);
    const auto got = rawCells(dir.file("out.raw"));
    ASSERT_EQ(got.size(), expected.size()) << name;
    std::size_t mismatches = 0, first = 0;
    for (std::size_t k = 0; k < got.size(); ++k)
      if (got[k] != expected[k] && mismatches++ == 0) first = k;
    EXPECT_EQ(mismatches, 0u) << name << ": first mismatch at cell " << first << " (got " << int(got[first])
                              << ", expected " << int(expected[first]) << ")";
    // The maps really exercise the rule: lethal, inscribed, graded and unknown cells all occur.
    std::size_t counts[4] = {0, 0, 0, 0};
    for (uint8_t c : got)
      ++counts[c == 254 ? 0 : c == 253 ? 1 : (c > 0 && c < 253) ? 2 : c == 255 ? 3 : 0];
    EXPECT_GT(counts[1], 0u) << name;
    EXPECT_GT(counts[2], 0u) << name;
  }
}

// The command line (CLI11): each option once, --mask and --features once per plugin name, -h.
TEST(CostmapTool, OptionsGivenTwiceAreRefusedExceptPerPluginOnes)
{
  TempDir dir;
  const std::string map = writeMap(dir, "map", 10, 10, std::vector<uint8_t>(100, 254), 1.0, 0.0, 0.0);
  const std::string params = dir.write("params.yaml", kGradientParams);
  const std::string two_filters = dir.write("filters.yaml", R"(
plugins: [{name: g, type: costmap_layers/GradientLayer}]
filters:
  - {name: keepout_a, type: costmap_layers/KeepoutFilter}
  - {name: keepout_b, type: costmap_layers/KeepoutFilter}
)");
  for (const std::string flag : {"--map", "--params", "--namespace", "--pose", "--repeat", "--out-raw", "--out-png"})
  {
    std::vector<std::string> args = {"--map", map, "--params", params};
    const std::map<std::string, std::string> values = {{"--map", map},
                                                       {"--params", params},
                                                       {"--namespace", "ns"},
                                                       {"--pose", "1,1,0"},
                                                       {"--repeat", "2"},
                                                       {"--out-raw", dir.file("o.raw")},
                                                       {"--out-png", dir.file("o.png")}};
    const std::string value = values.at(flag);
    if (flag != "--map" && flag != "--params")
    {
      args.push_back(flag);
      args.push_back(value);
    }
    args.push_back(flag);
    args.push_back(value);
    const ToolResult r = runTool(args, dir);
    EXPECT_EQ(r.exit_code, 2) << flag << ": " << r.err;
    EXPECT_EQ(r.err.find("costmap_tool: " + flag), 0u) << r.err;
    EXPECT_EQ(r.out, "") << flag;
  }
  // Two masks for two filters: fine. The same filter twice: refused, naming the flag and the plugin.
  const std::string mask = writeMap(dir, "mask", 10, 10, std::vector<uint8_t>(100, 254), 1.0, 0.0, 0.0);
  const ToolResult ok = runTool(
      {"--map", map, "--params", two_filters, "--mask", "keepout_a=" + mask, "--mask", "keepout_b=" + mask}, dir);
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(jsonOf(ok).value("width", -1), 10);
  const ToolResult twice = runTool(
      {"--map", map, "--params", two_filters, "--mask", "keepout_a=" + mask, "--mask", "keepout_a=" + mask}, dir);
  EXPECT_EQ(twice.exit_code, 2) << twice.err;
  EXPECT_NE(twice.err.find("--mask names plugin 'keepout_a' twice"), std::string::npos) << twice.err;
  const ToolResult features_twice =
      runTool({"--map", map, "--params", params, "--features", "s=a.yaml", "--features", "s=b.yaml"}, dir);
  EXPECT_EQ(features_twice.exit_code, 2) << features_twice.err;
  EXPECT_NE(features_twice.err.find("--features names plugin 's' twice"), std::string::npos) << features_twice.err;
  // Missing values and stray words are usage errors too; -h prints the options and succeeds.
  const ToolResult no_value = runTool({"--params", params, "--map"}, dir);
  EXPECT_EQ(no_value.exit_code, 2) << no_value.err;
  EXPECT_NE(no_value.err.find("--map"), std::string::npos) << no_value.err;
  const ToolResult stray = runTool({"--map", map, "--params", params, "stray"}, dir);
  EXPECT_EQ(stray.exit_code, 2) << stray.err;
  EXPECT_NE(stray.err.find("stray"), std::string::npos) << stray.err;
  const ToolResult bad_mask = runTool({"--map", map, "--params", params, "--mask", "nofile"}, dir);
  EXPECT_EQ(bad_mask.exit_code, 2) << bad_mask.err;
  EXPECT_NE(bad_mask.err.find("--mask expects PLUGIN_NAME=FILE"), std::string::npos) << bad_mask.err;
  const ToolResult help = runTool({"--help"}, dir);
  EXPECT_EQ(help.exit_code, 0) << help.err;
  for (const std::string flag :
       {"--map", "--params", "--namespace", "--mask", "--features", "--pose", "--repeat", "--out-raw", "--out-png"})
    EXPECT_NE(help.out.find(flag), std::string::npos) << flag << " missing from:\n" << help.out;
}

// A rolling costmap: the tool writes the window of the configured size centred on --pose, as
// costmap_node publishes it. The expected window is read straight off the map's pixels: window cell
// (i, j) is map cell (i + 5, j + 5), whose pixel is in image row (h - 1 - (j + 5)).
TEST(CostmapTool, RollingWindowAroundThePose)
{
  TempDir dir;
  const int w = 20, h = 16;
  std::vector<uint8_t> pixels(static_cast<std::size_t>(w * h));
  for (int row = 0; row < h; ++row)
    for (int col = 0; col < w; ++col)
    {
      // Occupied (0), free (254) and unknown (205) cells in a pattern no shift or flip maps onto itself.
      const int k = (col * 7 + row * 3 + (col * row) % 5) % 6;
      pixels[static_cast<std::size_t>(row * w + col)] = k == 0 ? 0 : k == 1 ? 205 : 254;
    }
  const std::string map = writeMap(dir, "map", w, h, pixels, 1.0, 0.0, 0.0);
  const std::string params = dir.write("params.yaml", R"(
rolling_window: true
width: 6
height: 4
resolution: 1.0
track_unknown_space: true
plugins: [{name: static_layer, type: costmap_layers/StaticLayer}]
)");
  // The robot at (8, 7): the window's origin is (8 - 3, 7 - 2) = (5, 5).
  const ToolResult r =
      runTool({"--map", map, "--params", params, "--pose", "8,7,0", "--out-raw", dir.file("out.raw")}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = jsonOf(r);
  EXPECT_EQ(j.value("width", -1), 6);
  EXPECT_EQ(j.value("height", -1), 4);
  EXPECT_DOUBLE_EQ(j.value("origin_x", -1.0), 5.0);
  EXPECT_DOUBLE_EQ(j.value("origin_y", -1.0), 5.0);
  std::vector<uint8_t> expected;
  for (int wj = 0; wj < 4; ++wj)
    for (int wi = 0; wi < 6; ++wi)
    {
      const uint8_t px = pixels[static_cast<std::size_t>((h - 1 - (wj + 5)) * w + (wi + 5))];
      expected.push_back(px == 0 ? 254 : px == 205 ? 255 : 0);  // lethal, unknown, free
    }
  EXPECT_EQ(rawCells(dir.file("out.raw")), expected);
  // The not-rolling twin of the same files writes the whole map.
  const std::string whole = dir.write("whole.yaml", R"(
track_unknown_space: true
plugins: [{name: static_layer, type: costmap_layers/StaticLayer}]
)");
  const ToolResult r2 = runTool({"--map", map, "--params", whole, "--pose", "8,7,0"}, dir);
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  EXPECT_EQ(jsonOf(r2).value("width", -1), w);
  EXPECT_EQ(jsonOf(r2).value("height", -1), h);
}

// The tool reads a costmap's namespace as costmap_node does (costmap_2d's rules): a pre-Hydro move_base
// file (no plugins: static_map, the inflation keys at the costmap level) with the footprint one level
// up (searchParam). Before, the tool built no layer from such a file and printed a free costmap.
TEST(CostmapTool, ReadsAMoveBaseFileAsCostmapNodeDoes)
{
  TempDir dir;
  std::vector<uint8_t> pixels(21 * 21, 254);
  pixels[10 * 21 + 10] = 0;  // one lethal cell in the middle
  const std::string map = writeMap(dir, "map", 21, 21, pixels, 0.1, 0.0, 0.0);
  const std::string params = dir.write("params.yaml", R"(
move_base:
  footprint: [[0.25, 0.25], [0.25, -0.25], [-0.25, -0.25], [-0.25, 0.25]]
  global_costmap:
    global_frame: map
    static_map: true
    inflation_radius: 0.6
    cost_scaling_factor: 5.0
)");
  const ToolResult r = runTool(
      {"--map", map, "--params", params, "--namespace", "move_base/global_costmap", "--out-raw", dir.file("out.raw")},
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("loading the pre-Hydro parameters"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("found in /move_base"), std::string::npos) << r.err;  // the footprint, by searchParam
  const std::vector<uint8_t> cells = rawCells(dir.file("out.raw"));
  ASSERT_EQ(cells.size(), 21u * 21u);
  auto at = [&](int x) { return static_cast<int>(cells[static_cast<std::size_t>(10 * 21 + x)]); };
  // Inscribed radius 0.26 m (the square's 0.25 plus costmap_2d's default footprint_padding 0.01),
  // 0.6 m inflation, factor 5; costmap_2d's rule: 252 * exp(-5 * (d - 0.26)) truncated.
  EXPECT_EQ(at(10), 254);
  EXPECT_EQ(at(12), 253);  // 0.2 m
  EXPECT_EQ(at(13), 206);  // 0.3 m: 252 * exp(-0.2) = 206.3
  EXPECT_EQ(at(16), 46);   // 0.6 m: 252 * exp(-1.7) = 46.0
  EXPECT_EQ(at(17), 0);    // 0.7 m, beyond inflation_radius
}

// costmap_tool types its --params as `rosparam load` does: 5e-1 is a string there, and the node would
// refuse it; the tool refuses it too, saying how to write it.
TEST(CostmapTool, NumbersRosparamReadsAsStringsAreRefusedAsByTheNode)
{
  TempDir dir;
  const std::string map = writeMap(dir, "map", 5, 5, std::vector<uint8_t>(25, 254), 0.1, 0.0, 0.0);
  const std::string params = dir.write("params.yaml", R"(
plugins:
  - {name: inflation, type: costmap_layers/InflationLayer}
inflation:
  inflation_radius: 5e-1
)");
  const ToolResult r = runTool({"--map", map, "--params", params}, dir);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("'inflation_radius'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("reads this as a string"), std::string::npos) << r.err;
}

// A key written twice in --params keeps its last value, as rosparam loads it for the node, and the tool
// says so (where, which key, where it was first), so that the lost first value is not a silent surprise.
TEST(CostmapTool, AKeyWrittenTwiceIsSaidAndTheLastValueIsUsed)
{
  TempDir dir;
  std::vector<uint8_t> pixels(21 * 21, 254);
  pixels[10 * 21 + 10] = 0;
  const std::string map = writeMap(dir, "map", 21, 21, pixels, 0.1, 0.0, 0.0);
  const std::string params = dir.write("params.yaml", R"(plugins:
  - {name: static, type: costmap_layers/StaticLayer}
  - {name: inflation, type: costmap_layers/InflationLayer}
robot_radius: 0.05
inflation:
  inflation_radius: 0.2
  cost_scaling_factor: 5.0
  inflation_radius: 0.5
)");
  const ToolResult r = runTool({"--map", map, "--params", params, "--out-raw", dir.file("out.raw")}, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: '" + params +
                       "' at line 8: key 'inflation_radius' is written twice in one map (first at line 6); the "
                       "last value is used (as rosparam loads it)"),
            std::string::npos)
      << r.err;
  const std::vector<uint8_t> cells = rawCells(dir.file("out.raw"));
  ASSERT_EQ(cells.size(), 21u * 21u);
  EXPECT_EQ(cells[10 * 21 + 10], 254);
  // 0.4 m from the obstacle: inflated with 0.5 m (with 0.2 m it would be 0): 252 * exp(-5 * (0.4 - r)),
  // r the inscribed radius of the padded 16-gon of robot_radius 0.05, between 0.05 and 0.07: 43.8 .. 48.4.
  EXPECT_GE(cells[10 * 21 + 14], 43);
  EXPECT_LE(cells[10 * 21 + 14], 48);
  EXPECT_EQ(cells[10 * 21 + 16], 0);  // 0.6 m: beyond
}

TEST(CostmapTool, CostQueriesAnswerAsTheNodesGetCost)
{
  TempDir dir;
  // The gradient on 57 x 31 cells of 0.1 m from (-1, 2): column i holds 254 - 10 * (i % 22) (see
  // expectedGradient), the same in every row.
  const std::string map = writeMap(dir, "map", 57, 31, std::vector<uint8_t>(57 * 31, 254), 0.1, -1.0, 2.0);
  const std::string params = dir.write("params.yaml", kGradientParams + R"(
footprint: [[0.1, 0.1], [-0.1, 0.1], [-0.1, -0.1], [0.1, -0.1]]
footprint_padding: 0.0
)");
  const std::vector<std::string> base = {"--map", map, "--params", params};
  auto with = [&](std::vector<std::string> extra)
  {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  // (-0.95, 2.05): column 0 -> 254; (-0.85, 2.05, yaw 1): column 1 -> 244; (-0.45, 3.05): column 5 -> 204.
  ToolResult r = runTool(with({"--cost", "-0.95,2.05", "--cost", "-0.85,2.05,1", "--cost", "-0.45,3.05"}), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json j = jsonOf(r);
  EXPECT_EQ(j["costs"], nlohmann::json::parse("[254.0, 244.0, 204.0]")) << j;
  EXPECT_EQ(j["costs_success"], true);
  // The footprint (+-0.1 m) at (-0.45, 3.05) spans x -0.55..-0.35: columns 4..6 -> max(214, 204, 194).
  r = runTool(with({"--cost", "-0.45,3.05,0", "--cost-footprint"}), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(jsonOf(r)["costs"], nlohmann::json::parse("[214.0]"));
  // Off the map (x < -1, or y >= 5.1; y 5.1 itself is row 30.99.. in floating point, on the map): 254 and
  // success false, as Nav2's GetCosts; a footprint with a vertex off the map is 254 with success still
  // true. (0.05, 3): column 10 -> 254 - 100.
  r = runTool(with({"--cost", "-1.01,3", "--cost", "0,5.15", "--cost", "0.05,3"}), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = jsonOf(r);
  EXPECT_EQ(j["costs"], nlohmann::json::parse("[254.0, 254.0, 154.0]")) << j;
  EXPECT_EQ(j["costs_success"], false);
  r = runTool(with({"--cost", "-0.95,3", "--cost-footprint"}), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(jsonOf(r)["costs"], nlohmann::json::parse("[254.0]"));
  EXPECT_EQ(jsonOf(r)["costs_success"], true);
  // Without --cost the output has no costs.
  r = runTool(base, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(jsonOf(r).contains("costs"));

  const std::vector<std::pair<std::vector<std::string>, std::string>> bad = {
      {{"--cost", "nan,1"}, "--cost expects X,Y or X,Y,YAW"},
      {{"--cost", "1,inf"}, "--cost expects X,Y or X,Y,YAW"},
      {{"--cost", "1"}, "--cost expects X,Y or X,Y,YAW"},
      {{"--cost", "1,2,3,4"}, "--cost expects X,Y or X,Y,YAW"},
      {{"--cost", "1,2,"}, "--cost expects X,Y or X,Y,YAW"},
      {{"--cost", "1e8,0"}, "(got \"1e8,0\")"},
      {{"--cost", "0,0,1e4"}, "|YAW| at most 1000 rad"},
      {{"--cost-footprint"}, "--cost-footprint shapes the --cost answers: give --cost too"},
  };
  for (const auto& [extra, needle] : bad)
  {
    r = runTool(with(extra), dir);
    EXPECT_EQ(r.exit_code, 2) << needle;
    EXPECT_NE(r.err.find(needle), std::string::npos) << "stderr was: " << r.err;
    EXPECT_EQ(r.out, "") << needle;
  }
}

// The AsymmetricInflationLayer offline: without --plan symmetric with the larger factor (10), with
// --plan along y = 2.0 the obstacle left of it (disfavoured, factor 1) costs more; a bad plan is refused
// naming the field and nothing is written. Lethal cells (20, 24) and (20, 16); costs read 0.4 m beyond
// each: floor(252 exp(-f (0.4 - 0.1))) = 186 for f = 1, 12 for f = 10.
TEST(CostmapTool, PlanFeedsTheAsymmetricInflationLayer)
{
  TempDir dir;
  std::vector<uint8_t> pixels(1600, 254);
  pixels[(39 - 24) * 40 + 20] = 0;  // image rows run from the highest y
  pixels[(39 - 16) * 40 + 20] = 0;
  const std::string map = writeMap(dir, "map", 40, 40, pixels, 0.1, 0.0, 0.0);
  const std::string params = dir.write("params.yaml", R"(
footprint: [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]]
footprint_padding: 0.0
plugins:
  - {name: static_layer, type: costmap_layers/StaticLayer}
  - {name: inflation, type: nav2_costmap_2d::AsymmetricInflationLayer}
inflation: {inflation_radius: 0.55, cost_scaling_factor_left: 1.0, cost_scaling_factor_right: 10.0}
)");
  const std::vector<std::string> base{"--map", map, "--params", params, "--pose", "0,0,0", "--out-raw",
                                      dir.file("out.raw")};
  const ToolResult none = runTool(base, dir);
  ASSERT_EQ(none.exit_code, 0) << none.err;
  auto cells = rawCells(dir.file("out.raw"));
  ASSERT_EQ(cells.size(), 1600u);
  EXPECT_EQ(cells[28 * 40 + 20], 12);
  EXPECT_EQ(cells[12 * 40 + 20], 12);
  EXPECT_NE(none.err.find("no plan"), std::string::npos) << none.err;

  auto with = base;
  with.insert(with.end(), {"--plan", "inflation=0.5,2,1.5,2,2.5,2,3.5,2"});
  const ToolResult planned = runTool(with, dir);
  ASSERT_EQ(planned.exit_code, 0) << planned.err;
  cells = rawCells(dir.file("out.raw"));
  EXPECT_EQ(cells[28 * 40 + 20], 186);
  EXPECT_EQ(cells[12 * 40 + 20], 12);

  for (const std::string& bad : {"inflation=0.5,2,nan,2", "inflation=0.5,2,1e8,2", "inflation=0.5,2"})
  {
    auto args = base;
    args.insert(args.end(), {"--plan", bad});
    const ToolResult r = runTool(args, dir);
    EXPECT_NE(r.exit_code, 0) << bad;
    EXPECT_NE(r.err.find("poses"), std::string::npos) << bad << ": " << r.err;
  }
  for (const std::string& bad : {"inflation=0.5,2,1", "inflation=0.5,x", "static_layer=0,0,1,1"})
  {
    auto args = base;
    args.insert(args.end(), {"--plan", bad});
    const ToolResult r = runTool(args, dir);
    EXPECT_NE(r.exit_code, 0) << bad;
    EXPECT_NE(r.err.find("--plan"), std::string::npos) << bad << ": " << r.err;
  }
}
