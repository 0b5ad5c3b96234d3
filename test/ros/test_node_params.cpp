// A small node's private parameters read from XmlRpc trees built in memory (what the parameter server
// would hold under the node's namespace): flat and nested files, typed reads and their errors.
#include <gtest/gtest.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "costmap_layers/ros/node_params.hpp"

using costmap_layers_ros::NodeParams;

namespace
{
/// The message of the std::invalid_argument fn throws ("" when it throws nothing, "?" for another type).
template <class Fn>
std::string errorOf(Fn fn)
{
  try
  {
    fn();
  }
  catch (const std::invalid_argument& e)
  {
    return e.what();
  }
  catch (...)
  {
    return "?";
  }
  return "";
}

XmlRpc::XmlRpcValue flat()
{
  XmlRpc::XmlRpcValue v;
  v["yaml_filename"] = std::string("mask.yaml");
  v["frequency"] = 2;
  v["rate"] = 0.5;
  v["latch"] = true;
  v["word"] = std::string("yes");
  v["nan"] = std::numeric_limits<double>::quiet_NaN();
  v["list"][0] = 1;
  v["list"][1] = 2;
  v["dict"]["x"] = 1;
  return v;
}
}  // namespace

TEST(NodeParams, AFlatTreeIsReadAtTheTopLevel)
{
  const NodeParams p(flat(), "/mask_server");
  EXPECT_EQ(p.where(), "~");
  EXPECT_FALSE(p.nested());
  EXPECT_EQ(p.getString("yaml_filename", "none"), "mask.yaml");
  EXPECT_EQ(p.getInt("frequency", 7), 2);
  EXPECT_EQ(p.getDouble("rate", 7.0), 0.5);
  EXPECT_EQ(p.getDouble("frequency", 7.0), 2.0);  // an int is a number too
  EXPECT_TRUE(p.getBool("latch", false));
  // Absent: the default.
  EXPECT_EQ(p.getString("topic", "/map"), "/map");
  EXPECT_EQ(p.getInt("missing", 7), 7);
  EXPECT_EQ(p.getDouble("missing", 1.5), 1.5);
  EXPECT_FALSE(p.getBool("missing", false));
  EXPECT_TRUE(p.has("rate"));
  EXPECT_FALSE(p.has("topic"));
  EXPECT_TRUE(p.hasAny({"topic", "latch"}));
  EXPECT_FALSE(p.hasAny({"topic", "missing"}));
}

TEST(NodeParams, AWrongTypeIsNamedWithItsValue)
{
  const NodeParams p(flat(), "/mask_server");
  EXPECT_EQ(errorOf([&] { p.getInt("rate", 0); }), "parameter ~rate must be an integer (got 0.5)");
  EXPECT_EQ(errorOf([&] { p.getString("frequency", ""); }), "parameter ~frequency must be a string (got 2)");
  EXPECT_EQ(errorOf([&] { p.getBool("word", false); }), "parameter ~word must be true or false (got \"yes\")");
  EXPECT_EQ(errorOf([&] { p.getDouble("word", 0.0); }), "parameter ~word must be a number (got \"yes\")");
  EXPECT_EQ(errorOf([&] { p.getDouble("nan", 0.0); }), "parameter ~nan must be a finite number (got nan)");
  EXPECT_EQ(errorOf([&] { p.getInt("list", 0); }), "parameter ~list must be an integer (got a list of 2)");
  EXPECT_EQ(errorOf([&] { p.getString("dict", ""); }), "parameter ~dict must be a string (got a dictionary)");
  EXPECT_EQ(errorOf([&] { p.getBool("frequency", false); }), "parameter ~frequency must be true or false (got 2)");
}

