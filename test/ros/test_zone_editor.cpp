// zone_server's editing model on plain objects: what ~set_shape, ~remove_shape, ~save, ~load and a
// marker drag do to the shapes in force and what they answer; no node, no marker server.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include "costmap_layers/ros/zone_editor.hpp"

using costmap_layers::ZoneLayout;
using costmap_layers::ZoneShape;
using costmap_layers::ZoneShapeType;
using costmap_layers_ros::ZoneEditor;

namespace
{
/// A dock square (1, 1) - (3, 2) and a slow circle at (4, 1.5), radius 0.5, in map at 0.1 m.
costmap_layers::ZoneSet layout()
{
  ZoneLayout l;
  l.frame_id = "map";
  l.resolution = 0.1;
  ZoneShape dock;
  dock.name = "dock";
  dock.type = ZoneShapeType::Polygon;
  dock.points = {{1.0, 1.0}, {3.0, 1.0}, {3.0, 2.0}, {1.0, 2.0}};
  dock.value = 100;
  ZoneShape slow;
  slow.name = "slow";
  slow.type = ZoneShapeType::Circle;
  slow.center = {4.0, 1.5};
  slow.radius = 0.5;
  slow.value = 40;
  l.shapes = {dock, slow};
  return costmap_layers::ZoneSet(l);
}

costmap_layers::ZoneShapeDescription circle(const std::string& name, double x, double y, double r)
{
  costmap_layers::ZoneShapeDescription d;
  d.name = name;
  d.type = "circle";
  d.value = 55;
  d.fill = true;
  d.center.x = x;
  d.center.y = y;
  d.radius = r;
  return d;
}

std::string contents(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// A fresh directory, removed with its files at the end of the test.
struct TempDir
{
  std::string path;
  TempDir()
  {
    char name[] = "/tmp/zone_editor_test_XXXXXX";
    path = mkdtemp(name);
  }
  ~TempDir() { std::system(("rm -rf '" + path + "'").c_str()); }
};
}  // namespace

TEST(ZoneEditor, SetAddsAShapeAndAnswers)
{
  ZoneEditor e(layout(), "/unused.yaml");
  const costmap_layers_ros::ZoneEdit r = e.set(circle("extra", -3.0, -3.0, 0.5));
  EXPECT_TRUE(r.success);
  EXPECT_EQ(r.message, "shape 'extra' in force");
  EXPECT_TRUE(r.error.ok());
  ASSERT_EQ(e.zones().layout().shapes.size(), 3u);
  ASSERT_NE(e.zones().find("extra"), nullptr);
  EXPECT_EQ(e.zones().find("extra")->radius, 0.5);
  EXPECT_EQ(e.zones().find("extra")->value, 55);
  // The same name again replaces it in its place.
  EXPECT_TRUE(e.set(circle("extra", -3.0, -3.0, 0.25)).success);
  EXPECT_EQ(e.zones().layout().shapes.size(), 3u);
  EXPECT_EQ(e.zones().find("extra")->radius, 0.25);
}

TEST(ZoneEditor, SetRefusesABadShapeAndKeepsTheShapes)
{
  ZoneEditor e(layout(), "/unused.yaml");
  costmap_layers::ZoneShapeDescription ellipse = circle("x", 0, 0, 1);
  ellipse.type = "ellipse";
  const auto r = e.set(ellipse);
  EXPECT_FALSE(r.success);
  EXPECT_EQ(r.error.field, "shapes/type");
  EXPECT_EQ(r.message, "shape 'x': type must be \"polygon\" or \"circle\" (got \"ellipse\")");
  costmap_layers::ZoneShapeDescription tri;
  tri.name = "tri";
  tri.type = "polygon";
  tri.points.resize(2);
  tri.points[1].x = 1.0;
  const auto r2 = e.set(tri);
  EXPECT_FALSE(r2.success);
  EXPECT_EQ(r2.error.field, "shapes/tri/points");
  EXPECT_EQ(r2.message, r2.error.message);
  EXPECT_EQ(e.zones().layout().shapes.size(), 2u);
  EXPECT_EQ(e.zones().find("tri"), nullptr);
}

TEST(ZoneEditor, RemoveAnswersAndRefusesAnUnknownName)
{
  ZoneEditor e(layout(), "/unused.yaml");
  const auto r = e.remove("slow");
  EXPECT_TRUE(r.success);
  EXPECT_EQ(r.message, "shape 'slow' removed");
  EXPECT_EQ(e.zones().layout().shapes.size(), 1u);
  const auto again = e.remove("slow");
  EXPECT_FALSE(again.success);
  EXPECT_FALSE(again.error.ok());
  EXPECT_EQ(again.message, again.error.message);
  EXPECT_EQ(e.zones().layout().shapes.size(), 1u);
}

TEST(ZoneEditor, ADragMovesAVertex)
{
  ZoneEditor e(layout(), "/unused.yaml");
  const costmap_layers_ros::ZoneDrag d = e.drag("dock/2", "map", 3.5, 2.5);
  EXPECT_TRUE(d.applies);
  EXPECT_TRUE(d.error.ok());
  EXPECT_EQ(d.index, 2u);
  EXPECT_EQ(d.frame, "map");
  EXPECT_FALSE(d.put_back);
  ASSERT_TRUE(d.moved);
  EXPECT_EQ(d.moved->points[2].x, 3.5);
  EXPECT_EQ(d.moved->points[2].y, 2.5);
  EXPECT_EQ(e.zones().find("dock")->points[2].x, 3.5);
}

TEST(ZoneEditor, ADragOfTheRadiusHandleSetsTheRadius)
{
  ZoneEditor e(layout(), "/unused.yaml");
  const auto d = e.drag("slow/radius", "map", 4.0, 2.5);  // 1 m above the centre
  EXPECT_TRUE(d.applies);
  EXPECT_EQ(d.index, 1u);
  ASSERT_TRUE(d.moved);
  EXPECT_EQ(d.moved->radius, 1.0);
  EXPECT_EQ(d.moved->center.x, 4.0);
}

TEST(ZoneEditor, ARefusedDragPutsTheHandleBack)
{
  ZoneEditor e(layout(), "/unused.yaml");
  // Vertex 0 above the top edge: the square would cross itself.
  const auto d = e.drag("dock/0", "map", 2.0, 3.0);
  EXPECT_TRUE(d.applies);
  EXPECT_EQ(d.error.field, "shapes/dock/points");
  ASSERT_TRUE(d.put_back);
  EXPECT_EQ(d.put_back->x, 1.0);
  EXPECT_EQ(d.put_back->y, 1.0);
  EXPECT_FALSE(d.moved);
  EXPECT_EQ(e.zones().find("dock")->points[0].x, 1.0);
  EXPECT_EQ(e.zones().find("dock")->points[0].y, 1.0);
}

TEST(ZoneEditor, ADragInAnotherFrameIsRefused)
{
  ZoneEditor e(layout(), "/unused.yaml");
  const auto d = e.drag("dock/2", "odom", 3.5, 2.5);
  EXPECT_TRUE(d.applies);
  EXPECT_EQ(d.error.field, "feedback/header.frame_id");
  EXPECT_EQ(d.error.message, "marker feedback for dock/2 is in frame 'odom', the zones are in 'map'");
  ASSERT_TRUE(d.put_back);
  EXPECT_EQ(d.put_back->x, 3.0);
  EXPECT_EQ(d.put_back->y, 2.0);
  EXPECT_EQ(e.zones().find("dock")->points[2].x, 3.0);
}

TEST(ZoneEditor, MarkersThatAreNoHandleOfAShapeAreLeftAlone)
{
  ZoneEditor e(layout(), "/unused.yaml");
  EXPECT_FALSE(e.drag("dock", "map", 0, 0).applies);     // the outline: no handle
  EXPECT_FALSE(e.drag("ghost/0", "map", 0, 0).applies);  // no such shape
  EXPECT_FALSE(e.drag("dock/x", "map", 0, 0).applies);
}

TEST(ZoneEditor, HandleNames)
{
  std::string shape;
  std::size_t index = 99;
  EXPECT_TRUE(costmap_layers_ros::parseHandleName("dock/12", &shape, &index));
  EXPECT_EQ(shape, "dock");
  EXPECT_EQ(index, 12u);
  EXPECT_TRUE(costmap_layers_ros::parseHandleName("a/b/center", &shape, &index));
  EXPECT_EQ(shape, "a/b");
  EXPECT_EQ(index, 0u);
  EXPECT_TRUE(costmap_layers_ros::parseHandleName("slow/radius", &shape, &index));
  EXPECT_EQ(index, 1u);
  EXPECT_FALSE(costmap_layers_ros::parseHandleName("/3", &shape, &index));
  EXPECT_FALSE(costmap_layers_ros::parseHandleName("dock/", &shape, &index));
  EXPECT_FALSE(costmap_layers_ros::parseHandleName("dock/1234567", &shape, &index));
  EXPECT_FALSE(costmap_layers_ros::parseHandleName("dock/1a", &shape, &index));
  EXPECT_FALSE(costmap_layers_ros::parseHandleName("dock", &shape, &index));
}

TEST(ZoneEditor, OnlyYamlFileNamesOfAPathsLength)
{
  using costmap_layers::io::zoneFilenameProblem;
  EXPECT_EQ(zoneFilenameProblem(""), "");
  EXPECT_EQ(zoneFilenameProblem("/tmp/a.yaml"), "");
  EXPECT_EQ(zoneFilenameProblem("/tmp/a.yml"), "");
  EXPECT_EQ(zoneFilenameProblem("/etc/passwd"),
            "filename '/etc/passwd' does not end in .yaml or .yml: zone files are YAML, and no other file is read "
            "or written");
  EXPECT_NE(zoneFilenameProblem(".yaml"), "");  // nothing before the extension
  EXPECT_NE(zoneFilenameProblem("dir/.yaml"), "");
  const std::string huge = "/tmp/" + std::string(5000, 'f') + ".yaml";
  EXPECT_EQ(zoneFilenameProblem(huge),
            "filename '/tmp/" + std::string(59, 'f') + "...' has 5010 characters, more than 4096 (PATH_MAX)");
}

TEST(ZoneEditor, SaveThenLoadRestoresTheSavedShapes)
{
  TempDir dir;
  const std::string path = dir.path + "/zones.yaml";
  ZoneEditor e(layout(), path);
  const auto saved = e.save("");  // no name: the configured file
  ASSERT_TRUE(saved.success) << saved.message;
  EXPECT_EQ(saved.message, path);
  ASSERT_TRUE(e.set(circle("extra", -3.0, -3.0, 0.5)).success);
  ASSERT_TRUE(e.remove("dock").success);
  const auto loaded = e.load("");
  ASSERT_TRUE(loaded.success) << loaded.message;
  EXPECT_EQ(loaded.message, "loaded " + path);
  ASSERT_EQ(e.zones().layout().shapes.size(), 2u);
  EXPECT_EQ(e.zones().layout().shapes[0].name, "dock");
  EXPECT_EQ(e.zones().layout().shapes[0].points[2].x, 3.0);
  EXPECT_EQ(e.zones().layout().shapes[1].name, "slow");
  EXPECT_EQ(e.zones().layout().shapes[1].radius, 0.5);
}

TEST(ZoneEditor, RefusedSavesAndLoadsChangeNothing)
{
  TempDir dir;
  ZoneEditor e(layout(), dir.path + "/zones.yaml");
  const std::string target = dir.path + "/keep.txt";
  {
    std::ofstream(target) << "keep me\n";
  }
  const auto not_yaml = e.save(target);
  EXPECT_FALSE(not_yaml.success);
  EXPECT_EQ(not_yaml.error.field, "save/filename");
  EXPECT_EQ(contents(target), "keep me\n");
  const auto no_dir = e.save(dir.path + "/no/such/dir/z.yaml");
  EXPECT_FALSE(no_dir.success);
  EXPECT_EQ(no_dir.error.field, "save/filename");
  // A YAML file in the folder that is not a zone file: the name is fine, the write is refused.
  {
    std::ofstream(dir.path + "/params.yaml") << "robot_radius: 0.3\n";
  }
  const auto not_zones = e.save("params.yaml");
  EXPECT_FALSE(not_zones.success);
  EXPECT_EQ(not_zones.error.field, "save");
  EXPECT_NE(not_zones.message.find("not a zone file"), std::string::npos) << not_zones.message;
  EXPECT_EQ(contents(dir.path + "/params.yaml"), "robot_radius: 0.3\n");
  const auto bad_name = e.load("/etc/passwd");
  EXPECT_FALSE(bad_name.success);
  EXPECT_EQ(bad_name.error.field, "load/filename");
  const auto missing = e.load(dir.path + "/missing.yaml");
  EXPECT_FALSE(missing.success);
  EXPECT_EQ(missing.error.field, "load");
  EXPECT_EQ(missing.message, missing.error.message);
  EXPECT_EQ(e.zones().layout().shapes.size(), 2u);
}

TEST(ZoneEditor, SaveAndLoadStayInTheSaveDirectory)
{
  // The layout: <dir>/zones holds the zone file, <dir>/robot a robot's parameters.
  TempDir dir;
  ASSERT_EQ(::mkdir((dir.path + "/zones").c_str(), 0755), 0);
  ASSERT_EQ(::mkdir((dir.path + "/zones/sub").c_str(), 0755), 0);
  ASSERT_EQ(::mkdir((dir.path + "/robot").c_str(), 0755), 0);
  const std::string params = dir.path + "/robot/params.yaml";
  {
    std::ofstream(params) << "robot_radius: 0.3\n";
  }
  ASSERT_EQ(::symlink((dir.path + "/robot").c_str(), (dir.path + "/zones/robot").c_str()), 0);
  ZoneEditor e(layout(), dir.path + "/zones/zones.yaml");
  ASSERT_TRUE(e.save("").success);
  // The name, and others of its class: '..', an absolute path elsewhere, a linked folder
  // leading out, a control character. Each refused for a save and for a load, nothing written.
  for (const std::string name :
       {dir.path + "/zones/sub/../../robot/params.yaml", std::string("../robot/params.yaml"), params,
        std::string("robot/params.yaml"), std::string("robot/new.yaml"), std::string("new\n.yaml")})
  {
    const auto saved = e.save(name);
    EXPECT_FALSE(saved.success) << name;
    EXPECT_EQ(saved.error.field, "save/filename") << name;
    EXPECT_EQ(saved.message.find('\n'), std::string::npos) << saved.message;
    const auto loaded = e.load(name);
    EXPECT_FALSE(loaded.success) << name;
    EXPECT_EQ(loaded.error.field, "load/filename") << name;
  }
  EXPECT_EQ(contents(params), "robot_radius: 0.3\n");
  EXPECT_NE(::access((dir.path + "/robot/new.yaml").c_str(), F_OK), 0);
  // Inside: a relative name, a subfolder, an absolute name.
  for (const std::string name : {std::string("copy.yaml"), std::string("sub/copy.yaml"), dir.path + "/zones/abs.yaml"})
  {
    const auto saved = e.save(name);
    ASSERT_TRUE(saved.success) << name << ": " << saved.message;
    EXPECT_TRUE(e.load(name).success) << name;
  }
  EXPECT_EQ(e.save("sub/copy.yaml").message, dir.path + "/zones/sub/copy.yaml");
  // Another save directory, named by the parameter: names go there, the empty name to the loaded file.
  ZoneEditor other(layout(), dir.path + "/zones/zones.yaml", dir.path + "/robot");
  EXPECT_EQ(other.save("zones_copy.yaml").message, dir.path + "/robot/zones_copy.yaml");
  EXPECT_EQ(other.save("").message, dir.path + "/zones/zones.yaml");
  EXPECT_FALSE(other.save("params.yaml").success);  // inside, but not a zone file
  EXPECT_FALSE(other.save(dir.path + "/zones/copy.yaml").success);
  EXPECT_EQ(contents(params), "robot_radius: 0.3\n");
}

TEST(ZoneEditor, SavingTheLoadedFileThroughALinkKeepsTheLinkAndTheMode)
{
  TempDir dir;
  ASSERT_EQ(::mkdir((dir.path + "/shared").c_str(), 0755), 0);
  ZoneEditor writer(layout(), dir.path + "/shared/zones.yaml");
  ASSERT_TRUE(writer.save("").success);
  ASSERT_EQ(::chmod((dir.path + "/shared/zones.yaml").c_str(), 0600), 0);
  ASSERT_EQ(::symlink((dir.path + "/shared/zones.yaml").c_str(), (dir.path + "/zones.yaml").c_str()), 0);
  ZoneEditor e(layout(), dir.path + "/zones.yaml");
  ASSERT_TRUE(e.remove("slow").success);
  const auto saved = e.save("");
  ASSERT_TRUE(saved.success) << saved.message;
  EXPECT_EQ(saved.message, dir.path + "/shared/zones.yaml");
  struct stat st
  {
  };
  ASSERT_EQ(::lstat((dir.path + "/zones.yaml").c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode));
  ASSERT_EQ(::stat((dir.path + "/shared/zones.yaml").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600u);
  EXPECT_EQ(costmap_layers::io::loadZoneFile(dir.path + "/shared/zones.yaml").shapes.size(), 1u);
}

TEST(ZoneEditor, FeedbackInAMalformedFrameIsRefusedWithoutEchoingIt)
{
  ZoneEditor e(layout(), "/unused.yaml");
  // "map\nodom" would have put a line break into the log line; a space, a tab, a DEL, a huge frame too.
  for (const std::string frame : {std::string("map\nodom"), std::string("map odom"), std::string("map\t"),
                                  std::string("map\x7f"), std::string(100000, 'm')})
  {
    const auto d = e.drag("dock/2", frame, 3.5, 2.5);
    EXPECT_TRUE(d.applies);
    EXPECT_EQ(d.error.field, "feedback/header.frame_id");
    EXPECT_NE(d.error.message.find("a frame id"), std::string::npos) << d.error.message;
    EXPECT_EQ(d.error.message.find_first_of("\n\t\x7f"), std::string::npos) << d.error.message;
    EXPECT_LT(d.error.message.size(), 400u);
    ASSERT_TRUE(d.put_back);
    EXPECT_EQ(e.zones().find("dock")->points[2].x, 3.0);
  }
  EXPECT_EQ(e.drag("dock/2", "", 3.5, 2.5).error.field, "feedback/header.frame_id");
}
