// ThrottledLog without a master: an injected sink and clock, so nothing here depends on timing.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "costmap_layers/ros/ros_layer_context.hpp"

using costmap_layers::Severity;
using costmap_layers_ros::ThrottledLog;

namespace
{
struct Rig
{
  double now = 100.0;
  std::vector<std::string> lines;
  ThrottledLog log{5.0, [this](Severity, const std::string& m) { lines.push_back(m); }, [this] { return now; }};
};
}  // namespace

TEST(ThrottledLog, OncePerPeriodPerKey)
{
  Rig r;
  for (int k = 0; k < 10; ++k)
    r.log.log(Severity::Error, "mask/info.resolution", "bad " + std::to_string(k));
  r.log.log(Severity::Error, "mask/data", "other field");
  // Each line ends with its key: what scripts and tests match on.
  EXPECT_EQ(r.lines, (std::vector<std::string>{"bad 0 [mask/info.resolution]", "other field [mask/data]"}));
  r.now += 4.9;
  r.log.log(Severity::Error, "mask/info.resolution", "still quiet");
  r.now += 0.1;
  r.log.log(Severity::Error, "mask/info.resolution", "again");
  EXPECT_EQ(r.lines.back(), "again [mask/info.resolution]");
  EXPECT_EQ(r.lines.size(), 3u);
}

TEST(ThrottledLog, AClockThatWentBackEndsThePeriod)
{
  Rig r;
  r.log.log(Severity::Warn, "k", "first");
  r.now -= 1000.0;  // e.g. a restarted simulation's clock
  r.log.log(Severity::Warn, "k", "after the jump");
  EXPECT_EQ(r.lines.size(), 2u);
  r.log.log(Severity::Warn, "k", "throttled again");
  EXPECT_EQ(r.lines.size(), 2u);
}

// The outside attack made a key per area id: 20 000 keys that were never freed. Whatever the keys, the
// table stays bounded and the log quiet.
TEST(ThrottledLog, TheKeyTableIsBoundedWhateverTheKeys)
{
  Rig r;
  for (int k = 0; k < 20000; ++k)
    r.log.log(Severity::Error, "area_" + std::to_string(k), "bad area " + std::to_string(k));
  EXPECT_LE(r.log.keyCount(), ThrottledLog::kMaxKeys + 1);
  // The first kMaxKeys distinct keys were logged, then one line under the overflow key.
  EXPECT_EQ(r.lines.size(), ThrottledLog::kMaxKeys + 1);
  // A period later, old keys are forgotten to make room: the table does not grow.
  r.now += 5.0;
  for (int k = 20000; k < 40000; ++k)
    r.log.log(Severity::Error, "area_" + std::to_string(k), "bad area " + std::to_string(k));
  EXPECT_LE(r.log.keyCount(), ThrottledLog::kMaxKeys + 1);
  EXPECT_LE(r.lines.size(), 2 * (ThrottledLog::kMaxKeys + 1));
}
