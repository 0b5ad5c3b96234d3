// Tests of costmap_layers::io PNG/raw writers: read the PNG back with libpng and check the colour of
// every class, the vertical flip, the legend band and the errors.
#include "costmap_layers/io/png_writer.hpp"
#include "temp_dir_test.hpp"

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

using costmap_layers::io::costColour;
using costmap_layers::io::legendBackground;
using costmap_layers::io::occupancyColour;
using costmap_layers::io::PngLabel;
using costmap_layers::io::PngOptions;
using costmap_layers::io::Rgb;
using costmap_layers::io::writeCostmapPng;
using costmap_layers::io::writeOccupancyPng;
using costmap_layers::io::writeRawBytes;

namespace
{
struct Picture
{
  uint32_t width = 0;
  uint32_t height = 0;
  int color_type = -1;
  int bit_depth = 0;
  std::vector<uint8_t> rgb;
  std::vector<png_bytep> rows;
  Rgb at(uint32_t x, uint32_t y) const
  {
    const uint8_t* p = &rgb[(static_cast<size_t>(y) * width + x) * 3];
    return Rgb{p[0], p[1], p[2]};
  }
};

/// Reads an 8-bit RGB PNG; false when libpng fails or the file is another kind of PNG.
bool readRgbPngRaw(const char* path, Picture& pic)
{
  FILE* fp = std::fopen(path, "rb");
  if (fp == nullptr) return false;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png)))
  {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(fp);
    return false;
  }
  png_init_io(png, fp);
  png_read_info(png, info);
  pic.width = png_get_image_width(png, info);
  pic.height = png_get_image_height(png, info);
  pic.color_type = png_get_color_type(png, info);
  pic.bit_depth = png_get_bit_depth(png, info);
  if (pic.color_type != PNG_COLOR_TYPE_RGB || pic.bit_depth != 8)
  {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(fp);
    return false;
  }
  pic.rgb.resize(static_cast<size_t>(pic.width) * pic.height * 3);
  pic.rows.resize(pic.height);
  for (uint32_t y = 0; y < pic.height; ++y)
    pic.rows[y] = pic.rgb.data() + static_cast<size_t>(y) * pic.width * 3;
  png_read_image(png, pic.rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(fp);
  return true;
}

Picture readRgbPng(const std::string& path)
{
  Picture pic;
  EXPECT_TRUE(readRgbPngRaw(path.c_str(), pic)) << "cannot read back " << path;
  return pic;
}

int distance(const Rgb& a, const Rgb& b)
{
  return std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b);
}

std::string str(const Rgb& c)
{
  return "(" + std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b) + ")";
}

template <typename F>
std::string errorOf(F&& f)
{
  try
  {
    f();
  }
  catch (const std::runtime_error& e)
  {
    return e.what();
  }
  return "<no exception>";
}

class PngWriterTest : public TempDirTest
{
};

const Rgb kWhite{255, 255, 255};
const Rgb kOrange{255, 150, 0};
const Rgb kBlack{0, 0, 0};
const Rgb kGrey{128, 128, 128};

TEST(PngColours, ClassesAreDistinct)
{
  EXPECT_EQ(costColour(0), kWhite);
  EXPECT_EQ(costColour(253), kOrange);
  EXPECT_EQ(costColour(254), kBlack);
  EXPECT_EQ(costColour(255), kGrey);
  EXPECT_EQ(costColour(1), (Rgb{190, 220, 255}));  // light blue
  EXPECT_EQ(costColour(252), (Rgb{200, 0, 60}));   // crimson
  const std::vector<Rgb> special = {kWhite, kOrange, kBlack, kGrey, legendBackground()};
  for (size_t a = 0; a < special.size(); ++a)
  {
    for (size_t b = a + 1; b < special.size(); ++b)
      EXPECT_GT(distance(special[a], special[b]), 60) << str(special[a]) << " vs " << str(special[b]);
  }
  // Every ramp colour is clearly different from every class colour, and the ramp changes along.
  for (int c = 1; c <= 252; ++c)
  {
    const Rgb rc = costColour(static_cast<uint8_t>(c));
    for (const Rgb& s : special)
      EXPECT_GT(distance(rc, s), 60) << "cost " << c << " " << str(rc) << " vs " << str(s);
    if (c > 25)
    {
      EXPECT_GT(distance(rc, costColour(static_cast<uint8_t>(c - 25))), 10) << c;
    }
  }
  EXPECT_GT(distance(costColour(1), costColour(126)), 150);
  EXPECT_GT(distance(costColour(126), costColour(252)), 150);
}

