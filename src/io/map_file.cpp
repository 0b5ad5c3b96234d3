#include "costmap_layers/io/map_file.hpp"

#include <png.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/io/file_limits.hpp"

namespace costmap_layers
{
namespace io
{
namespace
{
constexpr uint32_t kMaxSide = 100000;

/// A decoded image: 8 bits per sample, 1 (grey), 3 (RGB) or 4 (RGBA) channels, top row first.
struct Image
{
  uint32_t width = 0;
  uint32_t height = 0;
  int channels = 1;
  std::vector<uint8_t> pixels;
};

[[noreturn]] void fail(const std::string& path, const std::string& problem)
{
  throw std::runtime_error("'" + path + "': " + problem);
}

/// Empty when the size is acceptable, else the problem: zero, more than kMaxSide per side, or more
/// cells than limits::kMaxGridCells (the limit the node applies to a map message).
std::string sizeProblem(uint64_t width, uint64_t height)
{
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width == 0 || height == 0) return "image has zero size (" + size + ")";
  if (width > kMaxSide || height > kMaxSide)
    return "image size " + size + " is absurdly large (more than " + std::to_string(kMaxSide) + " pixels per side)";
  if (width * height > limits::kMaxGridCells)
    return "image size " + size + " is absurdly large (" + std::to_string(width * height) + " cells, more than " +
           std::to_string(limits::kMaxGridCells) + ")";
  return "";
}

void checkSize(const std::string& path, uint64_t width, uint64_t height)
{
  const std::string problem = sizeProblem(width, height);
  if (!problem.empty()) fail(path, problem);
}

// ---------------------------------------------------------------------------------------------
// PNM (P2/P3 ASCII, P5/P6 binary)

class PnmReader
{
public:
  PnmReader(const std::string& path, const std::vector<uint8_t>& bytes) : path_(path), b_(bytes) {}

  /// Checks the header in the first bytes of a file of file_size bytes (the bytes given to the
  /// constructor) before the rest is read: the dimensions, and for binary data that the file is long
  /// enough for them. Silent when the header does not end within those bytes (read() checks it then).
  void checkHead(uint64_t file_size)
  {
    const char kind = static_cast<char>(b_[1]);
    const bool supported = kind == '2' || kind == '3' || kind == '5' || kind == '6';
    if (supported && !headerComplete()) return;
    const Header h = header();  // throws for an unsupported type at once
    if (h.ascii) return;
    const uint64_t count = h.width * h.height * static_cast<uint64_t>(h.channels);
    const uint64_t need = count * (h.maxval > 255 ? 2 : 1);
    if (file_size < pos_ + 1 || file_size - pos_ - 1 < need)
      fail(path_, "truncated pixel data: the file has " + std::to_string(file_size) + " bytes, the header promises " +
                      std::to_string(need) + " bytes of pixels");
  }

  Image read()
  {
    const Header h = header();
    const bool ascii = h.ascii;
    const int channels = h.channels;
    const uint64_t width = h.width, height = h.height, maxval = h.maxval;

    Image img;
    img.width = static_cast<uint32_t>(width);
    img.height = static_cast<uint32_t>(height);
    img.channels = channels;
    const uint64_t count = width * height * static_cast<uint64_t>(channels);
    // Every sample takes at least one byte of the file: a header promising more samples than the file
    // holds is refused before the pixels are allocated (a 30-byte file must not allocate 30 GB).
    const uint64_t min_bytes = ascii ? count : count * (maxval > 255 ? 2 : 1);
    if (pos_ > b_.size() || b_.size() - pos_ < min_bytes)
      fail(path_, "truncated pixel data: " + std::to_string(b_.size() - std::min(pos_, b_.size())) + " bytes left, " +
                      std::to_string(count) + " samples expected");
    img.pixels.resize(count);

    if (ascii)
    {
      for (uint64_t k = 0; k < count; ++k)
      {
        skipSpaceAndComments();
        if (pos_ >= b_.size())
          fail(path_,
               "truncated pixel data: " + std::to_string(k) + " of " + std::to_string(count) + " samples present");
        const uint64_t v = number("sample");
        if (v > maxval) fail(path_, "sample " + std::to_string(v) + " exceeds maxval " + std::to_string(maxval));
        img.pixels[k] = scale(v, maxval);
      }
      return img;
    }

    // Binary: exactly one whitespace character separates maxval from the data.
    if (pos_ >= b_.size() || !std::isspace(b_[pos_])) fail(path_, "bad PNM header: no whitespace after maxval");
    ++pos_;
    const uint64_t bytes_per_sample = maxval > 255 ? 2 : 1;
    const uint64_t available = b_.size() - pos_;
    if (available < count * bytes_per_sample)
      fail(path_, "truncated pixel data: " + std::to_string(available) + " bytes, expected " +
                      std::to_string(count * bytes_per_sample));
    for (uint64_t k = 0; k < count; ++k)
    {
      uint64_t v = b_[pos_ + k * bytes_per_sample];
      if (bytes_per_sample == 2) v = (v << 8) | b_[pos_ + k * 2 + 1];
      if (v > maxval) fail(path_, "sample " + std::to_string(v) + " exceeds maxval " + std::to_string(maxval));
      img.pixels[k] = scale(v, maxval);
    }
    return img;
  }

private:
  struct Header
  {
    bool ascii = false;
    int channels = 1;
    uint64_t width = 0, height = 0, maxval = 0;
  };

