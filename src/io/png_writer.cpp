#include "costmap_layers/io/png_writer.hpp"

#include <png.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace costmap_layers
{
namespace io
{
namespace
{
const Rgb kFree{255, 255, 255};
const Rgb kInscribed{255, 150, 0};
const Rgb kLethal{0, 0, 0};
const Rgb kUnknown{128, 128, 128};
const Rgb kRampLow{190, 220, 255};
const Rgb kRampMid{120, 60, 210};
const Rgb kRampHigh{200, 0, 60};
const Rgb kBand{235, 225, 190};
const Rgb kInk{25, 25, 25};
const Rgb kRule{90, 90, 90};

uint8_t mix(uint8_t a, uint8_t b, double t)
{
  return static_cast<uint8_t>(std::lround(a + (static_cast<double>(b) - a) * t));
}

Rgb mix(const Rgb& a, const Rgb& b, double t)
{
  return Rgb{mix(a.r, b.r, t), mix(a.g, b.g, t), mix(a.b, b.b, t)};
}

// ---- A 5x7 bitmap font: each glyph is 7 rows of 5 columns, '#' = ink, plus 2 optional rows
// below the baseline for the descenders of g, j, p, q, y. ----
struct Glyph
{
  char c;
  const char* rows[9];
};

// clang-format off
const Glyph kFont[] = {
  {'a', {".....", ".....", ".###.", "....#", ".####", "#...#", ".####"}},
  {'b', {"#....", "#....", "####.", "#...#", "#...#", "#...#", "####."}},
  {'c', {".....", ".....", ".###.", "#....", "#....", "#...#", ".###."}},
  {'d', {"....#", "....#", ".####", "#...#", "#...#", "#...#", ".####"}},
  {'e', {".....", ".....", ".###.", "#...#", "#####", "#....", ".###."}},
  {'f', {"..##.", ".#..#", ".#...", "###..", ".#...", ".#...", ".#..."}},
  {'g', {".....", ".....", ".####", "#...#", "#...#", "#...#", ".####", "....#", ".###."}},
  {'h', {"#....", "#....", "#.##.", "##..#", "#...#", "#...#", "#...#"}},
  {'i', {"..#..", ".....", ".##..", "..#..", "..#..", "..#..", ".###."}},
  {'j', {"...#.", ".....", "..##.", "...#.", "...#.", "...#.", "...#.", "#..#.", ".##.."}},
  {'k', {"#....", "#....", "#..#.", "#.#..", "##...", "#.#..", "#..#."}},
  {'l', {".##..", "..#..", "..#..", "..#..", "..#..", "..#..", ".###."}},
  {'m', {".....", ".....", "##.#.", "#.#.#", "#.#.#", "#...#", "#...#"}},
  {'n', {".....", ".....", "#.##.", "##..#", "#...#", "#...#", "#...#"}},
  {'o', {".....", ".....", ".###.", "#...#", "#...#", "#...#", ".###."}},
  {'p', {".....", ".....", "####.", "#...#", "#...#", "#...#", "####.", "#....", "#...."}},
  {'q', {".....", ".....", ".####", "#...#", "#...#", "#...#", ".####", "....#", "....#"}},
  {'r', {".....", ".....", "#.##.", "##..#", "#....", "#....", "#...."}},
  {'s', {".....", ".....", ".####", "#....", ".###.", "....#", "####."}},
  {'t', {".#...", ".#...", "###..", ".#...", ".#...", ".#..#", "..##."}},
  {'u', {".....", ".....", "#...#", "#...#", "#...#", "#..##", ".##.#"}},
  {'v', {".....", ".....", "#...#", "#...#", "#...#", ".#.#.", "..#.."}},
  {'w', {".....", ".....", "#...#", "#...#", "#.#.#", "#.#.#", ".#.#."}},
  {'x', {".....", ".....", "#...#", ".#.#.", "..#..", ".#.#.", "#...#"}},
  {'y', {".....", ".....", "#...#", "#...#", "#...#", "#...#", ".####", "....#", ".###."}},
  {'z', {".....", ".....", "#####", "...#.", "..#..", ".#...", "#####"}},
  {'0', {".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###."}},
  {'1', {"..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###."}},
  {'2', {".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####"}},
  {'3', {"#####", "...#.", "..#..", "...#.", "....#", "#...#", ".###."}},
  {'4', {"...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#."}},
  {'5', {"#####", "#....", "####.", "....#", "....#", "#...#", ".###."}},
  {'6', {"..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###."}},
  {'7', {"#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#..."}},
  {'8', {".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###."}},
  {'9', {".###.", "#...#", "#...#", ".####", "....#", "...#.", ".##.."}},
  {'-', {".....", ".....", ".....", ".###.", ".....", ".....", "....."}},
  {'.', {".....", ".....", ".....", ".....", ".....", ".##..", ".##.."}},
  {':', {".....", ".##..", ".##..", ".....", ".##..", ".##..", "....."}},
  {' ', {".....", ".....", ".....", ".....", ".....", ".....", "....."}},
  {'?', {".###.", "#...#", "....#", "...#.", "..#..", ".....", "..#.."}},
  {'/', {".....", "....#", "...#.", "..#..", ".#...", "#....", "....."}},
  {'(', {"...#.", "..#..", ".#...", ".#...", ".#...", "..#..", "...#."}},
  {')', {".#...", "..#..", "...#.", "...#.", "...#.", "..#..", ".#..."}},
  {',', {".....", ".....", ".....", ".....", ".##..", "..#..", ".#..."}},
  {'_', {".....", ".....", ".....", ".....", ".....", ".....", "#####"}},
};
// clang-format on

const Glyph& glyphFor(char c)
{
  if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  for (const Glyph& g : kFont)
  {
    if (g.c == c) return g;
  }
  for (const Glyph& g : kFont)
  {
    if (g.c == '?') return g;
  }
  return kFont[0];
}

bool hasGlyph(char c)
{
  if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return std::any_of(std::begin(kFont), std::end(kFont), [c](const Glyph& g) { return g.c == c; });
}

constexpr int kGlyphW = 5;
constexpr int kGlyphH = 9;   // 7 rows + 2 descender rows
constexpr int kAdvance = 6;  // glyph width + 1 column of space

class Canvas
{
public:
  Canvas(unsigned w, unsigned h, Rgb fill) : w_(w), h_(h), px_(static_cast<size_t>(w) * h * 3)
  {
    for (size_t k = 0; k < px_.size(); k += 3)
    {
      px_[k] = fill.r;
      px_[k + 1] = fill.g;
      px_[k + 2] = fill.b;
    }
  }
  void set(long x, long y, Rgb c)
  {
    if (x < 0 || y < 0 || x >= static_cast<long>(w_) || y >= static_cast<long>(h_)) return;
    uint8_t* p = &px_[(static_cast<size_t>(y) * w_ + static_cast<size_t>(x)) * 3];
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
  }
  void rect(long x, long y, long w, long h, Rgb c)
  {
    for (long j = y; j < y + h; ++j)
    {
      for (long i = x; i < x + w; ++i)
        set(i, j, c);
    }
  }
  void frame(long x, long y, long w, long h, long t, Rgb c)
  {
    rect(x, y, w, t, c);
    rect(x, y + h - t, w, t, c);
    rect(x, y, t, h, c);
    rect(x + w - t, y, t, h, c);
  }
  void text(long x, long y, const std::string& s, int scale, Rgb c)
  {
    for (char ch : s)
    {
      const Glyph& g = glyphFor(ch);
      for (int r = 0; r < kGlyphH; ++r)
      {
        if (g.rows[r] == nullptr) continue;
        for (int q = 0; q < kGlyphW; ++q)
        {
          if (g.rows[r][q] == '#') rect(x + q * scale, y + r * scale, scale, scale, c);
        }
      }
      x += kAdvance * scale;
    }
  }
  unsigned width() const { return w_; }
  unsigned height() const { return h_; }
  const uint8_t* row(unsigned y) const { return px_.data() + static_cast<size_t>(y) * w_ * 3; }

private:
  unsigned w_;
  unsigned h_;
  std::vector<uint8_t> px_;
};

struct LegendEntry
{
  enum class Kind
  {
    Solid,
    Ramp
  } kind;
  Rgb colour;
  std::string label;
};

struct LegendLayout
{
  int scale = 1;
  long margin = 0;
  long line_h = 0;
  long swatch = 0;
  long gap = 0;
  std::vector<long> item_w;
  std::vector<std::pair<long, long>> pos;  // top-left of each entry, relative to the band
  long width = 0;                          // minimal width the band needs
  long height = 0;
};

long entryWidth(const LegendEntry& e, int scale)
{
  const long swatch_w = (e.kind == LegendEntry::Kind::Ramp ? 3 : 1) * 8 * scale;
  return swatch_w + 3 * scale + static_cast<long>(e.label.size()) * kAdvance * scale - scale;
}

LegendLayout layoutLegend(const std::vector<LegendEntry>& entries, unsigned map_width)
{
  LegendLayout l;
  l.scale = map_width >= 900 ? 3 : (map_width >= 300 ? 2 : 1);
  l.margin = 4 * l.scale;
  l.line_h = 12 * l.scale;
  l.gap = 9 * l.scale;
  long widest = 0;
  for (const auto& e : entries)
  {
    l.item_w.push_back(entryWidth(e, l.scale));
    widest = std::max(widest, l.item_w.back());
  }
  const long band_w = std::max<long>(static_cast<long>(map_width), widest + 2 * l.margin);
  long x = l.margin;
  long y = l.margin + l.scale;  // below the rule line
  for (size_t k = 0; k < entries.size(); ++k)
  {
    if (x > l.margin && x + l.item_w[k] > band_w - l.margin)
    {
      x = l.margin;
      y += l.line_h;
    }
    l.pos.emplace_back(x, y);
    x += l.item_w[k] + l.gap;
  }
  l.width = band_w;
  l.height = y + 9 * l.scale + l.margin;  // the last line's swatch (8) or descenders (9)
  return l;
}

void drawLegend(Canvas& canvas, long top, const std::vector<LegendEntry>& entries, const LegendLayout& l)
{
  const int s = l.scale;
  canvas.rect(0, top, canvas.width(), s, kRule);  // a rule between the grid and the band
  for (size_t k = 0; k < entries.size(); ++k)
  {
    const LegendEntry& e = entries[k];
    const long x = l.pos[k].first;
    const long y = top + l.pos[k].second;
    const long sw = (e.kind == LegendEntry::Kind::Ramp ? 3 : 1) * 8 * s;
    const long sh = 8 * s;
    if (e.kind == LegendEntry::Kind::Ramp)
    {
      for (long i = 0; i < sw; ++i)
      {
        const auto cost = static_cast<uint8_t>(1 + std::lround(251.0 * static_cast<double>(i) / (sw - 1)));
        canvas.rect(x + i, y, 1, sh, costColour(cost));
      }
    }
    else
    {
      canvas.rect(x, y, sw, sh, e.colour);
    }
    canvas.frame(x - 1, y - 1, sw + 2, sh + 2, 1, kRule);  // outside the swatch
    canvas.text(x + sw + 3 * s, y + s / 2, e.label, s, kInk);
  }
}

// ---- libpng: no C++ object with a destructor is created after setjmp. ----
struct PngSink
{
  std::string error;
};

void pngWriteError(png_structp png, png_const_charp message)
{
  auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
  if (sink->error.empty()) sink->error = message != nullptr ? message : "unknown libpng error";
  png_longjmp(png, 1);
}

void pngWriteWarning(png_structp, png_const_charp) {}

bool encodePng(FILE* fp, const Canvas& canvas, PngSink& sink)
{
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, pngWriteError, pngWriteWarning);
  if (png == nullptr)
  {
    sink.error = "cannot create libpng write struct";
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr)
  {
    png_destroy_write_struct(&png, nullptr);
    sink.error = "cannot create libpng info struct";
    return false;
  }
  if (setjmp(png_jmpbuf(png)))
  {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, fp);
  png_set_IHDR(png, info, canvas.width(), canvas.height(), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (unsigned y = 0; y < canvas.height(); ++y)
    png_write_row(png, canvas.row(y));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

void savePng(const std::string& path, const Canvas& canvas)
{
  FILE* fp = std::fopen(path.c_str(), "wb");
  if (fp == nullptr) throw std::runtime_error("cannot write PNG '" + path + "': " + std::strerror(errno));
  PngSink sink;
  const bool ok = encodePng(fp, canvas, sink);
  const bool closed = (std::fclose(fp) == 0);
  if (!ok || !closed)
  {
    std::remove(path.c_str());
    throw std::runtime_error("cannot write PNG '" + path + "': " + (ok ? std::string("error on close") : sink.error));
  }
}

std::string shown(const std::string& text)
{
  std::string out;
  for (char c : text.substr(0, kMaxPngLabelLength + 8))
    out += (c >= 0x20 && c < 0x7f) ? c : '?';
  return text.size() > kMaxPngLabelLength + 8 ? out + "..." : out;
}

/// Every option checked before anything is drawn or written; errors name the label and the value.
void checkOptions(const std::string& path, unsigned width, unsigned height, const PngOptions& o)
{
  const std::string where = "cannot write PNG '" + path + "': ";
  if (o.zoom < 1 || o.zoom > kMaxPngZoom)
    throw std::runtime_error(where + "zoom " + std::to_string(o.zoom) + " is outside 1.." + std::to_string(kMaxPngZoom));
  const double pixels = static_cast<double>(width) * o.zoom * static_cast<double>(height) * o.zoom;
  if (o.zoom > 1 && pixels > static_cast<double>(kMaxPngZoomedPixels))
    throw std::runtime_error(where + "a " + std::to_string(width) + "x" + std::to_string(height) + " grid at zoom " +
                             std::to_string(o.zoom) + " is more than " + std::to_string(kMaxPngZoomedPixels) +
                             " pixels: use a smaller zoom");
  if (o.labels.size() > kMaxPngLabels)
    throw std::runtime_error(where + std::to_string(o.labels.size()) + " labels, at most " +
                             std::to_string(kMaxPngLabels));
  for (size_t k = 0; k < o.labels.size(); ++k)
  {
    const PngLabel& l = o.labels[k];
    const std::string which = "label " + std::to_string(k + 1) + " \"" + shown(l.text) + "\": ";
    if (l.text.empty() || l.text.size() > kMaxPngLabelLength)
      throw std::runtime_error(where + which + "its text must have 1.." + std::to_string(kMaxPngLabelLength) +
                               " characters (it has " + std::to_string(l.text.size()) + ")");
    for (char c : l.text)
      if (!hasGlyph(c))
        throw std::runtime_error(where + which + "the character " +
                                 ((c >= 0x20 && c < 0x7f) ? "'" + std::string(1, c) + "'"
                                                          : "of code " + std::to_string(static_cast<unsigned char>(c))) +
                                 " has no glyph (letters, digits, space and - . : / ( ) , _ ?)");
    // NaN fails both comparisons, and so is refused with the points outside the grid.
    if (!(l.col >= 0.0 && l.col <= width) || !(l.row >= 0.0 && l.row <= height))
    {
      std::ostringstream msg;
      msg << where << which << "its place (" << l.col << ", " << l.row << ") [cells] is outside the " << width << "x"
          << height << " grid";
      throw std::runtime_error(msg.str());
    }
  }
}

/// A label's text on a tan box with a dark frame, so that it reads on every cost colour; centred on its
/// place, moved inside the grid's part of the picture when it would stick out.
void drawLabel(Canvas& canvas, const PngLabel& l, unsigned zoom, unsigned width, unsigned height)
{
  const int s = zoom >= 2 ? static_cast<int>((zoom + 2) / 2) : 1;  // 2x at zoom 2 and 3, 3x at 4 and 5, ...
  const long pad = 2 * s;
  const long text_w = static_cast<long>(l.text.size()) * kAdvance * s - s;
  const long box_w = text_w + 2 * pad + 2;
  const long box_h = kGlyphH * s + 2 * pad + 2;
  const long grid_w = static_cast<long>(width) * zoom;
  const long grid_h = static_cast<long>(height) * zoom;
  const long cx = std::lround(l.col * zoom);
  const long cy = std::lround((height - l.row) * zoom);  // row 0 is the bottom of the picture
  const long x = std::max(0L, std::min(cx - box_w / 2, grid_w - box_w));
  const long y = std::max(0L, std::min(cy - box_h / 2, grid_h - box_h));
  canvas.rect(x, y, box_w, box_h, kBand);
  canvas.frame(x, y, box_w, box_h, 1, kRule);
  canvas.text(x + 1 + pad, y + 1 + pad, l.text, s, kInk);
}

template <typename T, typename ColourFn>
void writeGridPng(const std::string& path, const T* cells, unsigned width, unsigned height, const PngOptions& options,
                  ColourFn colour, const std::vector<LegendEntry>& entries)
{
  if (cells == nullptr) throw std::runtime_error("cannot write PNG '" + path + "': no cell data (null pointer)");
  if (width == 0 || height == 0)
    throw std::runtime_error("cannot write PNG '" + path + "': empty grid (" + std::to_string(width) + "x" +
                             std::to_string(height) + ")");
  if (width > 1000000u || height > 1000000u)
    throw std::runtime_error("cannot write PNG '" + path + "': grid " + std::to_string(width) + "x" +
                             std::to_string(height) + " is too large");
  checkOptions(path, width, height, options);
  const unsigned z = options.zoom;
  const unsigned grid_w = width * z;
  const unsigned grid_h = height * z;
  LegendLayout layout;
  unsigned canvas_w = grid_w;
  unsigned canvas_h = grid_h;
  if (options.legend)
  {
    layout = layoutLegend(entries, grid_w);
    canvas_w = static_cast<unsigned>(layout.width);
    canvas_h = grid_h + static_cast<unsigned>(layout.height);
  }
  Canvas canvas(canvas_w, canvas_h, kBand);
  for (unsigned j = 0; j < height; ++j)
  {
    const T* row = cells + static_cast<size_t>(j) * width;
    const long y = static_cast<long>(height - 1 - j) * z;  // row 0 (lowest y) at the bottom
    for (unsigned i = 0; i < width; ++i)
    {
      if (z == 1)
        canvas.set(i, y, colour(row[i]));
      else
        canvas.rect(static_cast<long>(i) * z, y, z, z, colour(row[i]));
    }
  }
  for (const PngLabel& l : options.labels)
    drawLabel(canvas, l, z, width, height);
  if (options.legend) drawLegend(canvas, grid_h, entries, layout);
  savePng(path, canvas);
}
}  // namespace

Rgb costColour(uint8_t cost)
{
  switch (cost)
  {
    case 0:
      return kFree;
    case 253:
      return kInscribed;
    case 254:
      return kLethal;
    case 255:
      return kUnknown;
    default:
      break;
  }
  const double t = (cost - 1) / 251.0;  // 0 at cost 1, 1 at cost 252
  return t <= 0.5 ? mix(kRampLow, kRampMid, t * 2.0) : mix(kRampMid, kRampHigh, (t - 0.5) * 2.0);
}

Rgb occupancyColour(int8_t value)
{
  if (value == 0) return costColour(0);
  if (value >= 1 && value <= 98) return costColour(static_cast<uint8_t>(1 + std::lround((value - 1) * 251.0 / 97.0)));
  if (value == 99) return costColour(253);
  if (value == 100) return costColour(254);
  return costColour(255);
}

Rgb legendBackground()
{
  return kBand;
}

void writeCostmapPng(const std::string& path, const uint8_t* cells, unsigned width, unsigned height, bool legend)
{
  PngOptions o;
  o.legend = legend;
  writeCostmapPng(path, cells, width, height, o);
}

void writeCostmapPng(const std::string& path, const uint8_t* cells, unsigned width, unsigned height,
                     const PngOptions& options)
{
  const std::vector<LegendEntry> entries = {
      {LegendEntry::Kind::Solid, costColour(0), "free"},
      {LegendEntry::Kind::Ramp, Rgb{}, "cost 1-252"},
      {LegendEntry::Kind::Solid, costColour(253), "inscribed 253"},
      {LegendEntry::Kind::Solid, costColour(254), "lethal 254"},
      {LegendEntry::Kind::Solid, costColour(255), "unknown 255"},
  };
  writeGridPng(path, cells, width, height, options, costColour, entries);
}

void writeOccupancyPng(const std::string& path, const int8_t* values, unsigned width, unsigned height, bool legend)
{
  const std::vector<LegendEntry> entries = {
      {LegendEntry::Kind::Solid, occupancyColour(0), "free 0"},
      {LegendEntry::Kind::Ramp, Rgb{}, "occupancy 1-98"},
      {LegendEntry::Kind::Solid, occupancyColour(99), "inscribed 99"},
      {LegendEntry::Kind::Solid, occupancyColour(100), "lethal 100"},
      {LegendEntry::Kind::Solid, occupancyColour(-1), "unknown -1"},
  };
  PngOptions o;
  o.legend = legend;
  writeGridPng(path, values, width, height, o, occupancyColour, entries);
}

void writeRawBytes(const std::string& path, const uint8_t* cells, size_t n)
{
  if (cells == nullptr && n > 0) throw std::runtime_error("cannot write '" + path + "': no data (null pointer)");
  FILE* fp = std::fopen(path.c_str(), "wb");
  if (fp == nullptr) throw std::runtime_error("cannot write '" + path + "': " + std::strerror(errno));
  const size_t written = n > 0 ? std::fwrite(cells, 1, n, fp) : 0;
  const int saved_errno = errno;
  const bool closed = (std::fclose(fp) == 0);
  if (written != n || !closed)
  {
    std::remove(path.c_str());
    throw std::runtime_error("cannot write '" + path + "': " + std::strerror(written != n ? saved_errno : errno));
  }
}
}  // namespace io
}  // namespace costmap_layers