TEST(PngColours, OccupancyUsesTheColourOfItsCost)
{
  EXPECT_EQ(occupancyColour(0), costColour(0));
  EXPECT_EQ(occupancyColour(1), costColour(1));
  EXPECT_EQ(occupancyColour(98), costColour(252));
  EXPECT_EQ(occupancyColour(50), costColour(128));  // 1 + round(49 * 251 / 97) = 128
  EXPECT_EQ(occupancyColour(99), costColour(253));
  EXPECT_EQ(occupancyColour(100), costColour(254));
  EXPECT_EQ(occupancyColour(-1), costColour(255));
  EXPECT_EQ(occupancyColour(101), costColour(255));  // invalid values are drawn as unknown
  EXPECT_EQ(occupancyColour(-7), costColour(255));
}

// cells row 0 (lowest y): 0 1 252; row 1: 253 254 255. Picture row 0 (top) must show row 1.
TEST_F(PngWriterTest, CostmapClassesAndFlipWithoutLegend)
{
  const std::vector<uint8_t> cells = {0, 1, 252, 253, 254, 255};
  writeCostmapPng(tmp("c.png"), cells.data(), 3, 2, false);
  const Picture pic = readRgbPng(tmp("c.png"));
  ASSERT_EQ(pic.width, 3u);
  ASSERT_EQ(pic.height, 2u);
  EXPECT_EQ(pic.at(0, 0), kOrange);
  EXPECT_EQ(pic.at(1, 0), kBlack);
  EXPECT_EQ(pic.at(2, 0), kGrey);
  EXPECT_EQ(pic.at(0, 1), kWhite);
  EXPECT_EQ(pic.at(1, 1), costColour(1));
  EXPECT_EQ(pic.at(2, 1), costColour(252));
}

TEST_F(PngWriterTest, TallGridFlip)
{
  // 1 wide, 4 tall: lethal at the lowest y must be the bottom pixel.
  const std::vector<uint8_t> cells = {254, 0, 0, 253};
  writeCostmapPng(tmp("t.png"), cells.data(), 1, 4, false);
  const Picture pic = readRgbPng(tmp("t.png"));
  ASSERT_EQ(pic.height, 4u);
  EXPECT_EQ(pic.at(0, 3), kBlack);
  EXPECT_EQ(pic.at(0, 0), kOrange);
  EXPECT_EQ(pic.at(0, 1), kWhite);
}

TEST_F(PngWriterTest, OccupancyClassesAndFlip)
{
  const std::vector<int8_t> values = {0, 1, 98, 99, 100, -1};
  writeOccupancyPng(tmp("o.png"), values.data(), 3, 2, false);
  const Picture pic = readRgbPng(tmp("o.png"));
  ASSERT_EQ(pic.width, 3u);
  ASSERT_EQ(pic.height, 2u);
  EXPECT_EQ(pic.at(0, 0), kOrange);
  EXPECT_EQ(pic.at(1, 0), kBlack);
  EXPECT_EQ(pic.at(2, 0), kGrey);
  EXPECT_EQ(pic.at(0, 1), kWhite);
  EXPECT_EQ(pic.at(1, 1), costColour(1));
  EXPECT_EQ(pic.at(2, 1), costColour(252));
}

