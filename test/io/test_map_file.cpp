// Tests of costmap_layers::io map file loading: every mode on tiny images with hand-computed values,
// negate, alpha, colour/palette/16-bit images, the flip, PNG == PGM, every error, and the real maps
// copied into test/data/maps (sources and licences in test/data/README.md).
#include "costmap_layers/io/map_file.hpp"
#include "png_bytes.hpp"
#include "temp_dir_test.hpp"

#include <gtest/gtest.h>
#include <png.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

using costmap_layers::OccupancyGridData;
using costmap_layers::io::loadMapFile;
using costmap_layers::io::loadMapFileInfo;
using costmap_layers::io::loadMapImage;
using costmap_layers::io::MapFileInfo;
using costmap_layers::io::MapMode;
using costmap_layers::io::mapModeName;
using costmap_layers::io::parseMapMode;

namespace
{
std::string sourceDir()
{
#ifdef COSTMAP_LAYERS_SOURCE_DIR
  return COSTMAP_LAYERS_SOURCE_DIR;
#else
  // <root>/test/io/test_map_file.cpp (an absolute path when built by CMake)
  const std::string root = std::filesystem::path(__FILE__).parent_path().parent_path().parent_path().string();
  return root.empty() ? "." : root;
#endif
}

std::string dataDir()
{
  return sourceDir() + "/test/data";
}
std::string realMapsDir()
{
  return dataDir() + "/maps";
}

void writeText(const std::string& path, const std::string& text)
{
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// Writes a PNG with rows given in PNG's own packed layout (big-endian for 16 bits). Returns false on
/// a libpng error. No C++ object with a destructor is created after setjmp.
bool writeTestPngRaw(const char* path, uint32_t w, uint32_t h, int color_type, int bit_depth, const uint8_t* rows,
                     size_t rowbytes, const png_color* palette, int palette_size, const uint8_t* trns, int trns_size,
                     bool interlace)
{
  FILE* fp = std::fopen(path, "wb");
  if (fp == nullptr) return false;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png)))
  {
    png_destroy_write_struct(&png, &info);
    std::fclose(fp);
    return false;
  }
  png_init_io(png, fp);
  png_set_IHDR(png, info, w, h, bit_depth, color_type, interlace ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (palette_size > 0) png_set_PLTE(png, info, palette, palette_size);
  if (trns_size > 0) png_set_tRNS(png, info, trns, trns_size, nullptr);
  png_write_info(png, info);
  const int passes = png_set_interlace_handling(png);
  for (int pass = 0; pass < passes; ++pass)
  {
    for (uint32_t y = 0; y < h; ++y)
      png_write_row(png, rows + rowbytes * y);
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return std::fclose(fp) == 0;
}

void writeTestPng(const std::string& path, uint32_t w, uint32_t h, int color_type, int bit_depth,
                  const std::vector<uint8_t>& rows, const std::vector<png_color>& palette = {},
                  const std::vector<uint8_t>& trns = {}, bool interlace = false)
{
  const size_t rowbytes = rows.size() / h;
  ASSERT_EQ(rowbytes * h, rows.size());
  ASSERT_TRUE(writeTestPngRaw(path.c_str(), w, h, color_type, bit_depth, rows.data(), rowbytes,
                              palette.empty() ? nullptr : palette.data(), static_cast<int>(palette.size()),
                              trns.empty() ? nullptr : trns.data(), static_cast<int>(trns.size()), interlace));
}

std::vector<int> values(const OccupancyGridData& g)
{
  return std::vector<int>(g.data.begin(), g.data.end());
}

MapFileInfo defaultInfo(MapMode mode)
{
  MapFileInfo info;
  info.resolution = 0.05;
  info.occupied_thresh = 0.65;
  info.free_thresh = 0.196;
  info.mode = mode;
  return info;
}

/// Expects a std::runtime_error whose message contains every one of `parts`.
template <typename F>
void expectError(F&& f, const std::vector<std::string>& parts)
{
  try
  {
    f();
    ADD_FAILURE() << "no exception thrown; expected one mentioning " << parts.front();
  }
  catch (const std::runtime_error& e)
  {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "message has several lines: " << msg;
    for (const auto& p : parts)
      EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' missing in: " << msg;
  }
}

class MapFileTest : public TempDirTest
{
protected:
  /// A map YAML in the temp folder; `extra` lines are appended, keys in `drop` left out.
  std::string writeYaml(const std::string& name, const std::map<std::string, std::string>& overrides,
                        const std::set<std::string>& drop = {})
  {
    std::map<std::string, std::string> keys = {{"image", "img.pgm"},          {"resolution", "0.05"},
                                               {"origin", "[0.0, 0.0, 0.0]"}, {"negate", "0"},
                                               {"occupied_thresh", "0.65"},   {"free_thresh", "0.196"}};
    for (const auto& kv : overrides)
      keys[kv.first] = kv.second;
    std::string text;
    for (const auto& kv : keys)
    {
      if (drop.count(kv.first) == 0) text += kv.first + ": " + kv.second + "\n";
    }
    writeText(tmp(name), text);
    return tmp(name);
  }
};

// Hand computation for the 3x2 fixture (top row 0 127 128, bottom row 205 254 255), thresholds
// 0.65 / 0.196, occ = (255 - v) / 255:
//   v=0   occ=1.0         > 0.65                                  -> 100 in every threshold mode
//   v=127 occ=0.501961    ratio=(0.501961-0.196)/0.454=0.673923  scale 1+66.04 -> 67, nav2 67.39 -> 67
//   v=128 occ=0.498039    ratio=0.665285                         scale 1+65.20 -> 66, nav2 66.53 -> 67
//   v=205 occ=0.196078    just above 0.196: ratio=0.000173       scale 1+0.017 -> 1,  nav2 0.017 -> 0
//   v=254 occ=0.003922    < 0.196                                 -> 0
//   v=255 occ=0.0                                                 -> 0
// raw: 0, 127, 128 -> -128, 205 -> -51, 254 -> -2, 255 -> -1.
// Data row 0 is the image's BOTTOM row, so data = {205, 254, 255, 0, 127, 128} mapped.
TEST_F(MapFileTest, GreyPgmEveryModeExactValues)
{
  const std::string yaml = dataDir() + "/grey6.yaml";
  const OccupancyGridData t = loadMapFile(yaml);  // no mode key: trinary
  EXPECT_EQ(t.width, 3u);
  EXPECT_EQ(t.height, 2u);
  EXPECT_DOUBLE_EQ(t.resolution, 0.1);
  EXPECT_DOUBLE_EQ(t.origin_x, 1.5);
  EXPECT_DOUBLE_EQ(t.origin_y, -2.0);
  EXPECT_DOUBLE_EQ(t.origin_yaw, 0.25);
  EXPECT_EQ(t.frame_id, "map");
  EXPECT_EQ(values(t), (std::vector<int>{-1, 0, 0, 100, -1, -1}));
  EXPECT_EQ(values(loadMapFile(yaml, MapMode::Scale)), (std::vector<int>{1, 0, 0, 100, 67, 66}));
  EXPECT_EQ(values(loadMapFile(yaml, MapMode::Raw)), (std::vector<int>{-51, -2, -1, 0, 127, -128}));
  EXPECT_EQ(values(loadMapFile(yaml, MapMode::Nav2Scale)), (std::vector<int>{0, 0, 0, 100, 67, 67}));
}

TEST_F(MapFileTest, AsciiPgmAndPngGiveTheSameGridAsBinaryPgm)
{
  for (MapMode mode : {MapMode::Trinary, MapMode::Scale, MapMode::Raw, MapMode::Nav2Scale})
  {
    const OccupancyGridData ref = loadMapImage(dataDir() + "/grey6.pgm", defaultInfo(mode));
    EXPECT_EQ(values(loadMapImage(dataDir() + "/grey6_ascii.pgm", defaultInfo(mode))), values(ref))
        << mapModeName(mode);
    EXPECT_EQ(values(loadMapImage(dataDir() + "/grey6.png", defaultInfo(mode))), values(ref)) << mapModeName(mode);
  }
  // grey6_png.yaml names the PNG and mode: scale.
  const MapFileInfo info = loadMapFileInfo(dataDir() + "/grey6_png.yaml");
  EXPECT_EQ(info.mode, MapMode::Scale);
  EXPECT_FALSE(info.negate);
  EXPECT_EQ(info.image_path, dataDir() + "/grey6.png");
  EXPECT_EQ(values(loadMapFile(dataDir() + "/grey6_png.yaml")),
            values(loadMapFile(dataDir() + "/grey6.yaml", MapMode::Scale)));
}

// With negate the mean becomes 255 - v: occ = v / 255.
//   v=0 -> occ 0 -> 0; v=127 -> 0.498 -> unknown / scale 66 / nav2 67; v=128 -> 0.502 -> 67 / 67;
//   v=205, 254, 255 -> occ >= 0.80 -> 100. Raw: 255 - v wrapped: 255->-1, 128->-128, 127, 50, 1, 0.
TEST_F(MapFileTest, Negate)
{
  MapFileInfo info = defaultInfo(MapMode::Trinary);
  info.negate = true;
  const std::string pgm = dataDir() + "/grey6.pgm";
  EXPECT_EQ(values(loadMapImage(pgm, info)), (std::vector<int>{100, 100, 100, 0, -1, -1}));
  info.mode = MapMode::Scale;
  EXPECT_EQ(values(loadMapImage(pgm, info)), (std::vector<int>{100, 100, 100, 0, 66, 67}));
  info.mode = MapMode::Raw;
  EXPECT_EQ(values(loadMapImage(pgm, info)), (std::vector<int>{50, 1, 0, -1, -128, 127}));
  info.mode = MapMode::Nav2Scale;
  EXPECT_EQ(values(loadMapImage(pgm, info)), (std::vector<int>{100, 100, 100, 0, 67, 67}));

  // negate given as true / 1 in the YAML
  writeText(tmp("img.pgm"), "P2 1 1 255 0\n");
  EXPECT_TRUE(loadMapFileInfo(writeYaml("a.yaml", {{"negate", "true"}})).negate);
  EXPECT_TRUE(loadMapFileInfo(writeYaml("b.yaml", {{"negate", "1"}})).negate);
  EXPECT_FALSE(loadMapFileInfo(writeYaml("c.yaml", {{"negate", "false"}})).negate);
  EXPECT_EQ(values(loadMapFile(writeYaml("d.yaml", {{"negate", "1"}}))), (std::vector<int>{0}));
}

TEST_F(MapFileTest, FlipPutsTheTopImageRowLast)
{
  // 2 wide, 3 tall: top row black, middle grey 205 (unknown), bottom row white.
  writeText(tmp("col.pgm"), "P2\n2 3\n255\n0 0\n205 205\n255 255\n");
  const OccupancyGridData g = loadMapImage(tmp("col.pgm"), defaultInfo(MapMode::Trinary));
  ASSERT_EQ(g.width, 2u);
  ASSERT_EQ(g.height, 3u);
  EXPECT_EQ(values(g), (std::vector<int>{0, 0, -1, -1, 100, 100}));
  // Columns are not mirrored.
  writeText(tmp("row.pgm"), "P2\n3 1\n255\n0 205 255\n");
  EXPECT_EQ(values(loadMapImage(tmp("row.pgm"), defaultInfo(MapMode::Trinary))), (std::vector<int>{100, -1, 0}));
}

// RGBA pixels (grey 128 opaque, grey 128 transparent, grey 128 alpha 200, black transparent).
//   ROS 1 scale: alpha left out of the mean: 128 -> 66; alpha 0 -> unknown; alpha 200 is treated as
//     opaque (map_server tests alpha < 1) -> 66; black: occ 1 > 0.65 -> 100 before the alpha test.
//   ROS 1 raw: mean 128 -> -128 (alpha ignored); black -> 0.
//   Nav2 scale: every alpha < 255 -> -1; 128 opaque -> 67.
TEST_F(MapFileTest, AlphaInScaleRawAndNav2Modes)
{
  const std::string png = tmp("rgba.png");
  writeTestPng(png, 4, 1, PNG_COLOR_TYPE_RGB_ALPHA, 8,
               {128, 128, 128, 255, 128, 128, 128, 0, 128, 128, 128, 200, 0, 0, 0, 0});
  EXPECT_EQ(values(loadMapImage(png, defaultInfo(MapMode::Scale))), (std::vector<int>{66, -1, 66, 100}));
  EXPECT_EQ(values(loadMapImage(png, defaultInfo(MapMode::Raw))), (std::vector<int>{-128, -128, -128, 0}));
  EXPECT_EQ(values(loadMapImage(png, defaultInfo(MapMode::Nav2Scale))), (std::vector<int>{67, -1, -1, -1}));

  // Grey+alpha is handled as RGBA.
  const std::string ga = tmp("ga.png");
  writeTestPng(ga, 4, 1, PNG_COLOR_TYPE_GRAY_ALPHA, 8, {128, 255, 128, 0, 128, 200, 0, 0});
  for (MapMode mode : {MapMode::Trinary, MapMode::Scale, MapMode::Raw, MapMode::Nav2Scale})
    EXPECT_EQ(values(loadMapImage(ga, defaultInfo(mode))), values(loadMapImage(png, defaultInfo(mode))));
}

// Trinary mode averages alpha in with the colours (as map_server does):
//   white opaque: mean 255 -> 0; white transparent: mean (3*255+0)/4 = 191.25 -> occ 0.25 -> unknown;
//   black opaque: mean 63.75 -> occ 0.75 -> 100.
TEST_F(MapFileTest, TrinaryAveragesAlphaIn)
{
  const std::string png = tmp("rgba.png");
  writeTestPng(png, 3, 1, PNG_COLOR_TYPE_RGB_ALPHA, 8, {255, 255, 255, 255, 255, 255, 255, 0, 0, 0, 0, 255});
  EXPECT_EQ(values(loadMapImage(png, defaultInfo(MapMode::Trinary))), (std::vector<int>{0, -1, 100}));
}

// RGB: (255,0,0) mean 85 -> occ 0.667 -> 100; (0,255,255) mean 170 -> occ 0.3333 -> ratio 0.30249 ->
// scale 1+29.64 -> 30, nav2 30.25 -> 30; (60,90,120) mean 90 -> occ 0.64706 -> ratio 0.99361 ->
// scale 1+97.37 -> 98, nav2 99.36 -> 99. PPM (P6 and P3) give the same.
TEST_F(MapFileTest, RgbMeanPngAndPpm)
{
  const std::vector<uint8_t> px = {255, 0, 0, 0, 255, 255, 60, 90, 120};
  writeTestPng(tmp("rgb.png"), 3, 1, PNG_COLOR_TYPE_RGB, 8, px);
  std::string p6 = "P6\n3 1\n255\n";
  p6.append(px.begin(), px.end());
  writeText(tmp("rgb.ppm"), p6);
  writeText(tmp("rgb_ascii.ppm"), "P3 3 1 255\n255 0 0  0 255 255  60 90 120\n");
  for (const std::string& f : {tmp("rgb.png"), tmp("rgb.ppm"), tmp("rgb_ascii.ppm")})
  {
    EXPECT_EQ(values(loadMapImage(f, defaultInfo(MapMode::Scale))), (std::vector<int>{100, 30, 98})) << f;
    EXPECT_EQ(values(loadMapImage(f, defaultInfo(MapMode::Nav2Scale))), (std::vector<int>{100, 30, 99})) << f;
    EXPECT_EQ(values(loadMapImage(f, defaultInfo(MapMode::Raw))), (std::vector<int>{85, -86, 90})) << f;
  }
}

// Palette entries are expanded to their colours (not the index, unlike SDL in map_server).
TEST_F(MapFileTest, PaletteWithTransparency)
{
  const std::vector<png_color> palette = {{0, 0, 0}, {255, 255, 255}, {128, 128, 128}};
  writeTestPng(tmp("pal.png"), 4, 1, PNG_COLOR_TYPE_PALETTE, 8, {0, 1, 2, 2}, palette);
  EXPECT_EQ(values(loadMapImage(tmp("pal.png"), defaultInfo(MapMode::Scale))), (std::vector<int>{100, 0, 66, 66}));
  // index 2 fully transparent through tRNS
  writeTestPng(tmp("pal_t.png"), 4, 1, PNG_COLOR_TYPE_PALETTE, 8, {0, 1, 2, 2}, palette, {255, 255, 0});
  EXPECT_EQ(values(loadMapImage(tmp("pal_t.png"), defaultInfo(MapMode::Scale))), (std::vector<int>{100, 0, -1, -1}));
}

// 16-bit samples are scaled to 8 bits with rounding: 0 -> 0, 32768 -> 128, 65535 -> 255.
// A 4-bit maxval 15 PGM: 15 -> 255, 7 -> round(119.0) = 119, 8 -> round(136.0) = 136.
TEST_F(MapFileTest, SixteenBitAndSmallMaxval)
{
  const std::vector<uint8_t> be = {0x00, 0x00, 0x80, 0x00, 0xFF, 0xFF};
  writeTestPng(tmp("g16.png"), 3, 1, PNG_COLOR_TYPE_GRAY, 16, be);
  std::string p5 = "P5\n3 1\n65535\n";
  p5.append(be.begin(), be.end());
  writeText(tmp("g16.pgm"), p5);
  writeText(tmp("g16_ascii.pgm"), "P2\n3 1\n65535\n0 32768 65535\n");
  for (const std::string& f : {tmp("g16.png"), tmp("g16.pgm"), tmp("g16_ascii.pgm")})
    EXPECT_EQ(values(loadMapImage(f, defaultInfo(MapMode::Raw))), (std::vector<int>{0, -128, -1})) << f;

  writeText(tmp("g4.pgm"), "P2\n3 1\n15\n15 7 8\n");
  EXPECT_EQ(values(loadMapImage(tmp("g4.pgm"), defaultInfo(MapMode::Raw))), (std::vector<int>{-1, 119, -120}));

  // 1-bit grey PNG: bits 1 0 1 -> 255 0 255
  writeTestPng(tmp("g1.png"), 3, 1, PNG_COLOR_TYPE_GRAY, 1, {0xA0});
  EXPECT_EQ(values(loadMapImage(tmp("g1.png"), defaultInfo(MapMode::Trinary))), (std::vector<int>{0, 100, 0}));
}

TEST_F(MapFileTest, InterlacedPngEqualsPlainPng)
{
  std::vector<uint8_t> px;
  for (int k = 0; k < 9 * 7; ++k)
    px.push_back(static_cast<uint8_t>((k * 37) % 256));
  writeTestPng(tmp("plain.png"), 9, 7, PNG_COLOR_TYPE_GRAY, 8, px);
  writeTestPng(tmp("adam7.png"), 9, 7, PNG_COLOR_TYPE_GRAY, 8, px, {}, {}, true);
  EXPECT_EQ(values(loadMapImage(tmp("adam7.png"), defaultInfo(MapMode::Raw))),
            values(loadMapImage(tmp("plain.png"), defaultInfo(MapMode::Raw))));
}

TEST_F(MapFileTest, YamlVariants)
{
  writeText(tmp("img.pgm"), "P2 2 1 255 0 255\n");
  // absolute image path
  MapFileInfo info = loadMapFileInfo(writeYaml("abs.yaml", {{"image", tmp("img.pgm")}, {"mode", "raw"}}));
  EXPECT_EQ(info.image_path, tmp("img.pgm"));
  EXPECT_EQ(info.mode, MapMode::Raw);
  // image in a sub folder, relative to the YAML's folder
  std::filesystem::create_directory(tmp("sub"));
  writeText(tmp("sub/img2.pgm"), "P2 2 1 255 0 255\n");
  const std::string yaml =
      writeYaml("rel.yaml", {{"image", "sub/img2.pgm"}, {"mode", "nav2_scale"}, {"origin", "[-1, 2.5, 3]"}});
  info = loadMapFileInfo(yaml);
  EXPECT_EQ(info.image_path, tmp("sub/img2.pgm"));
  EXPECT_EQ(info.mode, MapMode::Nav2Scale);
  EXPECT_DOUBLE_EQ(info.origin[0], -1.0);
  EXPECT_DOUBLE_EQ(info.origin[1], 2.5);
  EXPECT_DOUBLE_EQ(info.origin[2], 3.0);
  EXPECT_EQ(values(loadMapFile(yaml)), (std::vector<int>{100, 0}));
  // the override wins over the YAML's mode
  EXPECT_EQ(values(loadMapFile(yaml, MapMode::Raw)), (std::vector<int>{0, -1}));
  // every mode name parses
  for (const char* m : {"trinary", "scale", "raw", "nav2_scale"})
    EXPECT_STREQ(mapModeName(parseMapMode(m)), m);
}

TEST_F(MapFileTest, YamlErrors)
{
  writeText(tmp("img.pgm"), "P2 1 1 255 0\n");
  expectError([&] { loadMapFile(tmp("nope.yaml")); }, {"nope.yaml", "cannot open"});
  writeText(tmp("syntax.yaml"), "image: img.pgm\nresolution: [0.05\norigin: {\n");
  expectError([&] { loadMapFile(tmp("syntax.yaml")); }, {"syntax.yaml", "bad YAML", "line"});
  writeText(tmp("list.yaml"), "- a\n- b\n");
  expectError([&] { loadMapFile(tmp("list.yaml")); }, {"list.yaml", "expected a map"});
  for (const char* key : {"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh"})
  {
    const std::string y = writeYaml(std::string("no_") + key + ".yaml", {}, {key});
    expectError([&] { loadMapFile(y); }, {y, "missing key", key});
  }
  for (const char* res : {"0", "-0.05", ".nan", ".inf", "abc"})
  {
    const std::string y = writeYaml("res.yaml", {{"resolution", res}});
    expectError([&] { loadMapFile(y); }, {y, "resolution"});
  }
  for (const char* origin : {"[0, 0]", "[0, 0, 0, 0]", "[a, 0, 0]", "0", "[.nan, 0, 0]"})
  {
    const std::string y = writeYaml("origin.yaml", {{"origin", origin}});
    expectError([&] { loadMapFile(y); }, {y, "origin"});
  }
  expectError([&] { loadMapFile(writeYaml("neg.yaml", {{"negate", "maybe"}})); }, {"neg.yaml", "negate"});
  expectError([&] { loadMapFile(writeYaml("t1.yaml", {{"occupied_thresh", "1.5"}})); }, {"t1.yaml", "[0, 1]"});
  expectError([&] { loadMapFile(writeYaml("t2.yaml", {{"free_thresh", "-0.1"}})); }, {"t2.yaml", "[0, 1]"});
  expectError([&] { loadMapFile(writeYaml("t3.yaml", {{"free_thresh", "0.7"}})); }, {"t3.yaml", "smaller"});
  expectError([&] { loadMapFile(writeYaml("t4.yaml", {{"free_thresh", "0.65"}})); }, {"t4.yaml", "smaller"});
  expectError([&] { loadMapFile(writeYaml("t5.yaml", {{"free_thresh", "x"}})); }, {"t5.yaml", "free_thresh"});
  expectError([&] { loadMapFile(writeYaml("mode.yaml", {{"mode", "fancy"}})); }, {"mode.yaml", "fancy"});
  expectError([&] { loadMapFile(writeYaml("img.yaml", {{"image", "[a, b]"}})); }, {"img.yaml", "image"});
  expectError([] { parseMapMode("Trinary"); }, {"Trinary", "trinary"});
  // invalid info given directly to loadMapImage
  MapFileInfo info = defaultInfo(MapMode::Trinary);
  info.resolution = 0.0;
  expectError([&] { loadMapImage(tmp("img.pgm"), info); }, {"img.pgm", "resolution"});
}

TEST_F(MapFileTest, ImageErrors)
{
  const MapFileInfo info = defaultInfo(MapMode::Trinary);
  const auto load = [&](const std::string& name) { return loadMapImage(tmp(name), info); };
  // missing image named by a YAML
  const std::string y = writeYaml("missing.yaml", {{"image", "gone.pgm"}});
  expectError([&] { loadMapFile(y); }, {"gone.pgm", "cannot open"});

  writeText(tmp("empty.pgm"), "");
  expectError([&] { load("empty.pgm"); }, {"empty.pgm", "empty"});
  writeText(tmp("text.pgm"), "hello world");
  expectError([&] { load("text.pgm"); }, {"text.pgm", "bad image header"});
  writeText(tmp("p4.pgm"), "P4\n8 1\n\x55");
  expectError([&] { load("p4.pgm"); }, {"p4.pgm", "P4"});
  writeText(tmp("noheight.pgm"), "P5\n3\n");
  expectError([&] { load("noheight.pgm"); }, {"noheight.pgm", "missing height"});
  writeText(tmp("badwidth.pgm"), "P5\nx 3\n255\n");
  expectError([&] { load("badwidth.pgm"); }, {"badwidth.pgm", "width"});
  writeText(tmp("maxval0.pgm"), "P2 1 1 0 0\n");
  expectError([&] { load("maxval0.pgm"); }, {"maxval0.pgm", "maxval"});
  writeText(tmp("maxval70000.pgm"), "P2 1 1 70000 0\n");
  expectError([&] { load("maxval70000.pgm"); }, {"maxval70000.pgm", "maxval"});
  writeText(tmp("zero.pgm"), "P5 0 3 255\n");
  expectError([&] { load("zero.pgm"); }, {"zero.pgm", "zero size"});
  writeText(tmp("huge.pgm"), "P5 100001 1 255\n");
  expectError([&] { load("huge.pgm"); }, {"huge.pgm", "absurdly large"});
  writeText(tmp("short.pgm"), "P5 3 2 255\nabcd");
  expectError([&] { load("short.pgm"); }, {"short.pgm", "truncated"});
  writeText(tmp("short16.pgm"), "P5 2 1 65535\nabc");
  expectError([&] { load("short16.pgm"); }, {"short16.pgm", "truncated"});
  writeText(tmp("short_ascii.pgm"), "P2 3 2 255\n1 2 3 4\n");
  expectError([&] { load("short_ascii.pgm"); }, {"short_ascii.pgm", "truncated"});
  writeText(tmp("over.pgm"), "P2 2 1 100\n50 101\n");
  expectError([&] { load("over.pgm"); }, {"over.pgm", "exceeds maxval"});
  writeText(tmp("junk.pgm"), "P2 2 1 255\n50 x\n");
  expectError([&] { load("junk.pgm"); }, {"junk.pgm", "expected a number"});

  // PNG: truncated, corrupted, absurdly wide
  std::vector<uint8_t> px(64 * 64);
  for (size_t k = 0; k < px.size(); ++k)
    px[k] = static_cast<uint8_t>(k * 7919 % 251);
  writeTestPng(tmp("ok.png"), 64, 64, PNG_COLOR_TYPE_GRAY, 8, px);
  std::ifstream in(tmp("ok.png"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 100u);
  writeText(tmp("cut.png"), bytes.substr(0, bytes.size() / 2));
  expectError([&] { load("cut.png"); }, {"cut.png", "truncated"});
  writeText(tmp("cut_header.png"), bytes.substr(0, 20));
  expectError([&] { load("cut_header.png"); }, {"cut_header.png", "truncated"});
  std::string bad = bytes;
  bad[50] = static_cast<char>(bad[50] ^ 0x5A);  // inside the compressed data: CRC error
  writeText(tmp("corrupt.png"), bad);
  expectError([&] { load("corrupt.png"); }, {"corrupt.png", "bad PNG"});
  writeTestPng(tmp("wide.png"), 100001, 1, PNG_COLOR_TYPE_GRAY, 1, std::vector<uint8_t>(12501, 0));
  expectError([&] { load("wide.png"); }, {"wide.png", "absurdly large"});
}

// ---- The real maps of test/data/maps ----
// Expected values come from the image itself: the test reads the PGM's grey levels with its own few
// lines and applies map_server's and Nav2's published rules to them, never the loader's output.

/// Grey level -> pixel count of a binary (P5, maxval 255) PGM, read here independently of the loader.
struct PgmCounts
{
  unsigned width = 0, height = 0;
  std::map<int, size_t> grey;
};

/// The next header token of a PGM, skipping white space and # comments.
std::string pgmToken(std::istream& in)
{
  std::string token;
  for (int c = in.get(); c != EOF; c = in.get())
  {
    if (c == '#')
    {
      std::string comment;
      std::getline(in, comment);
    }
    else if (std::isspace(c))
    {
      if (!token.empty()) return token;
    }
    else
      token += static_cast<char>(c);
  }
  return token;
}

PgmCounts countPgm(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  PgmCounts c;
  const std::string magic = pgmToken(in);
  c.width = static_cast<unsigned>(std::stoul(pgmToken(in)));
  c.height = static_cast<unsigned>(std::stoul(pgmToken(in)));
  const unsigned maxval = static_cast<unsigned>(std::stoul(pgmToken(in)));  // its single white space is read
  EXPECT_EQ(magic, "P5");
  EXPECT_EQ(maxval, 255u);
  std::vector<char> px(static_cast<size_t>(c.width) * c.height);
  in.read(px.data(), static_cast<std::streamsize>(px.size()));
  EXPECT_EQ(static_cast<size_t>(in.gcount()), px.size()) << path;
  for (char g : px)
    ++c.grey[static_cast<unsigned char>(g)];
  return c;
}

/// Applies a per-grey rule (occupancy p = (255 - g) / 255, negate 0) to the grey counts.
template <class Rule>
std::map<int, size_t> expectedValues(const PgmCounts& c, Rule rule)
{
  std::map<int, size_t> h;
  for (const auto& [g, n] : c.grey)
    h[rule((255.0 - g) / 255.0)] += n;
  return h;
}

std::map<int, size_t> histogram(const OccupancyGridData& g)
{
  std::map<int, size_t> h;
  for (int8_t v : g.data)
    ++h[v];
  return h;
}

TEST(RealMaps, Turtlebot3World)
{
  const std::string yaml = realMapsDir() + "/turtlebot3_world.yaml";
  const PgmCounts pgm = countPgm(realMapsDir() + "/turtlebot3_world.pgm");
  const OccupancyGridData g = loadMapFile(yaml);
  EXPECT_EQ(g.width, pgm.width);
  EXPECT_EQ(g.height, pgm.height);
  EXPECT_DOUBLE_EQ(g.resolution, 0.05);
  EXPECT_DOUBLE_EQ(g.origin_x, -10.0);
  EXPECT_DOUBLE_EQ(g.origin_y, -10.0);
  EXPECT_EQ(g.data.size(), static_cast<size_t>(pgm.width) * pgm.height);
  // map_server trinary with the file's thresholds (occupied 0.65, free 0.196), strict comparisons.
  const auto trinary = expectedValues(pgm, [](double p) { return p > 0.65 ? 100 : p < 0.196 ? 0 : -1; });
  const auto h = histogram(g);
  EXPECT_EQ(h, trinary);
  // The map really has all three classes.
  EXPECT_EQ(h.size(), 3u);
  // ROS 1 scale: between the thresholds 1 + 98 * ratio, truncated (the unknown grey 205 is value 1).
  const auto ros1_scale = expectedValues(pgm,
                                         [](double p)
                                         {
                                           if (p > 0.65) return 100;
                                           if (p < 0.196) return 0;
                                           return static_cast<int>(1.0 + 98.0 * (p - 0.196) / (0.65 - 0.196));
                                         });
  EXPECT_EQ(histogram(loadMapFile(yaml, MapMode::Scale)), ros1_scale);
  // Nav2 scale (nav2_map_server map_io): beyond the thresholds 100 / 0, between them
  // rint(100 * (p - free) / (occupied - free)).
  const auto nav2_scale = expectedValues(pgm,
                                         [](double p)
                                         {
                                           if (p >= 0.65) return 100;
                                           if (p <= 0.196) return 0;
                                           return static_cast<int>(std::rint(100.0 * (p - 0.196) / (0.65 - 0.196)));
                                         });
  EXPECT_EQ(histogram(loadMapFile(yaml, MapMode::Nav2Scale)), nav2_scale);
}

TEST(RealMaps, DepotKeepout)
{
  const std::string yaml = realMapsDir() + "/depot_keepout.yaml";
  const MapFileInfo info = loadMapFileInfo(yaml);
  EXPECT_EQ(info.mode, MapMode::Trinary);
  EXPECT_DOUBLE_EQ(info.free_thresh, 0.25);
  const PgmCounts pgm = countPgm(realMapsDir() + "/depot_keepout.pgm");
  const OccupancyGridData g = loadMapFile(yaml);
  EXPECT_EQ(g.width, pgm.width);
  EXPECT_EQ(g.height, pgm.height);
  const auto expected = expectedValues(pgm, [](double p) { return p > 0.65 ? 100 : p < 0.25 ? 0 : -1; });
  EXPECT_EQ(histogram(g), expected);
  // A keepout mask: free and keepout only, no unknown.
  EXPECT_EQ(expected.count(-1), 0u);
  EXPECT_GT(expected.at(100), 0u);
}

TEST(RealMaps, TutorialsSpeedMaskRos1VersusNav2)
{
  const std::string yaml = realMapsDir() + "/tutorials_speed_mask.yaml";
  const MapFileInfo info = loadMapFileInfo(yaml);
  EXPECT_EQ(info.mode, MapMode::Scale);
  EXPECT_DOUBLE_EQ(info.occupied_thresh, 1.0);
  EXPECT_DOUBLE_EQ(info.free_thresh, 0.0);
  const PgmCounts pgm = countPgm(realMapsDir() + "/tutorials_speed_mask.pgm");
  const OccupancyGridData ros1 = loadMapFile(yaml);
  const OccupancyGridData nav2 = loadMapFile(yaml, MapMode::Nav2Scale);
  ASSERT_EQ(ros1.width, pgm.width);
  ASSERT_EQ(ros1.height, pgm.height);
  ASSERT_EQ(nav2.data.size(), ros1.data.size());

  // With thresholds 0 and 1 nothing is strictly beyond them: ROS 1 gives 1 + 98 * p truncated
  // everywhere (white 1, black 99); Nav2 gives round(100 * p) (white 0, black 100).
  const auto ros1_expected = expectedValues(pgm, [](double p) { return static_cast<int>(1.0 + 98.0 * p); });
  const auto nav2_expected = expectedValues(pgm, [](double p) { return static_cast<int>(std::rint(100.0 * p)); });
  EXPECT_EQ(histogram(ros1), ros1_expected);
  EXPECT_EQ(histogram(nav2), nav2_expected);
  // The speed zones' grey levels as Nav2's tutorial documents them: 20, 40, 70 % and the black border.
  for (int v : {0, 20, 40, 70, 100})
    EXPECT_EQ(nav2_expected.count(v), 1u) << v;
  // Cell by cell, the two rules differ only by the grey's rounding, never by more than 1.
  for (size_t k = 0; k < ros1.data.size(); ++k)
  {
    ASSERT_LE(std::abs(ros1.data[k] - nav2.data[k]), 1) << "cell " << k;
  }
}
}  // namespace

// ---- Found by the fuzz target test/fuzz/fuzz_map_file.cpp (inputs in test/fuzz/regressions/map_file/)

namespace
{
std::vector<uint8_t> bytesOf(const std::string& s)
{
  return std::vector<uint8_t>(s.begin(), s.end());
}
}  // namespace

// A 30-byte PNM whose header says 25102 x 25102 colour pixels made the reader allocate 1.9 GB for the
// pixels before it noticed that the data was missing (the fuzzer's out-of-memory). Now refused as
// truncated before anything is allocated, in binary and ASCII form.
TEST(MapFileFuzzRegressions, PnmHeaderPromisingAHugeImageIsRefusedBeforeAllocating)
{
  MapFileInfo info;
  info.resolution = 0.05;
  for (const char* text :
       {"P3 25102 25102 255 0 0 0\n", "P6 99999 99999 255\n\x01\x02\x03", "P5 100000 100000 65535\n\x01\x02"})
  {
    try
    {
      costmap_layers::io::decodeMapImage(bytesOf(text), info, "huge.pnm");
      ADD_FAILURE() << "accepted " << text;
    }
    catch (const std::runtime_error& e)
    {
      // Refused for its size (more cells than the node's limit) or for the data it lacks; either way
      // before the pixels are allocated.
      const std::string what = e.what();
      EXPECT_TRUE(what.find("truncated") != std::string::npos || what.find("absurdly large") != std::string::npos)
          << what;
      EXPECT_NE(what.find("huge.pnm"), std::string::npos) << what;
    }
  }
}

// The same for PNG: an IHDR of 100000 x 100000 RGBA pixels followed by a few bytes of data made the
// decoder allocate 40 GB before libpng found the data missing. (100000 x 100000 is now refused for
// its cell count alone; 20000 x 20000, exactly the cell limit, still needs the data check: 1.6 GB of
// RGBA pixels cannot come from a few bytes of deflate data.)
TEST(MapFileFuzzRegressions, PngHeaderPromisingAHugeImageIsRefusedBeforeAllocating)
{
  const std::string ihdr{0,
                         0,
                         static_cast<char>(0x4E),
                         static_cast<char>(0x20),  // width 20000
                         0,
                         0,
                         static_cast<char>(0x4E),
                         static_cast<char>(0x20),  // height 20000
                         8,
                         6,
                         0,
                         0,
                         0};  // 8-bit RGBA
  const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + pngChunk("IHDR", ihdr) +
                          pngChunk("IDAT", std::string("\x78\x9c\x03\x00\x00\x00\x00\x01", 8)) + pngChunk("IEND", "");
  MapFileInfo info;
  info.resolution = 0.05;
  try
  {
    costmap_layers::io::decodeMapImage(bytesOf(png), info, "huge.png");
    ADD_FAILURE() << "accepted";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
}

// The in-memory entry points the fuzz target uses read exactly what the file functions read.
TEST(MapFileFuzzRegressions, InMemoryDecodingMatchesTheFiles)
{
  const std::string yaml =
      "image: m.pgm\nresolution: 0.5\norigin: [1, 2, 0]\nnegate: 0\n"
      "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: scale\n";
  const MapFileInfo info = costmap_layers::io::parseMapFileInfo(yaml, "/maps/m.yaml");
  EXPECT_EQ(info.image_path, "/maps/m.pgm");
  EXPECT_EQ(info.mode, MapMode::Scale);
  const OccupancyGridData g = costmap_layers::io::decodeMapImage(bytesOf("P2 2 1 255 0 255\n"), info, "m.pgm");
  ASSERT_EQ(g.data.size(), 2u);
  EXPECT_EQ(g.data[0], 100);
  EXPECT_EQ(g.data[1], 0);
  EXPECT_DOUBLE_EQ(g.origin_y, 2.0);
}
