// Writing costmaps and occupancy grids as colour PNG pictures (for people to look at), and raw cost
// bytes (for scripts), without ROS. Uses libpng.
//
// The grid is drawn one pixel per cell with +y up: data row 0 (the lowest y) is the bottom row of
// the picture. Colours, one per cost class:
//   free         cost 0            white          (255, 255, 255)
//   cost ramp    cost 1..252       light blue (190, 220, 255) -> purple (120, 60, 210) halfway
//                                  -> crimson (200, 0, 60) at 252, linear in between
//   inscribed    cost 253          orange         (255, 150, 0)
//   lethal       cost 254          black          (0, 0, 0)
//   unknown      cost 255          mid grey       (128, 128, 128)
// Occupancy values (nav_msgs/OccupancyGrid, as costmap_2d publishes a costmap) use the colour of the
// cost they come from: 0 free, 1..98 the ramp (value v drawn as cost 1 + round((v - 1) * 251 / 97)),
// 99 inscribed, 100 lethal, -1 unknown; any other value (invalid) is drawn as unknown.
//
// With `legend`, a band is added below the grid: a swatch and a label for each class ("free",
// "cost 1-252", "inscribed 253", "lethal 254", "unknown 255"; for occupancy "free 0",
// "occupancy 1-98", "inscribed 99", "lethal 100", "unknown -1"), written with a built-in 5x7 pixel
// font (with descenders), enlarged 2x or 3x for wide maps. The band wraps its entries onto several lines when needed;
// when even one entry is wider than the grid, the picture is widened and the area right of the grid
// is filled with the band's light tan colour (235, 225, 190). The grid always starts at the top-left
// pixel.
//
// With PngOptions, each cell may be drawn as zoom x zoom pixels (1..8), and labels may be written on the
// grid: each label's text (letters, digits, space and - . : / ( ) , _ ?; letters drawn lowercase) on a
// tan box with a dark frame, centred on its place and kept inside the grid's part of the picture; the
// font is enlarged with the zoom (2x at zoom 2 and 3, 3x at 4 and 5, ...).
//
// Errors (null data, zero size, file not writable, libpng failure) throw std::runtime_error naming
// the path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace costmap_layers
{
namespace io
{
struct Rgb
{
  uint8_t r = 0;
  uint8_t g = 0;
  uint8_t b = 0;
  bool operator==(const Rgb& o) const { return r == o.r && g == o.g && b == o.b; }
  bool operator!=(const Rgb& o) const { return !(*this == o); }
};

/// Text written on the grid, centred on (col, row) in cells: (0, 0) is the outer corner of cell 0 (the
/// lowest x and y), (width, height) the opposite corner.
struct PngLabel
{
  double col = 0.0;
  double row = 0.0;
  std::string text;
};

constexpr unsigned kMaxPngZoom = 8;
constexpr size_t kMaxPngLabels = 64;
constexpr size_t kMaxPngLabelLength = 48;
constexpr unsigned long kMaxPngZoomedPixels = 1UL << 27;  // 134 Mpx, 403 MB of RGB: a picture, not a dump

struct PngOptions
{
  bool legend = true;
  unsigned zoom = 1;
  std::vector<PngLabel> labels;
};

/// The colour of a costmap cost (see above).
Rgb costColour(uint8_t cost);
/// The colour of an occupancy value (see above).
Rgb occupancyColour(int8_t value);
/// The colour of the legend band and of the padding right of the grid.
Rgb legendBackground();

/// `cells`: width * height costs, row-major, row 0 = lowest y.
void writeCostmapPng(const std::string& path, const uint8_t* cells, unsigned width, unsigned height,
                     bool legend = true);

/// The same with a zoom and labels; every option is checked before anything is written.
void writeCostmapPng(const std::string& path, const uint8_t* cells, unsigned width, unsigned height,
                     const PngOptions& options);

/// `values`: width * height occupancy values (-1, 0..100), row-major, row 0 = lowest y.
void writeOccupancyPng(const std::string& path, const int8_t* values, unsigned width, unsigned height,
                       bool legend = true);

/// Writes n bytes as they are (e.g. a costmap's cells, row 0 = lowest y first).
void writeRawBytes(const std::string& path, const uint8_t* cells, size_t n);
}  // namespace io
}  // namespace costmap_layers