TEST_F(PngWriterTest, LegendPadsSmallMapsAndShowsEverySwatch)
{
  const std::vector<uint8_t> cells = {254, 0, 0, 255};
  writeCostmapPng(tmp("l.png"), cells.data(), 2, 2, true);
  const Picture pic = readRgbPng(tmp("l.png"));
  ASSERT_GT(pic.width, 60u);   // widened for the labels
  ASSERT_GT(pic.height, 40u);  // a band below the grid
  // the grid, top-left, flipped
  EXPECT_EQ(pic.at(0, 1), kBlack);
  EXPECT_EQ(pic.at(1, 1), kWhite);
  EXPECT_EQ(pic.at(0, 0), kWhite);
  EXPECT_EQ(pic.at(1, 0), kGrey);
  // padding right of the grid
  EXPECT_EQ(pic.at(2, 0), legendBackground());
  EXPECT_EQ(pic.at(pic.width - 1, 1), legendBackground());
  // the band holds swatches of each class and dark text
  std::set<std::tuple<int, int, int>> band;
  size_t ink = 0;
  for (uint32_t y = 2; y < pic.height; ++y)
  {
    for (uint32_t x = 0; x < pic.width; ++x)
    {
      const Rgb c = pic.at(x, y);
      band.insert({c.r, c.g, c.b});
      if (distance(c, Rgb{25, 25, 25}) == 0) ++ink;
    }
  }
  for (const Rgb& c : {kWhite, kOrange, kBlack, kGrey, costColour(1), costColour(252)})
    EXPECT_EQ(band.count({c.r, c.g, c.b}), 1u) << "no swatch " << str(c);
  EXPECT_GT(ink, 200u);
}

TEST_F(PngWriterTest, LegendOnWideMapKeepsTheWidth)
{
  const unsigned w = 400, h = 30;
  std::vector<uint8_t> cells(w * h, 0);
  for (unsigned x = 0; x < w; ++x)
    cells[x] = static_cast<uint8_t>(x % 256);  // row 0: all costs
  writeCostmapPng(tmp("w.png"), cells.data(), w, h, true);
  const Picture pic = readRgbPng(tmp("w.png"));
  EXPECT_EQ(pic.width, w);
  EXPECT_GT(pic.height, h);
  for (unsigned x = 0; x < w; ++x)
    ASSERT_EQ(pic.at(x, h - 1), costColour(static_cast<uint8_t>(x % 256))) << x;
  EXPECT_EQ(pic.at(5, 0), kWhite);
  // occupancy legend too
  std::vector<int8_t> occ(w * h, -1);
  writeOccupancyPng(tmp("wo.png"), occ.data(), w, h, true);
  const Picture po = readRgbPng(tmp("wo.png"));
  EXPECT_EQ(po.width, w);
  EXPECT_GT(po.height, h);
  EXPECT_EQ(po.at(0, 0), kGrey);
}

TEST_F(PngWriterTest, Errors)
{
  const std::vector<uint8_t> cells = {0, 1, 2, 3};
  const std::string bad_dir = tmp("no_such_dir/x.png");
  std::string e = errorOf([&] { writeCostmapPng(bad_dir, cells.data(), 2, 2); });
  EXPECT_NE(e.find(bad_dir), std::string::npos) << e;
  e = errorOf([&] { writeCostmapPng(tmp("n.png"), nullptr, 2, 2); });
  EXPECT_NE(e.find("n.png"), std::string::npos) << e;
  e = errorOf([&] { writeCostmapPng(tmp("z.png"), cells.data(), 0, 2); });
  EXPECT_NE(e.find("z.png"), std::string::npos) << e;
  EXPECT_NE(e.find("empty"), std::string::npos) << e;
  e = errorOf([&] { writeOccupancyPng(bad_dir, reinterpret_cast<const int8_t*>(cells.data()), 2, 2); });
  EXPECT_NE(e.find(bad_dir), std::string::npos) << e;
  e = errorOf([&] { writeOccupancyPng(tmp("n2.png"), nullptr, 2, 2, false); });
  EXPECT_NE(e.find("n2.png"), std::string::npos) << e;
  EXPECT_FALSE(std::filesystem::exists(tmp("n.png")));
}

const Rgb kTan{235, 225, 190};   // the label's box (the legend band's colour)
const Rgb kFrame{90, 90, 90};    // its frame
const Rgb kInkC{25, 25, 25};     // its text

PngOptions noLegend(unsigned zoom)
{
  PngOptions o;
  o.legend = false;
  o.zoom = zoom;
  return o;
}

