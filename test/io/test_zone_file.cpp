// Zone files: written by hand, read, saved and read back; the saved file rasterises to the same mask.
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "costmap_layers/core/rules/limits.hpp"
#include "costmap_layers/io/zone_file.hpp"
#include "temp_dir_test.hpp"
#include "zone_shape_helpers.hpp"

using namespace costmap_layers;

namespace
{
void write(const std::string& path, const std::string& text)
{
  std::ofstream(path) << text;
}

const char* kFile = R"(# a keepout wall and a slow circle
frame_id: map
resolution: 0.05
default_value: 0
overlay: max
shapes:
  - name: dock
    type: polygon
    value: 100
    points: [[1.0, 1.0], [3.0, 1.0], [3.0, 2.5], [1.0, 2.5]]
  - {name: slow, type: circle, value: 40, fill: false, center: [5, 2], radius: 1.2}
)";
}  // namespace

class ZoneFile : public TempDirTest
{
};

TEST_F(ZoneFile, ReadsWhatAPersonWrites)
{
  write(tmp("z.yaml"), kFile);
  const ZoneLayout l = io::loadZoneFile(tmp("z.yaml"));
  ASSERT_EQ(l.shapes.size(), 2u);
  EXPECT_EQ(l.overlay, ZoneOverlay::Max);
  EXPECT_EQ(l.shapes[0].name, "dock");
  EXPECT_EQ(l.shapes[0].points.size(), 4u);
  EXPECT_TRUE(l.shapes[0].fill);
  EXPECT_EQ(l.shapes[1].type, ZoneShapeType::Circle);
  EXPECT_FALSE(l.shapes[1].fill);
  EXPECT_DOUBLE_EQ(l.shapes[1].radius, 1.2);
  EXPECT_DOUBLE_EQ(l.shapes[1].center.x, 5.0);  // an integer in the file is a number of metres too
}

TEST_F(ZoneFile, SavedFileReloadsToTheSameLayoutAndMask)
{
  write(tmp("z.yaml"), kFile);
  ZoneSet set(io::loadZoneFile(tmp("z.yaml")));
  // An edit with a number that has no short decimal form, so that a lossy writer would show.
  ASSERT_TRUE(set.moveHandle("dock", 2, 3.0 + 1.0 / 3.0, 2.5 + 1e-9).ok());
  io::saveZoneFile(tmp("saved.yaml"), set.layout());
  const ZoneLayout back = io::loadZoneFile(tmp("saved.yaml"));
  ASSERT_EQ(back.shapes.size(), 2u);
  EXPECT_EQ(back.shapes[0].points[2].x, 3.0 + 1.0 / 3.0);  // bit for bit
  EXPECT_EQ(back.shapes[0].points[2].y, 2.5 + 1e-9);
  const OccupancyGridData a = rasterizeZones(set.layout()), b = rasterizeZones(back);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.origin_x, b.origin_x);
  EXPECT_EQ(a.origin_y, b.origin_y);
  EXPECT_EQ(a.data, b.data);
  // Saving over an existing file replaces it.
  io::saveZoneFile(tmp("z.yaml"), back);
  EXPECT_EQ(io::loadZoneFile(tmp("z.yaml")).shapes[0].points[2].x, 3.0 + 1.0 / 3.0);
}

TEST_F(ZoneFile, BadFilesNameThePathAndTheField)
{
  auto refused = [&](const std::string& text, const std::string& needle)
  {
    write(tmp("bad.yaml"), text);
    try
    {
      io::loadZoneFile(tmp("bad.yaml"));
      ADD_FAILURE() << "accepted; expected " << needle;
    }
    catch (const std::exception& e)
    {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.yaml"), std::string::npos) << e.what();
    }
  };
  refused("shapes:\n  - {name: a, type: polygon, value: 100, points: [[0, 0], [1, 1]]}\n", "at least 3 points");
  refused("shapes:\n  - {name: a, type: polygon, value: 100, points: [[0, 0], [1, .nan], [1, 0]]}\n", "finite");
  refused("shapes:\n  - {name: a, type: polygon, value: 100, points: [[0, 0], [1, 1], [1, 0], [0, 1]]}\n",
          "self-intersecting");
  refused("shapes:\n  - {name: a, type: circle, value: 100, center: [0, 0], radius: 1, colour: red}\n",
          "unknown field 'colour'");
  refused("resolution: 0.0001\nshapes:\n  - {name: a, type: circle, value: 100, center: [0, 0], radius: 9000}\n",
          "cells a mask may have");
  refused("shapes: [\n", "bad.yaml");
  // A key written twice would lose its first value: this package's own format refuses it, naming both lines.
  refused("shapes:\n  - {name: a, type: circle, value: 100, center: [0, 0], radius: 1}\nresolution: 0.05\nshapes: []\n",
          "at line 4: key 'shapes' is written twice in one map (first at line 1)");
  refused("shapes:\n  - {name: a, type: circle, value: 100, value: 40, center: [0, 0], radius: 1}\n",
          "key 'value' is written twice");
  EXPECT_THROW(io::loadZoneFile(tmp("missing.yaml")), std::exception);
  // A misspelt top-level key of a zone file is named ...
  refused("frame_id: map\nshape: []\n", "unknown field 'shape'");
  // ... but a file that is not meant as one is not quoted (zone_server answers a peer that named it):
  // neither its keys nor its values appear in the message.
  for (const char* text : {"api_key: hunter2\nuser: root\n", "hunter2\n", "[hunter2, root]\n"})
  {
    write(tmp("secret.yaml"), text);
    try
    {
      io::loadZoneFile(tmp("secret.yaml"));
      ADD_FAILURE() << "accepted " << text;
    }
    catch (const std::exception& e)
    {
      const std::string what = e.what();
      EXPECT_NE(what.find("not a zone file"), std::string::npos) << what;
      EXPECT_EQ(what.find("hunter2"), std::string::npos) << what;
      EXPECT_EQ(what.find("api_key"), std::string::npos) << what;
      EXPECT_EQ(what.find("root"), std::string::npos) << what;
    }
  }
}