TEST(NodeParams, ASectionNamedLikeTheNodeIsReadFromThere)
{
  XmlRpc::XmlRpcValue v;
  v["costmap_filter_info_server"]["type"] = 1;
  v["costmap_filter_info_server"]["mask_topic"] = std::string("/mask");
  v["other_node"]["type"] = 9;  // another node's section of the same file: left alone
  const NodeParams p(v, "/costmap_filter_info_server");
  EXPECT_TRUE(p.nested());
  EXPECT_EQ(p.where(), "~costmap_filter_info_server/");
  EXPECT_EQ(p.getInt("type", 0), 1);
  EXPECT_EQ(p.getString("mask_topic", ""), "/mask");
  EXPECT_FALSE(p.has("other_node"));
  EXPECT_EQ(errorOf([&] { p.getString("type", ""); }),
            "parameter ~costmap_filter_info_server/type must be a string (got 1)");
}

TEST(NodeParams, ASectionTwoLevelsDownIsReadToo)
{
  XmlRpc::XmlRpcValue v;
  v["zone_server"]["zone_server"]["markers"] = false;
  const NodeParams p(v, "/robot/zone_server");
  EXPECT_EQ(p.where(), "~zone_server/zone_server/");
  EXPECT_TRUE(p.has("markers"));
  EXPECT_FALSE(p.getBool("markers", true));
}

TEST(NodeParams, AValueBothBesideAndInsideTheSectionIsRefused)
{
  XmlRpc::XmlRpcValue v;
  v["type"] = 0;
  v["info"]["type"] = 1;
  EXPECT_EQ(errorOf([&] { NodeParams p(v, "/info"); }),
            "parameter ~type (0) is set both in ~ and in ~info/ (1): load the parameter file once, either at the "
            "top level (its key 'info:' is then this node's namespace) or with ns=\"info\"");
}

TEST(NodeParams, NothingOrNotADictionaryMeansDefaults)
{
  const NodeParams none(XmlRpc::XmlRpcValue(), "/mask_server");
  EXPECT_FALSE(none.has("yaml_filename"));
  EXPECT_EQ(none.getInt("frequency", 3), 3);
  EXPECT_TRUE(none.unknownKeys({}).empty());
  const NodeParams scalar(XmlRpc::XmlRpcValue(5), "/mask_server");
  EXPECT_FALSE(scalar.has("frequency"));
  EXPECT_EQ(scalar.where(), "~");
}

TEST(NodeParams, UnknownKeysAreTheScalarsNotKnown)
{
  XmlRpc::XmlRpcValue v;
  v["topic"] = std::string("/map");
  v["tpoic"] = std::string("/typo");
  v["frame"] = std::string("map");
  v["use_sim_time"] = true;  // reported by warnUseSimTime(), not here
  v["subsection"]["a"] = 1;  // another node's part of the file
  const NodeParams p(v, "/mask_server");
  const std::vector<std::string> unknown = p.unknownKeys({"topic"});
  EXPECT_EQ(unknown, (std::vector<std::string>{"frame", "tpoic"}));
}

TEST(NodeParams, ShowWritesAValueAsTheUserWroteIt)
{
  EXPECT_EQ(NodeParams::show(XmlRpc::XmlRpcValue(5)), "5");
  EXPECT_EQ(NodeParams::show(XmlRpc::XmlRpcValue(2.5)), "2.5");
  EXPECT_EQ(NodeParams::show(XmlRpc::XmlRpcValue(false)), "false");
  EXPECT_EQ(NodeParams::show(XmlRpc::XmlRpcValue(std::string("text"))), "\"text\"");
  XmlRpc::XmlRpcValue list;
  list.setSize(3);
  EXPECT_EQ(NodeParams::show(list), "a list of 3");
  XmlRpc::XmlRpcValue dict;
  dict["k"] = 1;
  EXPECT_EQ(NodeParams::show(dict), "a dictionary");
  EXPECT_EQ(NodeParams::show(XmlRpc::XmlRpcValue()), "an unsupported value");
}