TEST_F(PngWriterTest, ZoomDrawsEachCellAsASquareBlock)
{
  // 3 x 2 cells, row 0 (lowest y) = {0, 253, 254}, row 1 = {255, 1, 252}; at zoom 3 a 9 x 6 picture.
  const std::vector<uint8_t> cells = {0, 253, 254, 255, 1, 252};
  writeCostmapPng(tmp("z3.png"), cells.data(), 3, 2, noLegend(3));
  const Picture pic = readRgbPng(tmp("z3.png"));
  ASSERT_EQ(pic.width, 9u);
  ASSERT_EQ(pic.height, 6u);
  const Rgb top[3] = {kGrey, costColour(1), costColour(252)};  // row 1, drawn at the top
  const Rgb bottom[3] = {kWhite, kOrange, kBlack};
  for (uint32_t y = 0; y < 6; ++y)
    for (uint32_t x = 0; x < 9; ++x)
      ASSERT_EQ(pic.at(x, y), y < 3 ? top[x / 3] : bottom[x / 3]) << x << "," << y;
  // with the legend, the band starts below the zoomed grid
  PngOptions o;
  o.zoom = 4;
  writeCostmapPng(tmp("z4.png"), cells.data(), 3, 2, o);
  const Picture legend = readRgbPng(tmp("z4.png"));
  EXPECT_EQ(legend.at(0, 7), bottom[0]);
  EXPECT_EQ(legend.at(0, 8), kFrame);  // the rule between grid and band
  EXPECT_GT(legend.height, 8u);
}

TEST_F(PngWriterTest, ALabelIsCentredOnItsPlaceOnAFramedBox)
{
  // 40 x 20 free cells at zoom 2: an 80 x 40 picture. "ab" at (20, 10) cells = pixel (40, 20). Font
  // scale 2 at zoom 2: text 2 * 12 - 2 = 22 px wide, 18 high; padding 4 and a 1 px frame on each side:
  // a 32 x 28 box from (40 - 16, 20 - 14) = (24, 6) to (55, 33).
  const std::vector<uint8_t> cells(40 * 20, 0);
  PngOptions o = noLegend(2);
  o.labels.push_back(PngLabel{20.0, 10.0, "ab"});
  writeCostmapPng(tmp("l.png"), cells.data(), 40, 20, o);
  const Picture pic = readRgbPng(tmp("l.png"));
  ASSERT_EQ(pic.width, 80u);
  EXPECT_EQ(pic.at(24, 6), kFrame);
  EXPECT_EQ(pic.at(55, 33), kFrame);
  EXPECT_EQ(pic.at(25, 7), kTan);
  EXPECT_EQ(pic.at(23, 6), kWhite);
  EXPECT_EQ(pic.at(56, 33), kWhite);
  EXPECT_EQ(pic.at(24, 34), kWhite);
  size_t ink_inside = 0, not_white_outside = 0;
  for (uint32_t y = 0; y < pic.height; ++y)
    for (uint32_t x = 0; x < pic.width; ++x)
    {
      const bool inside = x >= 24 && x <= 55 && y >= 6 && y <= 33;
      if (inside && pic.at(x, y) == kInkC) ++ink_inside;
      if (!inside && pic.at(x, y) != kWhite) ++not_white_outside;
    }
  EXPECT_EQ(ink_inside, 4u * (14 + 16));  // 'a' and 'b' have 14 and 16 inked font pixels, each 2 x 2
  EXPECT_EQ(not_white_outside, 0u);
}

TEST_F(PngWriterTest, ALabelAtTheCornerStaysInsideTheGrid)
{
  // At (0, 0), the bottom-left corner: the box is moved up and right to fit, and the legend band
  // below the grid is not drawn over.
  const std::vector<uint8_t> cells(30 * 10, 0);
  PngOptions o;
  o.zoom = 3;
  o.labels.push_back(PngLabel{0.0, 0.0, "corner"});
  o.labels.push_back(PngLabel{30.0, 10.0, "top right"});
  writeCostmapPng(tmp("c.png"), cells.data(), 30, 10, o);
  const Picture pic = readRgbPng(tmp("c.png"));
  EXPECT_EQ(pic.at(0, 29), kFrame);   // the box's bottom-left corner on the grid's
  EXPECT_EQ(pic.at(89, 0), kFrame);   // the other's top-right corner on the grid's
  EXPECT_EQ(pic.at(0, 30), kFrame);   // the legend's rule, one row below the grid, untouched
  EXPECT_EQ(pic.at(1, 31), legendBackground());
}

