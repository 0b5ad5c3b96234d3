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
