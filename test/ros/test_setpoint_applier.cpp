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