// The named kinds of value every program reads the same way (issue 34): a topic, a frame id, a file, a
// number in a range. Each error names the parameter and shows the value as it was written.
TEST(NodeParams, TopicsFollowRosNamingRules)
{
  XmlRpc::XmlRpcValue v;
  v["good"] = std::string("/map_filter");
  v["relative"] = std::string("zone/mask");
  v["private"] = std::string("~private_mask");
  v["space"] = std::string("9 lives");
  v["accent"] = std::string("kart\xc3\xa9");
  v["empty"] = std::string("");
  v["number"] = 7;
  const NodeParams p(v, "/zone_server");
  EXPECT_EQ(p.getTopic("good", "/x"), "/map_filter");
  EXPECT_EQ(p.getTopic("relative", "/x"), "zone/mask");
  EXPECT_EQ(p.getTopic("missing", "/default"), "/default");
  EXPECT_EQ(p.getTopic("private", "/x"), "~private_mask");
  const std::string priv = errorOf([&] { p.getTopic("private", "/x", false); });
  EXPECT_EQ(priv.find("parameter ~private: the topic"), 0u) << priv;
  EXPECT_NE(priv.find("~private_mask"), std::string::npos) << priv;
  const std::string space = errorOf([&] { p.getTopic("space", "/x"); });
  EXPECT_EQ(space.find("parameter ~space: the topic"), 0u) << space;
  EXPECT_NE(space.find("9 lives"), std::string::npos) << space;
  EXPECT_EQ(errorOf([&] { p.getTopic("accent", "/x"); }).find("parameter ~accent: the topic"), 0u);
  EXPECT_EQ(errorOf([&] { p.getTopic("empty", "/x"); }), "parameter ~empty: the topic is empty");
  EXPECT_EQ(errorOf([&] { p.getTopic("number", "/x"); }), "parameter ~number must be a string (got 7)");
  // The default is checked by the same rule: a program's own default may not slip by.
  EXPECT_EQ(errorOf([&] { p.getTopic("missing", "a b"); }).find("parameter ~missing: the topic"), 0u);
}

TEST(NodeParams, FrameIdsFilesAndRanges)
{
  XmlRpc::XmlRpcValue v;
  v["frame"] = std::string("base_link");
  v["newline"] = std::string("map\nodom");
  v["space"] = std::string("ma p");
  v["long"] = std::string(257, 'f');
  v["file"] = std::string("zones.yaml");
  v["no_file"] = std::string("");
  v["rate"] = 5;
  v["low"] = -1.0;
  v["word"] = std::string("fast");
  const NodeParams p(v, "/mask_server");
  EXPECT_EQ(p.getFrameId("frame", "map"), "base_link");
  EXPECT_EQ(p.getFrameId("missing", "map"), "map");
  for (const char* bad : {"newline", "space", "long"})
  {
    const std::string e = errorOf([&] { p.getFrameId(bad, "map"); });
    EXPECT_EQ(e.find(std::string("parameter ~") + bad + ": the frame id"), 0u) << e;
  }
  // A control character is never printed as itself: one error is one line.
  EXPECT_EQ(errorOf([&] { p.getFrameId("newline", "map"); }).find('\n'), std::string::npos);
  EXPECT_EQ(p.getFile("file"), "zones.yaml");
  EXPECT_EQ(errorOf([&] { p.getFile("no_file"); }), "parameter ~no_file: is not set (a file name is needed)");
  EXPECT_EQ(errorOf([&] { p.getFile("missing"); }), "parameter ~missing: is not set (a file name is needed)");
  EXPECT_EQ(p.getDoubleIn("rate", 1.0, 0.0, 5.0), 5.0);  // the edges are inside
  EXPECT_EQ(p.getDoubleIn("missing", 2.5, 0.0, 5.0), 2.5);
  EXPECT_EQ(errorOf([&] { p.getDoubleIn("rate", 1.0, 0.0, 4.5); }), "parameter ~rate must be in [0, 4.5] (got 5)");
  EXPECT_EQ(errorOf([&] { p.getDoubleIn("low", 1.0, 0.0, 10.0); }), "parameter ~low must be in [0, 10] (got -1)");
  EXPECT_EQ(errorOf([&] { p.getDoubleIn("word", 1.0, 0.0, 10.0); }), "parameter ~word must be a number (got \"fast\")");
}
