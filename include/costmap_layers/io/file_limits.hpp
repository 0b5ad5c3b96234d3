// What every file loader of this library accepts before it reads or allocates anything: a regular
// file (checked with stat and again on the opened descriptor; FIFOs, devices, sockets and
// directories are refused with an error naming the path and what it is) no larger than a cap for
// its kind. A FIFO is opened non-blocking, so refusing it never waits for a writer.
//
// Caps per kind (the largest real files of each kind are far smaller):
//   map YAML (map_server format)      kMaxMapYamlBytes      256 KiB (real ones: ~200 bytes)
//   params YAML (rosparam format)     kMaxParamsYamlBytes   256 KiB (large real ones: ~20 KB)
//   features YAML (speed limits)      kMaxFeaturesYamlBytes 256 KiB (100 area ids fit in 4 KB)
//   map / mask image (PGM, PPM, PNG)  kMaxImageBytes        1 GiB: a binary 16-bit grey PGM of
//                                     limits::kMaxGridCells pixels (800 MB) fits. Image dimensions
//                                     are checked against limits::kMaxGridCells from the header,
//                                     before the pixel data is read.
// YAML parsed into a parameter tree also has a node budget (param_yaml.hpp): alias expansion cannot
// make a small file into a huge tree.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace costmap_layers
{
namespace io
{
constexpr uint64_t kMaxMapYamlBytes = uint64_t{256} << 10;
constexpr uint64_t kMaxParamsYamlBytes = uint64_t{256} << 10;
constexpr uint64_t kMaxFeaturesYamlBytes = uint64_t{256} << 10;
constexpr uint64_t kMaxImageBytes = uint64_t{1} << 30;

/// Called with the file's first bytes (up to kFileHeadBytes, fewer when the file is shorter) and the
/// file's size, before the rest is read; throws to refuse the file.
using FileHeadCheck = std::function<void(const std::vector<uint8_t>& head, uint64_t file_size)>;
constexpr std::size_t kFileHeadBytes = 4096;

/// Reads a whole regular file of at most max_bytes. `what` says what the file is ("params file",
/// "image file", ...) in errors. Throws std::runtime_error "'path': <problem>" when the path does
/// not exist, is not a regular file (naming what it is: directory, FIFO, character device, ...), is
/// larger than max_bytes, grows beyond it while read, or cannot be read. `head_check`, when given,
/// sees the first bytes before the rest is read.
std::vector<uint8_t> readRegularFile(const std::string& path, const std::string& what, uint64_t max_bytes,
                                     const FileHeadCheck& head_check = {});
}  // namespace io
}  // namespace costmap_layers