TEST_F(ZoneFile, SaveRefusesAnInvalidLayoutAndAnUnwritablePath)
{
  ZoneLayout l;
  l.resolution = 0.0;
  EXPECT_THROW(io::saveZoneFile(tmp("x.yaml"), l), std::runtime_error);
  EXPECT_THROW(io::saveZoneFile(tmp("no/such/dir/x.yaml"), ZoneLayout{}), std::runtime_error);
}

namespace
{
/// The text read back as parseZoneLayout() reads a file (through the io library's YAML reader).
ZoneLayout reread(const std::string& text, const std::string& path)
{
  std::ofstream(path) << text;
  return io::loadZoneFile(path);
}
}  // namespace

// Moved from test/core/zones/test_zone_shapes.cpp with the writer (the core no longer writes YAML).
TEST(ZoneLayoutParse, YamlTextReadsBackToAnEqualLayout)
{
  // zoneLayoutToYaml is read back in the tests below; here, the text itself: the shortest digits that
  // read back (1/3 is 0.333333333333333314829616256247..., and 16 threes already name it), names quoted.
  ZoneLayout l;
  l.shapes = {polygon("dock", {{0.1, 0.2}, {1.0 / 3.0, 0.2}, {0.3, 0.7}}, 100, false)};
  const std::string y = io::zoneLayoutToYaml(l);
  EXPECT_NE(y.find("- [0.3333333333333333, 0.2]\n"), std::string::npos) << y;
  EXPECT_EQ(y.find("0.33333333333333331"), std::string::npos) << y;
  EXPECT_NE(y.find("name: \"dock\""), std::string::npos) << y;
  EXPECT_NE(y.find("fill: false"), std::string::npos) << y;
}

TEST_F(ZoneFile, WrittenTextReadsBackBitForBit)
{
  ZoneLayout l;
  l.frame_id = "odd\"frame\"\\name";  // quotes and a backslash: printable ASCII without spaces
  l.resolution = 0.1;
  l.default_value = -1;
  l.overlay = ZoneOverlay::Min;
  // Names YAML would read as other types unquoted; integral and awkward doubles; a circle and an outline.
  l.shapes = {polygon("1", {{-2.0, 1e-7}, {4.0, 0.0}, {1.0 / 7.0, 3.0}}, 0, true),
              polygon("yes", {{10.0, 10.0}, {12.5, 10.0}, {12.5, 11.0 + 1e-12}}, -1, false),
              circle("null", 5.0, -3.0 / 11.0, 2.0 / 3.0, 55)};
  const ZoneLayout back = reread(io::zoneLayoutToYaml(l), tmp("w.yaml"));
  EXPECT_EQ(back.frame_id, l.frame_id);
  EXPECT_EQ(back.resolution, l.resolution);
  EXPECT_EQ(back.default_value, l.default_value);
  EXPECT_EQ(back.overlay, l.overlay);
  ASSERT_EQ(back.shapes.size(), l.shapes.size());
  for (std::size_t k = 0; k < l.shapes.size(); ++k)
  {
    const ZoneShape& a = l.shapes[k];
    const ZoneShape& b = back.shapes[k];
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.type, a.type);
    EXPECT_EQ(b.value, a.value);
    EXPECT_EQ(b.fill, a.fill);
    EXPECT_EQ(b.radius, a.radius);
    EXPECT_EQ(b.center.x, a.center.x);
    EXPECT_EQ(b.center.y, a.center.y);
    ASSERT_EQ(b.points.size(), a.points.size());
    for (std::size_t i = 0; i < a.points.size(); ++i)
    {
      EXPECT_EQ(b.points[i].x, a.points[i].x) << k << "/" << i;
      EXPECT_EQ(b.points[i].y, a.points[i].y) << k << "/" << i;
    }
  }
  EXPECT_EQ(rasterizeZones(back).data, rasterizeZones(l).data);
}

