// SetpointApplier's scheduling without a master: which node's setpoints go next. The nodes take turns
// round-robin, so a node whose server never answers (each turn ends after the timeout) cannot keep
// the others from being applied however often new sets arrive.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "costmap_layers/ros/setpoint_applier.hpp"

using costmap_layers::ParamValue;
using costmap_layers::Setpoint;
using costmap_layers_ros::SetpointApplier;

namespace
{
Setpoint sp(const std::string& node, const std::string& parameter, double v)
{
  Setpoint s;
  s.node = node;
  s.parameter = parameter;
  s.value = ParamValue::makeDouble(v);
  return s;
}

const std::vector<std::string> kOrder{"/stuck", "/planner", "/costmap"};
}  // namespace

TEST(SetpointApplier, NodesInTheOrderTheSetFirstNamesThem)
{
  const std::vector<Setpoint> set{sp("/b", "x", 1), sp("/a", "x", 1), sp("/b", "y", 2), sp("/c", "x", 3)};
  EXPECT_EQ(SetpointApplier::nodesOf(set), (std::vector<std::string>{"/b", "/a", "/c"}));
  EXPECT_TRUE(SetpointApplier::nodesOf({}).empty());
}

TEST(SetpointApplier, NextNodeStartsAfterTheLastOneAndWraps)
{
  // Nothing applied yet (or the last node is not in this set): from the start.
  EXPECT_EQ(SetpointApplier::nextNode(kOrder, kOrder, ""), "/stuck");
  EXPECT_EQ(SetpointApplier::nextNode(kOrder, kOrder, "/gone"), "/stuck");
  EXPECT_EQ(SetpointApplier::nextNode(kOrder, kOrder, "/stuck"), "/planner");
  EXPECT_EQ(SetpointApplier::nextNode(kOrder, kOrder, "/costmap"), "/stuck");
  // Only due nodes: after /planner, /costmap is not due, so round to /stuck.
  EXPECT_EQ(SetpointApplier::nextNode(kOrder, {"/stuck"}, "/planner"), "/stuck");
  EXPECT_EQ(SetpointApplier::nextNode(kOrder, {}, "/planner"), "");
  EXPECT_EQ(SetpointApplier::nextNode({}, {"/stuck"}, ""), "");
}

TEST(SetpointApplier, AStuckFirstNodeDoesNotStarveTheOthers)
{
  // Every turn of /stuck ends with a timeout, and a new complete set (every node due again) arrives
  // after each turn: the applier must still reach every other node. Simulated turn by turn.
  std::vector<std::string> due = kOrder;
  std::string last;
  std::vector<std::string> applied;
  for (int turn = 0; turn < 6; ++turn)
  {
    const std::string node = SetpointApplier::nextNode(kOrder, due, last);
    ASSERT_FALSE(node.empty());
    applied.push_back(node);
    last = node;
    due = kOrder;  // a new set came while that node was applied
  }
  EXPECT_EQ(applied, (std::vector<std::string>{"/stuck", "/planner", "/costmap", "/stuck", "/planner", "/costmap"}));
}

TEST(SetpointApplier, AHostileServersNamesAndValuesAreQuotedBriefly)
{
  // A description of 100 000 parameters, none the one wanted: 20 are named, the rest counted.
  dynamic_reconfigure::ConfigDescription d;
  d.groups.resize(1);
  for (int k = 0; k < 100000; ++k)
  {
    dynamic_reconfigure::ParamDescription p;
    p.name = "p" + std::to_string(k);
    p.type = "double";
    d.groups[0].parameters.push_back(p);
  }
  const std::string missing = SetpointApplier::checkAgainst(sp("/n", "max_vel_x", 1.0), d);
  EXPECT_LT(missing.size(), 400u) << missing.substr(0, 400);
  EXPECT_NE(missing.find("p18, p19 and 99980 more"), std::string::npos) << missing.substr(0, 400);
  // Its max_vel_x declared with a type name of a million characters.
  dynamic_reconfigure::ParamDescription odd;
  odd.name = "max_vel_x";
  odd.type = std::string(1000000, 't');
  d.groups[0].parameters.push_back(odd);
  const std::string type = SetpointApplier::checkAgainst(sp("/n", "max_vel_x", 1.0), d);
  EXPECT_LT(type.size(), 300u) << type.substr(0, 300);
  EXPECT_NE(type.find("(1000000 characters)"), std::string::npos) << type.substr(0, 300);
  // An answer holding a string of a million characters where the number was sent (quoted: 1000002).
  dynamic_reconfigure::Config answer;
  dynamic_reconfigure::StrParameter big;
  big.name = "max_vel_x";
  big.value = std::string(1000000, 'v');
  answer.strs.push_back(big);
  const std::string refused = SetpointApplier::checkAnswer(sp("/n", "max_vel_x", 1.0), answer);
  EXPECT_LT(refused.size(), 300u) << refused.substr(0, 300);
  EXPECT_NE(refused.find("(1000002 characters)"), std::string::npos) << refused.substr(0, 300);
}
