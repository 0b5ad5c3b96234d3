// What every file loader does with a file that is not what it should be: a FIFO, a device, a
// directory, a file far too large (sparse, so the test costs no disk), images whose headers promise
// more cells than the node accepts in a message, a YAML alias bomb, and numbers at the edge of their
// ranges in a map YAML. Each must be refused before the loader reads or allocates much, with an error
// naming the path and the problem. The limits are written here as numbers, independently of the
// library's constants: 256 KiB for map YAML, params and features files, 1 GiB for images, 400 million
// cells, resolution in [1e-4, 1e3] m/pixel, |origin x/y| <= 1e7 m, |yaw| <= 1e3 rad.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "costmap_layers/io/features_file.hpp"
#include "costmap_layers/io/map_file.hpp"
#include "costmap_layers/io/param_yaml.hpp"
#include "png_bytes.hpp"
#include "temp_dir_test.hpp"

using costmap_layers::io::decodeMapImage;
using costmap_layers::io::loadFeaturesFile;
using costmap_layers::io::loadMapFile;
using costmap_layers::io::loadMapFileInfo;
using costmap_layers::io::loadMapImage;
using costmap_layers::io::loadParamsYamlFile;
using costmap_layers::io::MapFileInfo;
using costmap_layers::io::parseMapFileInfo;
using costmap_layers::io::parseParamsYaml;