TEST_F(PngWriterTest, BadOptionsAreRefusedNamingTheValueAndWriteNothing)
{
  const std::vector<uint8_t> cells(4, 0);
  struct Case
  {
    PngOptions options;
    std::string needle;
  };
  auto withLabel = [](double col, double row, std::string text)
  {
    PngOptions o;
    o.labels.push_back(PngLabel{col, row, std::move(text)});
    return o;
  };
  PngOptions many;
  many.labels.assign(65, PngLabel{1.0, 1.0, "x"});
  std::vector<Case> cases = {
      {noLegend(0), "zoom 0 is outside 1..8"},
      {noLegend(9), "zoom 9 is outside 1..8"},
      {many, "65 labels, at most 64"},
      {withLabel(1, 1, ""), "1..48 characters (it has 0)"},
      {withLabel(1, 1, std::string(49, 'a')), "(it has 49)"},
      {withLabel(1, 1, "dock#1"), "the character '#' has no glyph"},
      {withLabel(1, 1, "a\nb"), "the character of code 10 has no glyph"},
      {withLabel(1, 1, "caf\xc3\xa9"), "of code 195"},
      {withLabel(-0.01, 1, "left"), "outside the 2x2 grid"},
      {withLabel(1, 2.01, "above"), "outside the 2x2 grid"},
      {withLabel(std::nan(""), 1, "nan"), "outside the 2x2 grid"},
      {withLabel(1, 1e300, "far"), "outside the 2x2 grid"},
  };
  for (const Case& c : cases)
  {
    const std::string e = errorOf([&] { writeCostmapPng(tmp("bad.png"), cells.data(), 2, 2, c.options); });
    EXPECT_NE(e.find(c.needle), std::string::npos) << e;
    EXPECT_NE(e.find("bad.png"), std::string::npos) << e;
    EXPECT_FALSE(std::filesystem::exists(tmp("bad.png"))) << c.needle;
  }
  // The edges themselves are accepted: zoom 1 and 8, 64 labels of 48 characters, places on the border.
  PngOptions edge = noLegend(8);
  edge.labels.assign(63, PngLabel{2.0, 2.0, std::string(48, 'z')});
  edge.labels.push_back(PngLabel{0.0, 0.0, "(a/b, c_d) 1.5: -?"});
  writeCostmapPng(tmp("edge.png"), cells.data(), 2, 2, edge);
  EXPECT_EQ(readRgbPng(tmp("edge.png")).width, 16u);
  // Too many pixels: refused before any cell is read (the buffer is deliberately small).
  const std::string e = errorOf([&] { writeCostmapPng(tmp("huge.png"), cells.data(), 20000, 20000, noLegend(2)); });
  EXPECT_NE(e.find("20000x20000 grid at zoom 2 is more than 134217728 pixels"), std::string::npos) << e;
}

TEST_F(PngWriterTest, RawBytes)
{
  const std::vector<uint8_t> cells = {0, 1, 128, 253, 254, 255};
  writeRawBytes(tmp("raw.bin"), cells.data(), cells.size());
  std::ifstream in(tmp("raw.bin"), std::ios::binary);
  const std::vector<uint8_t> back((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(back, cells);
  writeRawBytes(tmp("empty.bin"), nullptr, 0);
  EXPECT_EQ(std::filesystem::file_size(tmp("empty.bin")), 0u);
  const std::string bad = tmp("no_such_dir/raw.bin");
  std::string e = errorOf([&] { writeRawBytes(bad, cells.data(), cells.size()); });
  EXPECT_NE(e.find(bad), std::string::npos) << e;
  e = errorOf([&] { writeRawBytes(tmp("null.bin"), nullptr, 3); });
  EXPECT_NE(e.find("null.bin"), std::string::npos) << e;
}
}  // namespace