  /// Parses the magic number, width, height and maxval, and checks them.
  Header header()
  {
    if (b_.size() < 2 || b_[0] != 'P') fail(path_, "bad PNM header: missing magic number");
    const char kind = static_cast<char>(b_[1]);
    if (kind != '2' && kind != '3' && kind != '5' && kind != '6')
      fail(path_,
           std::string("bad PNM header: unsupported type P") + kind + " (expected P2, P5 grey or P3, P6 colour)");
    pos_ = 2;
    Header h;
    h.ascii = (kind == '2' || kind == '3');
    h.channels = (kind == '2' || kind == '5') ? 1 : 3;
    h.width = headerNumber("width");
    h.height = headerNumber("height");
    h.maxval = headerNumber("maxval");
    if (h.maxval == 0 || h.maxval > 65535)
      fail(path_, "bad PNM header: maxval " + std::to_string(h.maxval) + " is not in 1..65535");
    checkSize(path_, h.width, h.height);
    return h;
  }

  /// True when the bytes hold the whole header: three numbers after the magic, each followed by
  /// something that is not a digit.
  bool headerComplete()
  {
    pos_ = 2;
    for (int k = 0; k < 3; ++k)
    {
      skipSpaceAndComments();
      if (pos_ >= b_.size() || !std::isdigit(b_[pos_])) return pos_ < b_.size();  // malformed: header() says so
      while (pos_ < b_.size() && std::isdigit(b_[pos_]))
        ++pos_;
      if (pos_ >= b_.size()) return false;
    }
    return true;
  }

  static uint8_t scale(uint64_t v, uint64_t maxval)
  {
    if (maxval == 255) return static_cast<uint8_t>(v);
    return static_cast<uint8_t>((v * 255 + maxval / 2) / maxval);
  }

  void skipSpaceAndComments()
  {
    while (pos_ < b_.size())
    {
      if (b_[pos_] == '#')
      {
        while (pos_ < b_.size() && b_[pos_] != '\n' && b_[pos_] != '\r')
          ++pos_;
      }
      else if (std::isspace(b_[pos_]))
      {
        ++pos_;
      }
      else
      {
        break;
      }
    }
  }

  uint64_t number(const char* what)
  {
    if (pos_ >= b_.size() || !std::isdigit(b_[pos_]))
      fail(path_, std::string("bad PNM data: expected a number for ") + what);
    uint64_t v = 0;
    while (pos_ < b_.size() && std::isdigit(b_[pos_]))
    {
      v = v * 10 + static_cast<uint64_t>(b_[pos_] - '0');
      if (v > 0xFFFFFFFFull) fail(path_, std::string("bad PNM data: ") + what + " is too large");
      ++pos_;
    }
    return v;
  }

