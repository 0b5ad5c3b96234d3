// Zone files: written by hand, read, saved and read back; the saved file rasterises to the same mask.
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

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
  // zoneLayoutToYaml is read back in the tests below; here, the text itself: 17 significant digits,
  // names quoted.
  ZoneLayout l;
  l.shapes = {polygon("dock", {{0.1, 0.2}, {1.0 / 3.0, 0.2}, {0.3, 0.7}}, 100, false)};
  const std::string y = io::zoneLayoutToYaml(l);
  EXPECT_NE(y.find("0.33333333333333331"), std::string::npos) << y;
  EXPECT_NE(y.find("name: \"dock\""), std::string::npos) << y;
  EXPECT_NE(y.find("fill: false"), std::string::npos) << y;
}

TEST_F(ZoneFile, WrittenTextReadsBackBitForBit)
{
  ZoneLayout l;
  l.frame_id = "odd \"frame\" \\ name";
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