TEST_F(ZoneFile, EmptyLayoutWritesAnEmptyShapeList)
{
  const std::string y = io::zoneLayoutToYaml(ZoneLayout{});
  EXPECT_NE(y.find("shapes: []"), std::string::npos) << y;
  EXPECT_EQ(y.rfind("# zone_server shapes", 0), 0u) << y;
  EXPECT_TRUE(reread(y, tmp("e.yaml")).shapes.empty());
}

namespace
{
std::string contents(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

uint64_t fileSize(const std::string& path)
{
  struct stat st
  {
  };
  return ::stat(path.c_str(), &st) == 0 ? static_cast<uint64_t>(st.st_size) : 0;
}

/// Equal bit for bit (so -0.0 differs from 0.0).
bool same(double a, double b)
{
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

/// Whether b is a, every number bit for bit; the first difference is reported.
::testing::AssertionResult sameLayout(const ZoneLayout& a, const ZoneLayout& b)
{
  if (a.frame_id != b.frame_id) return ::testing::AssertionFailure() << "frame_id";
  if (!same(a.resolution, b.resolution)) return ::testing::AssertionFailure() << "resolution";
  if (a.default_value != b.default_value || a.overlay != b.overlay) return ::testing::AssertionFailure() << "header";
  if (a.shapes.size() != b.shapes.size()) return ::testing::AssertionFailure() << "shape count";
  for (std::size_t k = 0; k < a.shapes.size(); ++k)
  {
    const ZoneShape& s = a.shapes[k];
    const ZoneShape& t = b.shapes[k];
    if (s.name != t.name) return ::testing::AssertionFailure() << "name of shape " << k;
    if (s.type != t.type || s.value != t.value || s.fill != t.fill)
      return ::testing::AssertionFailure() << "type, value or fill of shape " << k;
    if (s.type == ZoneShapeType::Circle &&
        (!same(s.center.x, t.center.x) || !same(s.center.y, t.center.y) || !same(s.radius, t.radius)))
      return ::testing::AssertionFailure() << "circle " << k;
    if (s.type == ZoneShapeType::Polygon)
    {
      if (s.points.size() != t.points.size()) return ::testing::AssertionFailure() << "points of shape " << k;
      for (std::size_t i = 0; i < s.points.size(); ++i)
        if (!same(s.points[i].x, t.points[i].x) || !same(s.points[i].y, t.points[i].y))
          return ::testing::AssertionFailure() << "shape " << k << " point " << i;
    }
  }
  return ::testing::AssertionSuccess();
}

/// A polygon star-shaped around (cx, cy): n vertices at increasing angles, each at a radius in
/// [0.5 r, r]: its edges never cross. Random digits in every coordinate (17 significant ones mostly).
ZoneShape star(std::mt19937_64& rng, const std::string& name, std::size_t n, double cx, double cy, double r)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<ZonePoint> p;
  for (std::size_t k = 0; k < n; ++k)
  {
    const double a = 2.0 * M_PI * (static_cast<double>(k) + 0.4 * unit(rng)) / static_cast<double>(n);
    const double rho = r * (0.5 + 0.5 * unit(rng));
    p.push_back({cx + rho * std::cos(a), cy + rho * std::sin(a)});
  }
  std::uniform_int_distribution<int> value(-1, 100);
  return polygon(name, std::move(p), value(rng), unit(rng) < 0.7);
}

/// A name of exactly `bytes` bytes (>= 8) starting with its index (names are unique), then pieces that
/// stress the writer: quotes and backslashes, YAML syntax, UTF-8 of 2, 3 and 4 bytes including NEL
/// (U+0085), NBSP, LINE SEPARATOR (U+2028), BOM (U+FEFF), the noncharacters U+FDD0 and U+FFFF, and
/// U+10FFFF; spaces at either end.
std::string label(std::mt19937_64& rng, std::size_t index, std::size_t bytes)
{
  static const std::vector<std::string> kPieces = {"\"",
                                                   "\\",
                                                   " ",
                                                   "#",
                                                   ": ",
                                                   "- ",
                                                   "'",
                                                   "{",
                                                   "[",
                                                   ",",
                                                   "&",
                                                   "*",
                                                   "!",
                                                   "%",
                                                   "@",
                                                   "`",
                                                   "a",
                                                   "Z",
                                                   "9",
                                                   "_",
                                                   "\xc3\xa9",
                                                   "\xc2\x85",
                                                   "\xc2\xa0",
                                                   "\xe2\x80\xa8",
                                                   "\xef\xbb\xbf",
                                                   "\xef\xb7\x90",
                                                   "\xef\xbf\xbf",
                                                   "\xf0\x9f\x98\x80",
                                                   "\xf4\x8f\xbf\xbf",
                                                   "\xe6\xbc\xa2"};
  std::string name = std::to_string(index) + " ";
  std::uniform_int_distribution<std::size_t> pick(0, kPieces.size() - 1);
  while (name.size() < bytes)
  {
    const std::string& piece = kPieces[pick(rng)];
    name += name.size() + piece.size() <= bytes ? piece : std::string(1, 'x');
  }
  return name;
}

/// A frame id of kMaxNameLength printable ASCII characters with '"' and '\' among them.
std::string longestFrame()
{
  std::string f;
  for (std::size_t k = 0; f.size() < kMaxNameLength; ++k)
    f += static_cast<char>('!' + k % 94);  // '!' .. '~', '"' and '\' included
  return f;
}

/// Saves, checks the size against the cap, loads back; returns the file's size.
uint64_t roundTrip(const ZoneLayout& l, const std::string& path)
{
  EXPECT_TRUE(validateLayout(l).ok()) << validateLayout(l).message;
  io::saveZoneFile(path, l);
  const uint64_t size = fileSize(path);
  EXPECT_LE(size, io::kMaxZoneYamlBytes);
  ZoneLayout back;
  try
  {
    back = io::loadZoneFile(path);
  }
  catch (const std::exception& e)
  {
    ADD_FAILURE() << "a saved layout does not load: " << e.what();
    return size;
  }
  EXPECT_TRUE(sameLayout(l, back));
  return size;
}
}  // namespace

TEST_F(ZoneFile, NumbersAreWrittenInTheShortestFormThatReadsBack)
{
  ZoneLayout l;
  l.resolution = 1e3;  // kMaxResolution: the coordinate limit below stays within the cell limit
  // Each value and its shortest round-trip text, worked out by hand from the double's exact value.
  l.shapes = {polygon("n", {{-0.0, 0.1}, {-1.2345678901234567e-300, 3.0}, {1e7, 5e-324}}),
              circle("c", 2.5e-8, -9999999.999999998, 1.0 / 3.0)};
  const std::string y = io::zoneLayoutToYaml(l);
  EXPECT_NE(y.find("resolution: 1000\n"), std::string::npos) << y;
  EXPECT_NE(y.find("- [-0.0, 0.1]\n"), std::string::npos) << y;
  // 17 digits, 24 characters: the longest a number takes (its nearest double prints ...68 at 17 digits).
  EXPECT_NE(y.find("- [-1.2345678901234568e-300, 3]\n"), std::string::npos) << y;
  EXPECT_NE(y.find("- [1e+07, 5e-324]\n"), std::string::npos) << y;
  EXPECT_NE(y.find("center: [2.5e-08, -9999999.999999998]\n"), std::string::npos) << y;
  EXPECT_NE(y.find("radius: 0.3333333333333333\n"), std::string::npos) << y;
  const ZoneLayout back = reread(y, tmp("n.yaml"));
  EXPECT_TRUE(sameLayout(l, back));
  EXPECT_TRUE(std::signbit(back.shapes[0].points[0].x));
}

TEST(ZoneFileCaps, AreDerivedFromTheLayoutLimits)
{
  // Worked out by hand from the format: a vertex line is "      - [" + 24 + ", " + 24 + "]\n" = 61 bytes,
  // and a valid layout has at most floor(sqrt(1000 * 2e7)) = 141 421 vertices (Cauchy-Schwarz over
  // the vertex-pair limit): 8 626 681. A shape's lines at their longest (a circle, a 256-byte name with
  // every byte escaped): name 10 + 514 + 1, type 10 + 7 + 1, value 11 + 3 + 1, fill 10 + 5 + 1, centre
  // 13 + 52, radius 12 + 24 + 1: 676 bytes, 676 000 for 1000. The head: the comment 61, frame_id
  // 10 + 514 + 1, resolution 12 + 24 + 1, default_value 15 + 3 + 1, overlay 9 + 4 + 1, "shapes: []\n"
  // 11: 667. Values: 6 at the top, at most 9 per shape (a circle), 3 per vertex.
  EXPECT_EQ(io::kMaxZoneYamlBytes, 8626681u + 676000u + 667u);
  EXPECT_EQ(io::kMaxZoneYamlNodes, 6u + 9000u + 3u * 141421u);
}

TEST_F(ZoneFile, AThousandOctagonsSaveAndLoadBack)
{
  // The issue's layout: 1000 octagons (within every limit), 17-digit coordinates. Saved with 17 digits
  // it was 388 KB and its own load refused it (the cap was 262144 bytes).
  ZoneLayout l;
  for (int k = 0; k < 1000; ++k)
  {
    std::vector<ZonePoint> p;
    const double cx = (k % 40) * 2.5 + 0.1, cy = (k / 40) * 2.5 + 0.1;
    for (int j = 0; j < 8; ++j)
      p.push_back({cx + 0.9 * std::cos(0.1 + M_PI * j / 4.0), cy + 0.9 * std::sin(0.1 + M_PI * j / 4.0)});
    l.shapes.push_back(polygon("octagon_" + std::to_string(k), std::move(p)));
  }
  const uint64_t size = roundTrip(l, tmp("octagons.yaml"));
  std::cout << "[ figures  ] 1000 octagons: " << size << " bytes; zone-file cap " << io::kMaxZoneYamlBytes << " bytes, "
            << io::kMaxZoneYamlNodes << " values\n";
}

TEST_F(ZoneFile, EveryValidLayoutAtTheLimitsSavesAndLoadsBackEqual)
{
  // Property: whatever valid layout the server holds, what it saves loads back equal. Seeded layouts at
  // the edge of each limit, then smaller random ones; each is asserted valid before it is saved.
  const std::string longest = longestFrame();
  ASSERT_EQ(longest.size(), kMaxNameLength);
  uint64_t largest = 0;

  // 1. kMaxZoneShapes shapes, polygons and circles, every name and the frame at their longest.
  {
    std::mt19937_64 rng(1);
    ZoneLayout l;
    l.frame_id = longest;
    l.resolution = 0.012345678901234567;
    l.overlay = ZoneOverlay::Max;
    l.default_value = -1;
    std::uniform_real_distribution<double> r(0.05, 1.0);
    for (std::size_t k = 0; k < limits::kMaxZoneShapes; ++k)
    {
      const double cx = static_cast<double>(k % 40) * 2.5, cy = static_cast<double>(k / 40) * 2.5;
      if (k % 2 == 0)
        l.shapes.push_back(star(rng, label(rng, k, kMaxNameLength), 3 + k % 20, cx, cy, r(rng)));
      else
        l.shapes.push_back(
            circle(label(rng, k, kMaxNameLength), cx, cy, r(rng), static_cast<int>(k % 102) - 1, k % 3 == 0));
    }
    largest = std::max(largest, roundTrip(l, tmp("shapes.yaml")));
  }
  // 2. The most vertices the vertex-pair limit allows: 420 polygons of 142 and 580 of 141 vertices
  //    (420 * 142^2 + 580 * 141^2 = 19 999 860 <= 2e7; one more vertex anywhere passes it), longest
  //    names: the largest file.
  {
    std::mt19937_64 rng(2);
    ZoneLayout l;
    l.frame_id = longest;
    l.resolution = 0.05;
    double pairs = 0.0;
    for (std::size_t k = 0; k < limits::kMaxZoneShapes; ++k)
    {
      const std::size_t n = k < 420 ? 142 : 141;
      pairs += static_cast<double>(n * n);
      l.shapes.push_back(star(rng, label(rng, k, kMaxNameLength), n, (k % 40) * 2.5, (k / 40) * 2.5, 1.0));
    }
    ASSERT_LE(pairs, limits::kMaxZoneVertexPairs);
    ASSERT_GT(pairs + 2 * 142 + 1, limits::kMaxZoneVertexPairs);
    const uint64_t size = roundTrip(l, tmp("pairs.yaml"));
    std::cout << "[ figures  ] 141 420 vertices, 1000 names of 256 bytes: " << size << " bytes\n";
    largest = std::max(largest, size);
  }
  // 3. kMaxZoneVertices in each of 20 polygons (20 * 1000^2 = 2e7: the pair limit exactly).
  {
    std::mt19937_64 rng(3);
    ZoneLayout l;
    for (std::size_t k = 0; k < 20; ++k)
      l.shapes.push_back(star(rng, label(rng, k, 8 + k * 12), limits::kMaxZoneVertices, k * 30.0, 0.0, 12.0));
    largest = std::max(largest, roundTrip(l, tmp("vertices.yaml")));
  }
  // 4. Numbers at their longest text: tiny magnitudes with 17 significant digits and 3-digit exponents,
  //    subnormals, negative zero, the coordinate limit.
  {
    ZoneLayout l;
    l.resolution = 1e3;  // kMaxResolution: the far corners below stay within the cell limit
    l.shapes = {polygon("tiny", {{-1.2345678901234567e-300, -2.2250738585072014e-308},
                                 {1.5, -4.9406564584124654e-324},
                                 {0.75, 1.7976931348623157e-299}}),
                polygon("far", {{-1e7, -1e7}, {-9999999.999999998, -1e7}, {-1e7, -9999999.999999996}}),
                polygon("zero", {{-0.0, -0.0}, {2.0, 0.0}, {0.0, 2.0}}),
                circle("dot", -1.2345678901234567e-300, 9.8765432109876543e-300, 1.2345678901234567e-300)};
    largest = std::max(largest, roundTrip(l, tmp("numbers.yaml")));
  }
  // 5. Random layouts below the limits.
  std::mt19937_64 rng(5);
  for (int round = 0; round < 40; ++round)
  {
    std::uniform_int_distribution<std::size_t> count(0, 60), verts(3, 60), len(1, kMaxNameLength);
    std::uniform_real_distribution<double> r(0.1, 2.0), res(0.01, 0.5);
    ZoneLayout l;
    l.resolution = res(rng);
    l.default_value = static_cast<int>(rng() % 102) - 1;
    l.overlay = static_cast<ZoneOverlay>(rng() % 3);
    l.frame_id = longest.substr(0, len(rng));
    const std::size_t shapes = count(rng);
    for (std::size_t k = 0; k < shapes; ++k)
    {
      const double cx = static_cast<double>(k % 8) * 5.0 - 20.0, cy = static_cast<double>(k / 8) * 5.0 - 20.0;
      const std::string name = label(rng, k, std::max<std::size_t>(8, len(rng)));
      if (rng() % 2)
        l.shapes.push_back(star(rng, name, verts(rng), cx, cy, r(rng)));
      else
        l.shapes.push_back(circle(name, cx, cy, r(rng), static_cast<int>(rng() % 102) - 1, rng() % 2 == 0));
    }
    roundTrip(l, tmp("random.yaml"));
  }
  EXPECT_LE(largest, io::kMaxZoneYamlBytes);
}

TEST_F(ZoneFile, SaveReplacesOnlyAZoneFile)
{
  write(tmp("z.yaml"), kFile);
  const ZoneLayout l = io::loadZoneFile(tmp("z.yaml"));
  // A robot's parameters (the issue's example), a map_server map file, an empty file, a text that is not
  // YAML, a YAML list: none is a zone file, and none is replaced.
  const std::vector<std::string> others = {"robot_radius: 0.3\ninflation_radius: 0.55\n",
                                           "image: map.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n", "", "a: [b\n",
                                           "- shapes\n- frame_id\n"};
  for (const std::string& text : others)
  {
    write(tmp("other.yaml"), text);
    EXPECT_THROW(io::saveZoneFile(tmp("other.yaml"), l), std::runtime_error) << text;
    EXPECT_EQ(contents(tmp("other.yaml")), text);
  }
  // A zone file, even one that does not load (a hand edit gone wrong), may be saved over.
  write(tmp("broken.yaml"), "frame_id: map\nshapes: 3\n");
  io::saveZoneFile(tmp("broken.yaml"), l);
  EXPECT_TRUE(sameLayout(l, io::loadZoneFile(tmp("broken.yaml"))));
}

TEST_F(ZoneFile, SaveThroughALinkWritesItsTargetAndKeepsTheLink)
{
  ASSERT_EQ(::mkdir(tmp("shared").c_str(), 0755), 0);
  write(tmp("shared/zones.yaml"), kFile);
  ASSERT_EQ(::symlink(tmp("shared/zones.yaml").c_str(), tmp("link.yaml").c_str()), 0);
  ASSERT_EQ(::symlink(tmp("link.yaml").c_str(), tmp("link2.yaml").c_str()), 0);  // a link to a link
  ZoneSet set(io::loadZoneFile(tmp("link.yaml")));
  ASSERT_TRUE(set.remove("slow").ok());
  for (const char* name : {"link.yaml", "link2.yaml"})
  {
    io::saveZoneFile(tmp(name), set.layout());
    struct stat st
    {
    };
    ASSERT_EQ(::lstat(tmp(name).c_str(), &st), 0);
    EXPECT_TRUE(S_ISLNK(st.st_mode)) << name;
    EXPECT_EQ(io::loadZoneFile(tmp("shared/zones.yaml")).shapes.size(), 1u) << name;
  }
  // A link to a file that is not a zone file, and a link to nothing: refused, nothing made.
  write(tmp("shared/params.yaml"), "robot_radius: 0.3\n");
  ASSERT_EQ(::symlink(tmp("shared/params.yaml").c_str(), tmp("params_link.yaml").c_str()), 0);
  EXPECT_THROW(io::saveZoneFile(tmp("params_link.yaml"), set.layout()), std::runtime_error);
  EXPECT_EQ(contents(tmp("shared/params.yaml")), "robot_radius: 0.3\n");
  ASSERT_EQ(::symlink(tmp("shared/none.yaml").c_str(), tmp("dangling.yaml").c_str()), 0);
  EXPECT_THROW(io::saveZoneFile(tmp("dangling.yaml"), set.layout()), std::runtime_error);
  EXPECT_NE(::access(tmp("shared/none.yaml").c_str(), F_OK), 0);
}

TEST_F(ZoneFile, SaveKeepsTheFilesModeAndOwner)
{
  write(tmp("z.yaml"), kFile);
  const ZoneLayout l = io::loadZoneFile(tmp("z.yaml"));
  for (const mode_t mode : {mode_t{0600}, mode_t{0640}})
  {
    ASSERT_EQ(::chmod(tmp("z.yaml").c_str(), mode), 0);
    io::saveZoneFile(tmp("z.yaml"), l);
    struct stat st
    {
    };
    ASSERT_EQ(::stat(tmp("z.yaml").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, mode);
  }
  // Only root may give a file to another user (the package's test containers run as root).
  const uid_t uid = ::geteuid() == 0 ? 1234 : ::geteuid();
  const gid_t gid = ::geteuid() == 0 ? 5678 : ::getegid();
  ASSERT_EQ(::chown(tmp("z.yaml").c_str(), uid, gid), 0);
  io::saveZoneFile(tmp("z.yaml"), l);
  struct stat st
  {
  };
  ASSERT_EQ(::stat(tmp("z.yaml").c_str(), &st), 0);
  EXPECT_EQ(st.st_uid, uid);
  EXPECT_EQ(st.st_gid, gid);
}

TEST_F(ZoneFile, ALinkPlantedAtTheOldTemporaryNameIsNotFollowed)
{
  // The writer used "<target>.tmp.<pid>" with an ordinary open: a link planted there redirected the
  // write. A link to a file (which would be overwritten) and a link to nothing (which would be created).
  write(tmp("z.yaml"), kFile);
  const ZoneLayout l = io::loadZoneFile(tmp("z.yaml"));
  const std::string planted = tmp("z.yaml") + ".tmp." + std::to_string(::getpid());
  write(tmp("victim.txt"), "keep me\n");
  ASSERT_EQ(::symlink(tmp("victim.txt").c_str(), planted.c_str()), 0);
  io::saveZoneFile(tmp("z.yaml"), l);
  EXPECT_EQ(contents(tmp("victim.txt")), "keep me\n");
  struct stat st
  {
  };
  ASSERT_EQ(::lstat(tmp("z.yaml").c_str(), &st), 0);
  EXPECT_TRUE(S_ISREG(st.st_mode));
  ASSERT_EQ(::unlink(planted.c_str()), 0);
  ASSERT_EQ(::symlink(tmp("created.txt").c_str(), planted.c_str()), 0);
  io::saveZoneFile(tmp("z.yaml"), l);
  EXPECT_NE(::access(tmp("created.txt").c_str(), F_OK), 0);
}

namespace
{
/// The reason a ZoneFolder gives for `name` ("" when it resolves).
std::string folderRefusal(const io::ZoneFolder& folder, const std::string& name, bool load)
{
  try
  {
    (void)(load ? folder.fileToLoad(name) : folder.fileToSave(name));
    return "";
  }
  catch (const std::invalid_argument& e)
  {
    return e.what();
  }
}
}  // namespace

TEST_F(ZoneFile, NamesStayInsideTheSaveDirectory)
{
  // tmp/zones holds the loaded file; tmp/robot a robot's parameters; tmp/zones/escape links to tmp/robot.
  ASSERT_EQ(::mkdir(tmp("zones").c_str(), 0755), 0);
  ASSERT_EQ(::mkdir(tmp("zones/sub").c_str(), 0755), 0);
  ASSERT_EQ(::mkdir(tmp("robot").c_str(), 0755), 0);
  write(tmp("zones/zones.yaml"), kFile);
  write(tmp("zones/other.yaml"), kFile);
  write(tmp("robot/params.yaml"), "robot_radius: 0.3\n");
  write(tmp("robot/zones.yaml"), kFile);
  ASSERT_EQ(::symlink(tmp("robot").c_str(), tmp("zones/escape").c_str()), 0);
  ASSERT_EQ(::symlink(tmp("robot/zones.yaml").c_str(), tmp("zones/out_link.yaml").c_str()), 0);
  ASSERT_EQ(::symlink("other.yaml", tmp("zones/in_link.yaml").c_str()), 0);
  const io::ZoneFolder folder(tmp("zones/zones.yaml"));
  EXPECT_EQ(folder.directory(), tmp("zones"));

  // Allowed: the loaded file, relative names, an absolute name inside, a subfolder, a link inside.
  EXPECT_EQ(folder.fileToSave(""), tmp("zones/zones.yaml"));
  EXPECT_EQ(folder.fileToSave("new.yaml"), tmp("zones/new.yaml"));
  EXPECT_EQ(folder.fileToSave("./sub/new.yml"), tmp("zones/sub/new.yml"));
  EXPECT_EQ(folder.fileToSave(tmp("zones/other.yaml")), tmp("zones/other.yaml"));
  EXPECT_EQ(folder.fileToLoad("in_link.yaml"), tmp("zones/other.yaml"));
  EXPECT_EQ(folder.fileToSave(std::string(NAME_MAX - 5, 'n') + ".yaml"),
            tmp("zones/" + std::string(NAME_MAX - 5, 'n') + ".yaml"));

  // Refused, for a save and for a load: '..' anywhere (the issue's example first), absolute paths
  // elsewhere, a linked folder or file leading out, control characters, names too long.
  const std::vector<std::pair<std::string, std::string>> refused = {
      {tmp("zones/sub/../../robot/params.yaml"), "'..'"},
      {tmp("zones/sub/../zones.yaml"), "'..'"},
      {"../robot/params.yaml", "'..'"},
      {"sub/..", "'..'"},
      {tmp("robot/params.yaml"), "outside the save directory"},
      {"/etc/hosts.yaml", "outside the save directory"},
      {"escape/params.yaml", "outside the save directory"},
      {"escape/zones.yaml", "outside the save directory"},
      {"out_link.yaml", "outside the save directory"},
      {"a\nb.yaml", "character code 10 at position 1"},
      {std::string("a\0b.yaml", 8), "character code 0 at position 1"},
      {std::string(NAME_MAX - 4, 'n') + ".yaml", "(NAME_MAX)"},
      {std::string(PATH_MAX + 1 - 5, 'p') + ".yaml", "(PATH_MAX)"},
      {"params.txt", ".yaml or .yml"},
      {"missing/z.yaml", "folder cannot be resolved"},
  };
  for (const auto& [name, why] : refused)
    for (const bool load : {false, true})
    {
      const std::string got = folderRefusal(folder, name, load);
      EXPECT_NE(got.find(why), std::string::npos) << (load ? "load " : "save ") << name << ": " << got;
      EXPECT_EQ(got.find('\n'), std::string::npos) << got;
      EXPECT_LT(got.size(), 400u);
    }
  EXPECT_THROW(io::loadZoneFile(folder.fileToLoad("new.yaml")), std::exception);  // the reader refuses it

  // Another save directory: names resolve there; the empty name is still the loaded file.
  const io::ZoneFolder robot(tmp("zones/zones.yaml"), tmp("robot"));
  EXPECT_EQ(robot.fileToLoad("zones.yaml"), tmp("robot/zones.yaml"));
  EXPECT_EQ(robot.fileToSave(""), tmp("zones/zones.yaml"));
  EXPECT_NE(folderRefusal(robot, tmp("zones/other.yaml"), false), "");
  // A save directory that does not exist refuses every name.
  const io::ZoneFolder none(tmp("zones/zones.yaml"), tmp("nowhere"));
  EXPECT_NE(folderRefusal(none, "z.yaml", false).find("save directory"), std::string::npos);
}

TEST_F(ZoneFile, ALoadedFileReachedByALinkMayBeWrittenThroughIt)
{
  // The loaded file is a link to a shared file elsewhere: saving it (by no name, or by the link's name)
  // writes the shared file; another link to that same file counts as the loaded file too.
  ASSERT_EQ(::mkdir(tmp("zones").c_str(), 0755), 0);
  ASSERT_EQ(::mkdir(tmp("shared").c_str(), 0755), 0);
  write(tmp("shared/zones.yaml"), kFile);
  ASSERT_EQ(::symlink(tmp("shared/zones.yaml").c_str(), tmp("zones/zones.yaml").c_str()), 0);
  ASSERT_EQ(::symlink(tmp("shared/zones.yaml").c_str(), tmp("zones/again.yaml").c_str()), 0);
  const io::ZoneFolder folder(tmp("zones/zones.yaml"));
  EXPECT_EQ(folder.fileToSave(""), tmp("shared/zones.yaml"));
  EXPECT_EQ(folder.fileToSave("zones.yaml"), tmp("shared/zones.yaml"));
  EXPECT_EQ(folder.fileToSave("again.yaml"), tmp("shared/zones.yaml"));
  EXPECT_NE(folderRefusal(folder, tmp("shared/other.yaml"), false), "");
}
