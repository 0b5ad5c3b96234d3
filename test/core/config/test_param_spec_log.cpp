// ParamSpecLog: what the parse functions read, recorded for the generated reference, with each reader's
// owner and the role of a name (topic, frame id); declare() reaches the log only, never the
// dynamic_reconfigure recording (which cannot hold a list).
#include <gtest/gtest.h>

#include "costmap_layers/core/config/param_reader.hpp"

using costmap_layers::ParamReader;
using costmap_layers::ParamSpec;
using costmap_layers::ParamSpecLog;
using costmap_layers::ParamValue;

TEST(ParamSpecLog, RecordsEveryReadWithItsOwnerAndRole)
{
  ParamValue ns = ParamValue::makeMap();
  ns.set("rate", ParamValue::makeDouble(2.5));
  ParamSpecLog log;
  const ParamReader r(ns, "layer");
  EXPECT_EQ(r.getDouble("rate", 1.0, 0.0, 10.0), 2.5);
  r.getTopic("topic", "/map");
  r.getFrameId("frame", "map");
  r.getChoice("mode", "a", {"a", "b"});
  const ParamValue empty = ParamValue::makeMap();  // a reader keeps a reference: the map must outlive it
  const ParamReader sub(empty, "layer/scan");
  sub.getBool("marking", true);
  r.declare("sources", "names", "none");
  ASSERT_EQ(log.entries().size(), 6u);
  EXPECT_EQ(log.entries()[0].owner, "layer");
  EXPECT_EQ(log.entries()[0].spec.name, "rate");
  EXPECT_EQ(log.entries()[0].spec.default_value.asDouble(), 1.0);  // the default, not the value set
  EXPECT_EQ(log.entries()[0].spec.min, 0.0);
  EXPECT_EQ(log.entries()[0].spec.max, 10.0);
  EXPECT_EQ(log.entries()[1].spec.role, "topic");
  EXPECT_EQ(log.entries()[2].spec.role, "frame id");
  EXPECT_EQ(log.entries()[3].spec.choices, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(log.entries()[4].owner, "layer/scan");
  EXPECT_EQ(log.entries()[5].spec.type, ParamValue::Type::Null);
  EXPECT_EQ(log.entries()[5].spec.role, "names");
  EXPECT_EQ(log.entries()[5].spec.default_value.asString(), "none");
}

TEST(ParamSpecLog, NestsAndStopsWithItsScope)
{
  const ParamValue none = ParamValue::makeMap();
  const ParamReader r(none, "x");
  r.getInt("before", 1);  // no log: nothing happens
  EXPECT_EQ(ParamSpecLog::current(), nullptr);
  ParamSpecLog outer;
  r.getInt("a", 1);
  {
    ParamSpecLog inner;
    r.getInt("b", 2);
    EXPECT_EQ(ParamSpecLog::current(), &inner);
    ASSERT_EQ(inner.entries().size(), 1u);
    EXPECT_EQ(inner.entries()[0].spec.name, "b");
  }
  EXPECT_EQ(ParamSpecLog::current(), &outer);
  r.getInt("c", 3);
  ASSERT_EQ(outer.entries().size(), 2u);
  EXPECT_EQ(outer.entries()[0].spec.name, "a");
  EXPECT_EQ(outer.entries()[1].spec.name, "c");
}

TEST(ParamSpecLog, DeclareNeverReachesTheReconfigureRecording)
{
  const ParamValue none = ParamValue::makeMap();
  std::vector<ParamSpec> recorded;
  ParamReader r(none, "x");
  r.recordInto(&recorded);
  r.declare("footprint", "points", "none");
  r.getTopic("topic", "/t");
  ASSERT_EQ(recorded.size(), 1u);
  EXPECT_EQ(recorded[0].name, "topic");
  EXPECT_EQ(recorded[0].role, "topic");
}