namespace
{
constexpr uint64_t kYamlCap = uint64_t{256} << 10;  // map YAML, params, features: 256 KiB
constexpr uint64_t kImageCap = uint64_t{1} << 30;   // images: 1 GiB

/// The message of the exception fn throws, or "" when it throws none. Any exception counts (an
/// out-of-memory one included), so that a regression fails the expectation instead of aborting.
std::string errorOf(const std::function<void()>& fn)
{
  try
  {
    fn();
  }
  catch (const std::exception& e)
  {
    return std::string("[") + (dynamic_cast<const std::runtime_error*>(&e) ? "runtime_error" : "other") + "] " +
           e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& needle)
{
  return text.find(needle) != std::string::npos;
}

void writeBytes(const std::string& path, const std::string& bytes)
{
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

/// A sparse file: `head` followed by zeros up to `size` bytes (no disk blocks for the zeros).
void writeSparse(const std::string& path, const std::string& head, uint64_t size)
{
  writeBytes(path, head);
  ASSERT_EQ(::truncate(path.c_str(), static_cast<off_t>(size)), 0) << path;
}

const char* kMapYamlKeys =
    "resolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\n"
    "free_thresh: 0.196\n";

class FileEdges : public TempDirTest
{
protected:
  /// A map YAML naming `image`.
  std::string mapYaml(const std::string& name, const std::string& image)
  {
    writeBytes(tmp(name), "image: " + image + "\n" + kMapYamlKeys);
    return tmp(name);
  }
};

/// Runs load(path) on a FIFO without ever blocking the test, whatever the loader does: a helper
/// thread opens the FIFO for writing (which waits for a reader) and closes it at once. A loader that
/// opens the FIFO meets that writer and reads an empty stream; a loader that refuses it never opens
/// it, and the test then opens it itself (non-blocking) so that the helper can finish.
std::string loadFifo(const std::string& path, const std::function<void(const std::string&)>& load)
{
  if (::mkfifo(path.c_str(), 0600) != 0) return "mkfifo failed";
  std::thread writer(
      [&path]
      {
        const int fd = ::open(path.c_str(), O_WRONLY);
        if (fd >= 0) ::close(fd);
      });
  const std::string error = errorOf([&] { load(path); });
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK);
  writer.join();
  if (fd >= 0) ::close(fd);
  return error;
}

// ---------------------------------------------------------------------------------------------
// Not a regular file

TEST_F(FileEdges, FifoIsRefusedByEveryLoaderWithoutWaiting)
{
  const std::vector<std::pair<std::string, std::function<void(const std::string&)>>> loaders = {
      {"map yaml", [](const std::string& p) { loadMapFileInfo(p); }},
      {"params", [](const std::string& p) { loadParamsYamlFile(p); }},
      {"features", [](const std::string& p) { loadFeaturesFile(p); }},
      {"image",
       [](const std::string& p) {
         loadMapImage(p, MapFileInfo{"", 0.05});
       }},
  };
  int k = 0;
  for (const auto& [name, load] : loaders)
  {
    const std::string path = tmp("fifo" + std::to_string(k++));
    const std::string e = loadFifo(path, load);
    EXPECT_TRUE(contains(e, "[runtime_error]")) << name << ": " << e;
    EXPECT_TRUE(contains(e, path)) << name << ": " << e;
    EXPECT_TRUE(contains(e, "FIFO")) << name << ": " << e;
  }
  // Through the map YAML too: its image is the FIFO.
  const std::string fifo = tmp("image_fifo");
  const std::string yaml = mapYaml("fifo_image.yaml", fifo);
  const std::string e = loadFifo(fifo, [&yaml](const std::string&) { loadMapFile(yaml); });
  EXPECT_TRUE(contains(e, fifo) && contains(e, "FIFO")) << e;
}

TEST_F(FileEdges, DevZeroAsImageIsRefusedBeforeReading)
{
  // map_server would read it until memory runs out.
  const std::string yaml = mapYaml("zero.yaml", "/dev/zero");
  const std::string e = errorOf([&] { loadMapFile(yaml); });
  EXPECT_TRUE(contains(e, "[runtime_error]")) << e;
  EXPECT_TRUE(contains(e, "/dev/zero")) << e;
  EXPECT_TRUE(contains(e, "character device")) << e;
  for (const auto& load : std::vector<std::function<void()>>{[] { loadParamsYamlFile("/dev/zero"); },
                                                             [] { loadFeaturesFile("/dev/null"); },
                                                             [] { loadMapFileInfo("/dev/urandom"); }})
  {
    const std::string d = errorOf(load);
    EXPECT_TRUE(contains(d, "[runtime_error]") && contains(d, "character device")) << d;
  }
}

TEST_F(FileEdges, DirectoryIsRefusedByName)
{
  const std::string dir = tmp("adir");
  ASSERT_TRUE(std::filesystem::create_directory(dir));
  for (const auto& load :
       std::vector<std::function<void()>>{[&] { loadMapFileInfo(dir); }, [&] { loadParamsYamlFile(dir); },
                                          [&] { loadFeaturesFile(dir); }, [&] { loadMapFile(mapYaml("d.yaml", dir)); }})
  {
    const std::string e = errorOf(load);
    EXPECT_TRUE(contains(e, "[runtime_error]") && contains(e, dir) && contains(e, "directory")) << e;
  }
}

// ---------------------------------------------------------------------------------------------
// Too large

TEST_F(FileEdges, OversizeSparseFilesAreRefusedFromTheirSize)
{
  // One byte over each cap; the content is valid as far as it goes, then zeros.
  const std::string params = tmp("big_params.yaml");
  writeSparse(params, "a: 1\n", kYamlCap + 1);
  const std::string map_yaml = tmp("big_map.yaml");
  writeSparse(map_yaml, std::string("image: x.pgm\n") + kMapYamlKeys, kYamlCap + 1);
  const std::string image = tmp("big.pgm");
  writeSparse(image, "P5\n100 100\n255\n", kImageCap + 1);

  const std::string limit_yaml = std::to_string(kYamlCap);
  for (const auto& [path, load] :
       std::vector<std::pair<std::string, std::function<void()>>>{{params, [&] { loadParamsYamlFile(params); }},
                                                                  {params, [&] { loadFeaturesFile(params); }},
                                                                  {map_yaml, [&] { loadMapFileInfo(map_yaml); }}})
  {
    const std::string e = errorOf(load);
    EXPECT_TRUE(contains(e, "[runtime_error]") && contains(e, path) && contains(e, "too large") &&
                contains(e, limit_yaml))
        << e;
  }
  const std::string e = errorOf([&] { loadMapFile(mapYaml("big_image.yaml", image)); });
  EXPECT_TRUE(contains(e, "[runtime_error]") && contains(e, image) && contains(e, "too large") &&
              contains(e, std::to_string(kImageCap)))
      << e;

  // Exactly at the cap is still read (and then judged by its content).
  const std::string at_cap = tmp("cap_params.yaml");
  writeSparse(at_cap, "a: 1\n", kYamlCap);
  const std::string c = errorOf([&] { loadParamsYamlFile(at_cap); });
  EXPECT_FALSE(contains(c, "too large")) << c;
}

// ---------------------------------------------------------------------------------------------
// Image headers promising too many cells: 22000 x 22000 = 484 million > 400 million.

/// A PNG of w x h 8-bit grey pixels whose IDAT holds only a few bytes, followed by `padding` bytes of
/// an ancillary chunk: the file is large enough that a deflate-ratio test alone lets it through (the
/// 512 KB PNG of the attack), while the pixels it promises need w * h bytes.
std::string hugePng(uint32_t w, uint32_t h, std::size_t padding)
{
  const std::string ihdr = be32(w) + be32(h) + std::string("\x08\x00\x00\x00\x00", 5);
  std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + pngChunk("IHDR", ihdr);
  png += pngChunk("IDAT", std::string("\x78\x9c", 2));  // a zlib header, nothing more
  png += pngChunk("zPAD", std::string(padding, '\0'));
  png += pngChunk("IEND", "");
  return png;
}

TEST_F(FileEdges, PngHeaderPromisingMoreCellsThanTheLimitIsRefusedBeforeAllocating)
{
  const std::string png = hugePng(22000, 22000, 512 * 1024);
  ASSERT_EQ(png.substr(12, 4), "IHDR");
  const std::string path = tmp("huge.png");
  writeBytes(path, png);
  const std::string e = errorOf([&] { loadMapFile(mapYaml("huge_png.yaml", path)); });
  EXPECT_TRUE(contains(e, "[runtime_error]") && contains(e, path)) << e;
  EXPECT_TRUE(contains(e, "22000x22000") && contains(e, "400000000")) << e;
  // The same bytes in memory (what the fuzz target and decodeMapImage callers see).
  const std::vector<uint8_t> bytes(png.begin(), png.end());
  const std::string m = errorOf([&] { decodeMapImage(bytes, MapFileInfo{"", 0.05}, "huge.png"); });
  EXPECT_TRUE(contains(m, "22000x22000") && contains(m, "400000000")) << m;
  // One side over the per-side limit (100000) is refused as before.
  const std::string wide = tmp("wide.png");
  writeBytes(wide, hugePng(100001, 1, 16));
  const std::string w = errorOf([&] { loadMapImage(wide, MapFileInfo{"", 0.05}); });
  EXPECT_TRUE(contains(w, "100001x1") && contains(w, "absurdly large")) << w;
}

TEST_F(FileEdges, PgmHeaderPromisingMoreCellsThanTheLimitIsRefusedBeforeReading)
{
  // A sparse PGM whose pixel data is all there (zeros): 484 million bytes after the header. It must
  // be refused from its header, not read and decoded into a 484-million-cell grid.
  const std::string header = "P5\n22000 22000\n255\n";
  const std::string path = tmp("huge.pgm");
  writeSparse(path, header, header.size() + uint64_t{22000} * 22000);
  const std::string e = errorOf([&] { loadMapFile(mapYaml("huge_pgm.yaml", path)); });
  EXPECT_TRUE(contains(e, "[runtime_error]") && contains(e, path)) << e;
  EXPECT_TRUE(contains(e, "22000x22000") && contains(e, "400000000")) << e;
  // In memory, with the header alone, and as ASCII.
  for (const std::string& text :
       {header, std::string("P2 22000 22000 255\n0 0 0\n"), std::string("P6 20001 20000 255 ")})
  {
    const std::vector<uint8_t> bytes(text.begin(), text.end());
    const std::string m = errorOf([&] { decodeMapImage(bytes, MapFileInfo{"", 0.05}, "huge.pgm"); });
    EXPECT_TRUE(contains(m, "absurdly large") && contains(m, "400000000")) << text << ": " << m;
  }
  // 20000 x 20000 is exactly the limit: refused only because the file is short, and from the header.
  const std::string at_limit = tmp("limit.pgm");
  writeBytes(at_limit, "P5\n20000 20000\n255\n");
  const std::string l = errorOf([&] { loadMapImage(at_limit, MapFileInfo{"", 0.05}); });
  EXPECT_TRUE(contains(l, "truncated") && !contains(l, "absurdly")) << l;
}

TEST_F(FileEdges, ImageOfUnknownFormatIsRefusedFromItsFirstBytes)
{
  // 600 MB of zeros: no image format starts with a zero byte; refused without reading the rest.
  const std::string path = tmp("zeros.img");
  writeSparse(path, "", uint64_t{600} << 20);
  const std::string e = errorOf([&] { loadMapImage(path, MapFileInfo{"", 0.05}); });
  EXPECT_TRUE(contains(e, "[runtime_error]") && contains(e, path) && contains(e, "bad image header")) << e;
}

// ---------------------------------------------------------------------------------------------
// YAML alias expansion

/// `levels` anchors, each a list of ten aliases of the one before: 10^levels leaves.
std::string aliasBomb(int levels)
{
  std::string text = "l0: &l0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int k = 1; k < levels; ++k)
  {
    const std::string prev = "*l" + std::to_string(k - 1);
    text += "l" + std::to_string(k) + ": &l" + std::to_string(k) + " [";
    for (int i = 0; i < 10; ++i)
      text += (i ? ", " : "") + prev;
    text += "]\n";
  }
  return text;
}

TEST_F(FileEdges, YamlAliasBombIsRefused)
{
  // The "billion laughs": 9 levels, about 500 bytes, 10^9 values once expanded.
  const std::string bomb = aliasBomb(9);
  EXPECT_LT(bomb.size(), 520u);
  const std::string path = tmp("bomb.yaml");
  writeBytes(path, bomb);
  for (const auto& load :
       std::vector<std::function<void()>>{[&] { loadParamsYamlFile(path); }, [&] { loadFeaturesFile(path); },
                                          [&] { parseParamsYaml(bomb, "--params"); }})
  {
    const std::string e = errorOf(load);
    EXPECT_TRUE(contains(e, "[runtime_error]") && contains(e, "alias")) << e;
  }
  // Six levels: level k expands to V(k) = 1 + 10 V(k-1) values with V(0) = 11 (a list of ten), so the
  // document is 1 + 11 + 111 + ... + 1111111 = 1234567 values, over the budget of 2^18 = 262144.
  const std::string six = errorOf([&] { parseParamsYaml(aliasBomb(6), "six"); });
  EXPECT_TRUE(contains(six, "[runtime_error]") && contains(six, "six") && contains(six, "262144")) << six;
  // Five levels (1 + 11 + ... + 111111 = 123456 values) are large but allowed: aliases still work.
  const auto five = parseParamsYaml(aliasBomb(5), "five");
  ASSERT_NE(five.findPath("l4"), nullptr);
  EXPECT_EQ(five.findPath("l4")->asList().size(), 10u);
  EXPECT_EQ(five.findPath("l4")->asList()[3].asList()[9].asList()[0].asList().size(), 10u);
  // A map YAML keeps no expanded tree: a bomb beside the keys costs nothing and the map loads.
  const std::string map = tmp("map_bomb.yaml");
  writeBytes(map, std::string("image: x.pgm\n") + kMapYamlKeys + aliasBomb(9));
  EXPECT_EQ(errorOf([&] { loadMapFileInfo(map); }), "");
}

// ---------------------------------------------------------------------------------------------
// Numbers at the edge in a map YAML: resolution in [1e-4, 1e3] m/pixel, |origin x/y| <= 1e7 m,
// |yaw| <= 1e3 rad, thresholds in [0, 1].

TEST(MapYamlNumbers, EdgesOfEveryNumericKey)
{
  struct Case
  {
    std::string resolution, origin, occ, free;
    bool ok;
    std::string needle;  // in the error when refused
  };
  const std::vector<Case> cases = {
      {"1e-4", "[0, 0, 0]", "0.65", "0.196", true, ""},
      {"1e3", "[0, 0, 0]", "0.65", "0.196", true, ""},
      {"1e-300", "[0, 0, 0]", "0.65", "0.196", false, "resolution"},
      {"1e300", "[0, 0, 0]", "0.65", "0.196", false, "resolution"},
      {"9.9e-5", "[0, 0, 0]", "0.65", "0.196", false, "resolution"},
      {"1000.001", "[0, 0, 0]", "0.65", "0.196", false, "resolution"},
      {"0", "[0, 0, 0]", "0.65", "0.196", false, "resolution"},
      {"-0.05", "[0, 0, 0]", "0.65", "0.196", false, "resolution"},
      {".nan", "[0, 0, 0]", "0.65", "0.196", false, "resolution"},
      {".inf", "[0, 0, 0]", "0.65", "0.196", false, "resolution"},
      {"0.05", "[1e7, -1e7, 1e3]", "0.65", "0.196", true, ""},
      {"0.05", "[-1e7, 1e7, -1e3]", "0.65", "0.196", true, ""},
      {"0.05", "[1e300, 0, 0]", "0.65", "0.196", false, "origin x"},
      {"0.05", "[0, -10000000.5, 0]", "0.65", "0.196", false, "origin y"},
      {"0.05", "[0, 0, 1e300]", "0.65", "0.196", false, "origin yaw"},
      {"0.05", "[0, 0, -1000.5]", "0.65", "0.196", false, "origin yaw"},
      {"0.05", "[0, .nan, 0]", "0.65", "0.196", false, "origin"},
      {"0.05", "[0, 0, 0]", "1.0", "0.0", true, ""},
      {"0.05", "[0, 0, 0]", "1.5", "0.196", false, "thresh"},
      {"0.05", "[0, 0, 0]", "0.65", "-1e-300", false, "thresh"},
      {"0.05", "[0, 0, 0]", ".nan", "0.196", false, "thresh"},
  };
  for (const auto& c : cases)
  {
    const std::string text = "image: x.pgm\nresolution: " + c.resolution + "\norigin: " + c.origin +
                             "\nnegate: 0\noccupied_thresh: " + c.occ + "\nfree_thresh: " + c.free + "\n";
    const std::string e = errorOf([&] { parseMapFileInfo(text, "/maps/edge.yaml"); });
    if (c.ok)
    {
      EXPECT_EQ(e, "") << text;
      continue;
    }
    EXPECT_TRUE(contains(e, "[runtime_error]") && contains(e, "/maps/edge.yaml") && contains(e, c.needle)) << text << e;
  }
  // The same ranges hold for an info handed to the image decoder directly.
  const std::vector<uint8_t> pgm = {'P', '5', ' ', '1', ' ', '1', ' ', '2', '5', '5', ' ', 0};
  for (const double res : {1e-300, 1e300, 9e-5, 1001.0})
  {
    const std::string e = errorOf([&] { decodeMapImage(pgm, MapFileInfo{"", res}, "direct.pgm"); });
    EXPECT_TRUE(contains(e, "resolution")) << res << ": " << e;
  }
  MapFileInfo far{"", 0.05};
  far.origin[0] = 1e300;
  EXPECT_TRUE(contains(errorOf([&] { decodeMapImage(pgm, far, "direct.pgm"); }), "origin")) << "origin 1e300";
  EXPECT_EQ(errorOf([&] { decodeMapImage(pgm, MapFileInfo{"", 1e-4}, "direct.pgm"); }), "");
}
}  // namespace
