// Reading map_server map files (a YAML description plus a PGM or PNG image) into OccupancyGridData,
// without ROS. Used by costmap_tool, the mask_server node and the tests.
//
// YAML keys (map_server format):
//   image            path of the image; relative paths are relative to the YAML file's folder
//   resolution       [m/pixel], in [limits::kMinResolution, limits::kMaxResolution] = [1e-4, 1e3]
//   origin           [x, y, yaw] of the lower-left pixel, 3 finite numbers, |x|, |y| <= 1e7 m
//                    (limits::kMaxCoordinate), |yaw| <= 1e3 rad (limits::kMaxYaw)
//   negate           0/1 or true/false
//   occupied_thresh  in [0, 1]
//   free_thresh      in [0, 1], must be < occupied_thresh
//   mode             optional: trinary (default) | scale | raw, and nav2_scale (an extension of
//                    this library: Nav2 calls its rule "scale" too)
//
// Images: binary and ASCII PGM (P5/P2) and PPM (P6/P3), any maxval 1..65535 (values are rescaled to
// 0..255 with rounding when maxval != 255); PNG through libpng (grey, grey+alpha, RGB, RGBA,
// palette, 1..16 bits; 16-bit samples are rescaled to 8 bits with rounding, no gamma correction).
// The format is detected from the file's first bytes, not from its name. Each side must be at
// most 100000 pixels, and width x height at most limits::kMaxGridCells (400 million, the limit the
// node applies to map messages).
//
// Files: the YAML and the image must be regular files of at most kMaxMapYamlBytes and kMaxImageBytes
// (file_limits.hpp); FIFOs, devices and directories are refused before anything is read, and the
// image's format and dimensions are checked from its first bytes before the rest is read.
//
// Orientation: image row 0 (the top of the picture) becomes the LAST row of `data`, so that data
// row 0 is the lowest y, as in nav_msgs/OccupancyGrid.
//
// ---- Pixel rule of ROS 1 map_server (modes Trinary, Scale, Raw; image_loader.cpp) ----
//   mean  = mean of the pixel's channels. The alpha channel is left out of the mean in Scale and
//           Raw mode but, as map_server does, averaged in with the colours in Trinary mode.
//   if negate: mean = 255 - mean
//   Raw:   value = (unsigned char)mean (truncated), stored as int8, so 0..127 stay as they are
//          and 128..255 wrap to -128..-1 (255 -> -1, 205 -> -51).
//   occ   = (255 - mean) / 255                          (double precision)
//   occ > occupied_thresh               -> 100          (strict comparisons)
//   occ < free_thresh                   -> 0
//   Trinary, or alpha == 0 (transparent) -> -1
//   otherwise (Scale)                   -> (unsigned char)(1 + 98 * (occ - free) / (occ_th - free)),
//                                          i.e. truncated, so values fall in 1..99.
//   With the default thresholds 0.65 / 0.196 an 8-bit grey pixel gives:
//     grey      0    127   128   205   254   255
//     trinary  100   -1    -1    -1     0     0
//     scale    100   67    66     1     0     0
//     raw       0   127  -128   -51    -2    -1
//   With thresholds 1.0 / 0.0 (the Nav2 speed masks) Scale mode maps white to 1 and black to 99:
//   nothing is ever strictly above 1.0 or strictly below 0.0.
//   Differences to map_server kept on purpose: map_server (through SDL) uses the palette INDEX of a
//   palette image and reads the blue byte of an RGB pixel as its "alpha"; here palette images are
//   expanded to their colours and RGB images without alpha are opaque. Only a fully transparent
//   pixel (alpha 0) is unknown in Scale mode, as in map_server (it tests alpha < 1).
//
// ---- Pixel rule of Nav2 map_io.cpp in scale mode (mode Nav2Scale, YAML "nav2_scale") ----
//   (the current, Eigen-based map_io: single-precision floats, inclusive thresholds)
//   grey  = mean of the colour channels (alpha excluded). Nav2 converts to grey with
//           GraphicsMagick's luminance weights; for grey images, which all masks are, it is the same.
//   p     = grey / 255.0f; occ = negate ? p : 1.0f - p
//   occ >= occupied_thresh -> 100
//   occ <= free_thresh     -> 0
//   otherwise              -> round(100 * (occ - free) / (occ_th - free))   (round half away from 0)
//   if the image has an alpha channel and alpha < 255 -> -1 (overrides the above)
//   With the default thresholds 0.65 / 0.196: grey 0 -> 100, 127 -> 67, 128 -> 67, 205 -> 0,
//   254 -> 0, 255 -> 0. With thresholds 1.0 / 0.0: white -> 0, black -> 100, grey g -> the
//   rounded percentage 100 * (255 - g) / 255. (Older Nav2 releases, e.g. Humble, compared with
//   strict < / > and rounded with rint; results differ only exactly at the thresholds or at ties.)
//
// Errors: every function throws std::runtime_error with a one-line message that names the file and
// the problem (missing file, bad YAML, missing or invalid key, bad image header, truncated pixel
// data, unknown mode, absurd size, ...).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "costmap_layers/core/data/grid_data.hpp"

namespace costmap_layers
{
namespace io
{
enum class MapMode
{
  Trinary,   ///< ROS 1 map_server "trinary": 0 / 100 / -1
  Scale,     ///< ROS 1 map_server "scale": 0, 1..99 (truncated), 100, -1 for transparent
  Raw,       ///< ROS 1 map_server "raw": the grey value itself, wrapped into int8
  Nav2Scale  ///< Nav2 map_io "scale": 0..100 with round(), inclusive thresholds
};

/// "trinary", "scale", "raw", "nav2_scale".
const char* mapModeName(MapMode mode);
/// Inverse of mapModeName (exact, lower case); throws std::runtime_error naming the allowed values.
MapMode parseMapMode(const std::string& name);

struct MapFileInfo
{
  std::string image_path;              ///< resolved (relative to the YAML's folder) by loadMapFileInfo
  double resolution = 0.0;             ///< [m/pixel]
  double origin[3] = {0.0, 0.0, 0.0};  ///< x [m], y [m], yaw [rad] of the lower-left pixel
  bool negate = false;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  MapMode mode = MapMode::Trinary;
};

/// Reads and validates the YAML only (the image is not opened).
MapFileInfo loadMapFileInfo(const std::string& yaml_path);

/// loadMapFileInfo() on YAML text already in memory; `yaml_path` names it in errors and is the base of
/// a relative image path.
MapFileInfo parseMapFileInfo(const std::string& yaml_text, const std::string& yaml_path);

/// Reads the YAML and its image. `mode_override` replaces the YAML's mode when given.
/// The result has frame_id "map" and stamp_ns 0.
OccupancyGridData loadMapFile(const std::string& yaml_path, std::optional<MapMode> mode_override = {});

/// Reads `image_path` (info.image_path is ignored) and converts it with the thresholds, negate flag,
/// mode, resolution and origin of `info` (validated first).
OccupancyGridData loadMapImage(const std::string& image_path, const MapFileInfo& info);
/// loadMapImage() on the image file's bytes already in memory; `what` names them in errors.
OccupancyGridData decodeMapImage(const std::vector<uint8_t>& bytes, const MapFileInfo& info, const std::string& what);
}  // namespace io
}  // namespace costmap_layers