  uint64_t headerNumber(const char* what)
  {
    skipSpaceAndComments();
    if (pos_ >= b_.size()) fail(path_, std::string("bad PNM header: missing ") + what);
    if (!std::isdigit(b_[pos_])) fail(path_, std::string("bad PNM header: invalid ") + what);
    return number(what);
  }

  const std::string& path_;
  const std::vector<uint8_t>& b_;
  size_t pos_ = 0;
};

// ---------------------------------------------------------------------------------------------
// PNG through libpng. libpng reports errors by longjmp, so the decoding function creates no C++
// object with a destructor after setjmp; everything it fills lives in the caller's frame.

struct PngSource
{
  const std::vector<uint8_t>* bytes = nullptr;
  size_t pos = 0;
  std::string error;
};

void pngRead(png_structp png, png_bytep out, png_size_t length)
{
  auto* src = static_cast<PngSource*>(png_get_io_ptr(png));
  if (src->bytes->size() - src->pos < length) png_error(png, "truncated data: the file ends early");
  std::memcpy(out, src->bytes->data() + src->pos, length);
  src->pos += length;
}

void pngError(png_structp png, png_const_charp message)
{
  auto* src = static_cast<PngSource*>(png_get_error_ptr(png));
  if (src->error.empty()) src->error = message != nullptr ? message : "unknown libpng error";
  png_longjmp(png, 1);
}

void pngWarning(png_structp, png_const_charp) {}

/// Returns false with src.error set on failure.
bool decodePngInto(PngSource& src, Image& img, std::vector<png_bytep>& rows)
{
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &src, pngError, pngWarning);
  if (png == nullptr)
  {
    src.error = "cannot create libpng read struct";
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr)
  {
    png_destroy_read_struct(&png, nullptr, nullptr);
    src.error = "cannot create libpng info struct";
    return false;
  }
  if (setjmp(png_jmpbuf(png)))
  {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_set_read_fn(png, &src, pngRead);
  png_read_info(png, info);

  const png_uint_32 width = png_get_image_width(png, info);
  const png_uint_32 height = png_get_image_height(png, info);
  src.error = sizeProblem(width, height);
  if (!src.error.empty())
  {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }

  // The pixel data is deflate-compressed, which expands at most 1032-fold: a header promising far more
  // pixel bytes than the rest of the file can hold is refused before the pixels are allocated (half the
  // unfiltered size is a safe lower bound of the inflated size, interlaced or not).
  const uint64_t inflated_at_least = static_cast<uint64_t>(png_get_rowbytes(png, info)) * height / 2;
  if (inflated_at_least > static_cast<uint64_t>(src.bytes->size() - src.pos) * 1032)
  {
    src.error = "truncated data: " + std::to_string(width) + "x" + std::to_string(height) +
                " pixels cannot fit in the file's " + std::to_string(src.bytes->size()) + " bytes";
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }

  const int color_type = png_get_color_type(png, info);
  const int bit_depth = png_get_bit_depth(png, info);
  if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (color_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  if (bit_depth == 16) png_set_scale_16(png);
  // Grey+alpha becomes RGBA, as SDL_image (used by map_server) does it.
  if ((color_type & PNG_COLOR_MASK_COLOR) == 0 &&
      ((color_type & PNG_COLOR_MASK_ALPHA) != 0 || png_get_valid(png, info, PNG_INFO_tRNS)))
    png_set_gray_to_rgb(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);

  const int channels = png_get_channels(png, info);
  const size_t rowbytes = png_get_rowbytes(png, info);
  if ((channels != 1 && channels != 3 && channels != 4) || png_get_bit_depth(png, info) != 8 ||
      rowbytes != static_cast<size_t>(width) * static_cast<size_t>(channels))
  {
    src.error = "unsupported PNG layout after conversion";
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  img.width = width;
  img.height = height;
  img.channels = channels;
  img.pixels.resize(rowbytes * height);
  rows.resize(height);
  for (png_uint_32 y = 0; y < height; ++y)
    rows[y] = img.pixels.data() + rowbytes * y;
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

Image decodePng(const std::string& path, const std::vector<uint8_t>& bytes)
{
  PngSource src;
  src.bytes = &bytes;
  Image img;
  std::vector<png_bytep> rows;
  if (!decodePngInto(src, img, rows))
  {
    const std::string& e = src.error;
    if (e.find("truncated") != std::string::npos || e.find("absurdly") != std::string::npos ||
        e.find("zero size") != std::string::npos)
      fail(path, e);
    fail(path, "bad PNG: " + e);
  }
  return img;
}

const uint8_t kPngMagic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};

/// The check of an image file's first bytes before the rest is read (see readRegularFile): a known
/// format, and dimensions within the limits. PNG: the IHDR chunk, which must come first, holds the
/// width and height at bytes 16..23. PNM: the text header; binary data must fit in the file.
void checkImageHead(const std::string& path, const std::vector<uint8_t>& head, uint64_t file_size)
{
  if (head.empty()) fail(path, "image file is empty");
  if (head.size() >= 8 && std::memcmp(head.data(), kPngMagic, 8) == 0)
  {
    if (head.size() < 24 || std::memcmp(head.data() + 12, "IHDR", 4) != 0) return;  // libpng reports it
    const auto be32 = [&head](std::size_t at)
    { return uint64_t{head[at]} << 24 | uint64_t{head[at + 1]} << 16 | uint64_t{head[at + 2]} << 8 | head[at + 3]; };
    checkSize(path, be32(16), be32(20));
    return;
  }
  if (head.size() >= 2 && head[0] == 'P' && head[1] >= '1' && head[1] <= '7')
  {
    PnmReader(path, head).checkHead(file_size);
    return;
  }
  fail(path, "bad image header: not a PGM/PPM (P2, P3, P5, P6) or PNG file");
}

Image decodeImage(const std::string& path, const std::vector<uint8_t>& bytes)
{
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), kPngMagic, 8) == 0) return decodePng(path, bytes);
  if (bytes.size() >= 2 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '7') return PnmReader(path, bytes).read();
  if (bytes.empty()) fail(path, "image file is empty");
  fail(path, "bad image header: not a PGM/PPM (P2, P3, P5, P6) or PNG file");
}

// ---------------------------------------------------------------------------------------------
// Pixel rules (see the header for the documentation).

int8_t ros1Value(const uint8_t* p, int channels, const MapFileInfo& info)
{
  const bool has_alpha = (channels == 4);
  const int avg_channels = (info.mode == MapMode::Trinary || !has_alpha) ? channels : channels - 1;
  int sum = 0;
  for (int k = 0; k < avg_channels; ++k)
    sum += p[k];
  double mean = sum / static_cast<double>(avg_channels);
  const int alpha = has_alpha ? p[3] : 255;
  if (info.negate) mean = 255.0 - mean;

  unsigned char value = 0;
  if (info.mode == MapMode::Raw)
  {
    value = static_cast<unsigned char>(mean);
    return static_cast<int8_t>(value);
  }
  const double occ = (255.0 - mean) / 255.0;
  if (occ > info.occupied_thresh)
  {
    value = 100;
  }
  else if (occ < info.free_thresh)
  {
    value = 0;
  }
  else if (info.mode == MapMode::Trinary || alpha < 1)
  {
    return -1;
  }
  else
  {
    const double ratio = (occ - info.free_thresh) / (info.occupied_thresh - info.free_thresh);
    value = static_cast<unsigned char>(1.0 + 98.0 * ratio);
  }
  return static_cast<int8_t>(value);
}

int8_t nav2ScaleValue(const uint8_t* p, int channels, const MapFileInfo& info)
{
  const bool has_alpha = (channels == 4);
  if (has_alpha && p[3] < 255) return -1;
  const int colour_channels = has_alpha ? 3 : channels;
  int sum = 0;
  for (int k = 0; k < colour_channels; ++k)
    sum += p[k];
  const float grey = static_cast<float>(sum) / static_cast<float>(colour_channels);
  const float shade = grey / 255.0f;
  const float occ = info.negate ? shade : 1.0f - shade;
  const float occ_th = static_cast<float>(info.occupied_thresh);
  const float free_th = static_cast<float>(info.free_thresh);
  if (occ >= occ_th) return 100;
  if (occ <= free_th) return 0;
  const float scaled = (occ - free_th) / (occ_th - free_th) * 100.0f;
  return static_cast<int8_t>(std::round(scaled));
}

void validateInfo(const std::string& path, const MapFileInfo& info)
{
  if (!(info.resolution >= limits::kMinResolution && info.resolution <= limits::kMaxResolution))
  {
    std::ostringstream s;
    s << "resolution must be in [" << limits::kMinResolution << ", " << limits::kMaxResolution << "] m/pixel, got "
      << info.resolution;
    fail(path, s.str());
  }
  for (int k = 0; k < 3; ++k)
  {
    if (!std::isfinite(info.origin[k])) fail(path, "origin must contain finite numbers");
  }
  static const char* const kOriginNames[3] = {"x", "y", "yaw"};
  for (int k = 0; k < 3; ++k)
  {
    const double bound = k < 2 ? limits::kMaxCoordinate : limits::kMaxYaw;
    if (std::fabs(info.origin[k]) > bound)
    {
      std::ostringstream s;
      s << "origin " << kOriginNames[k] << " must be within +-" << bound << (k < 2 ? " m" : " rad") << ", got "
        << info.origin[k];
      fail(path, s.str());
    }
  }
  const auto in01 = [](double v) { return std::isfinite(v) && v >= 0.0 && v <= 1.0; };
  if (!in01(info.occupied_thresh) || !in01(info.free_thresh))
  {
    std::ostringstream s;
    s << "thresholds must be in [0, 1], got occupied_thresh " << info.occupied_thresh << ", free_thresh "
      << info.free_thresh;
    fail(path, s.str());
  }
  if (info.free_thresh >= info.occupied_thresh)
  {
    std::ostringstream s;
    s << "free_thresh (" << info.free_thresh << ") must be smaller than occupied_thresh (" << info.occupied_thresh
      << ")";
    fail(path, s.str());
  }
}

// ---------------------------------------------------------------------------------------------
// YAML

std::string folderOf(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return "";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

YAML::Node requireKey(const std::string& path, const YAML::Node& doc, const char* key)
{
  const YAML::Node node = doc[key];
  if (!node || node.IsNull()) fail(path, std::string("missing key '") + key + "'");
  return node;
}

double requireDouble(const std::string& path, const YAML::Node& doc, const char* key)
{
  const YAML::Node node = requireKey(path, doc, key);
  double v = 0.0;
  if (!node.IsScalar() || !YAML::convert<double>::decode(node, v))
    fail(path, std::string("key '") + key + "' must be a number");
  return v;
}
}  // namespace

const char* mapModeName(MapMode mode)
{
  switch (mode)
  {
    case MapMode::Trinary:
      return "trinary";
    case MapMode::Scale:
      return "scale";
    case MapMode::Raw:
      return "raw";
    case MapMode::Nav2Scale:
      return "nav2_scale";
  }
  return "?";
}

MapMode parseMapMode(const std::string& name)
{
  for (MapMode m : {MapMode::Trinary, MapMode::Scale, MapMode::Raw, MapMode::Nav2Scale})
  {
    if (name == mapModeName(m)) return m;
  }
  throw std::runtime_error("unknown map mode '" + name + "' (expected trinary, scale, raw or nav2_scale)");
}

MapFileInfo loadMapFileInfo(const std::string& yaml_path)
{
  const std::vector<uint8_t> bytes = readRegularFile(yaml_path, "map YAML file", kMaxMapYamlBytes);
  return parseMapFileInfo(std::string(bytes.begin(), bytes.end()), yaml_path);
}

MapFileInfo parseMapFileInfo(const std::string& yaml_text, const std::string& yaml_path)
{
  YAML::Node doc;
  try
  {
    doc = YAML::Load(yaml_text);
  }
  catch (const YAML::Exception& e)
  {
    fail(yaml_path, "bad YAML at line " + std::to_string(e.mark.line + 1) + ", column " +
                        std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
  if (!doc.IsMap()) fail(yaml_path, "bad YAML: expected a map of keys (image, resolution, origin, ...)");

  MapFileInfo info;
  try
  {
    const YAML::Node image = requireKey(yaml_path, doc, "image");
    if (!image.IsScalar() || image.Scalar().empty()) fail(yaml_path, "key 'image' must be a file name");
    info.image_path = image.Scalar();
    if (info.image_path[0] != '/')
    {
      const std::string folder = folderOf(yaml_path);
      if (!folder.empty()) info.image_path = (folder == "/" ? folder : folder + "/") + info.image_path;
    }

    info.resolution = requireDouble(yaml_path, doc, "resolution");

    const YAML::Node origin = requireKey(yaml_path, doc, "origin");
    if (!origin.IsSequence() || origin.size() != 3)
      fail(yaml_path, "key 'origin' must be a list of 3 numbers [x, y, yaw]");
    for (std::size_t k = 0; k < 3; ++k)
    {
      if (!origin[k].IsScalar() || !YAML::convert<double>::decode(origin[k], info.origin[k]))
        fail(yaml_path, "key 'origin' must be a list of 3 numbers [x, y, yaw]");
    }

    const YAML::Node negate = requireKey(yaml_path, doc, "negate");
    long long negate_int = 0;
    bool negate_bool = false;
    if (negate.IsScalar() && YAML::convert<long long>::decode(negate, negate_int))
      info.negate = (negate_int != 0);
    else if (negate.IsScalar() && YAML::convert<bool>::decode(negate, negate_bool))
      info.negate = negate_bool;
    else
      fail(yaml_path, "key 'negate' must be 0, 1, true or false");

    info.occupied_thresh = requireDouble(yaml_path, doc, "occupied_thresh");
    info.free_thresh = requireDouble(yaml_path, doc, "free_thresh");

    const YAML::Node mode = doc["mode"];
    if (mode && !mode.IsNull())
    {
      if (!mode.IsScalar()) fail(yaml_path, "key 'mode' must be trinary, scale, raw or nav2_scale");
      try
      {
        info.mode = parseMapMode(mode.Scalar());
      }
      catch (const std::runtime_error& e)
      {
        fail(yaml_path, e.what());
      }
    }
  }
  catch (const YAML::Exception& e)
  {
    fail(yaml_path, "bad YAML: " + e.msg);
  }
  validateInfo(yaml_path, info);
  return info;
}

OccupancyGridData loadMapImage(const std::string& image_path, const MapFileInfo& info)
{
  validateInfo(image_path, info);
  const auto head_check = [&image_path](const std::vector<uint8_t>& head, uint64_t size)
  { checkImageHead(image_path, head, size); };
  return decodeMapImage(readRegularFile(image_path, "image file", kMaxImageBytes, head_check), info, image_path);
}

OccupancyGridData decodeMapImage(const std::vector<uint8_t>& bytes, const MapFileInfo& info, const std::string& what)
{
  validateInfo(what, info);
  const Image img = decodeImage(what, bytes);

  OccupancyGridData grid;
  grid.frame_id = "map";
  grid.width = img.width;
  grid.height = img.height;
  grid.resolution = info.resolution;
  grid.origin_x = info.origin[0];
  grid.origin_y = info.origin[1];
  grid.origin_yaw = info.origin[2];
  grid.data.resize(static_cast<size_t>(img.width) * img.height);

  const size_t stride = static_cast<size_t>(img.width) * static_cast<size_t>(img.channels);
  for (uint32_t j = 0; j < img.height; ++j)
  {
    const uint8_t* row = img.pixels.data() + stride * j;
    int8_t* out = grid.data.data() + static_cast<size_t>(img.width) * (img.height - 1 - j);
    for (uint32_t i = 0; i < img.width; ++i)
    {
      const uint8_t* p = row + static_cast<size_t>(i) * static_cast<size_t>(img.channels);
      out[i] =
          info.mode == MapMode::Nav2Scale ? nav2ScaleValue(p, img.channels, info) : ros1Value(p, img.channels, info);
    }
  }
  return grid;
}

OccupancyGridData loadMapFile(const std::string& yaml_path, std::optional<MapMode> mode_override)
{
  MapFileInfo info = loadMapFileInfo(yaml_path);
  if (mode_override) info.mode = *mode_override;
  return loadMapImage(info.image_path, info);
}
}  // namespace io
}  // namespace costmap_layers
