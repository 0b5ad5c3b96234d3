// mask_server's load summary: value counts, the histogram, and the warning for a mask drawn for the
// other pixel rule, on the Nav2 tutorial's speed mask (test/data/maps, copied unchanged).
#include "costmap_layers/io/mask_summary.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace costmap_layers;

namespace
{
const std::string kSpeedMask = std::string(COSTMAP_LAYERS_SOURCE_DIR) + "/test/data/maps/tutorials_speed_mask.yaml";

uint64_t count(const std::array<uint64_t, 256>& c, int v)
{
  return c[static_cast<std::size_t>(v + 128)];
}
}  // namespace

TEST(MaskSummary, TutorialSpeedMaskWithNav2Rule)
{
  // The image has five greys: 254 (8181 px), 205 (138514), 153 (500), 77 (180), 0 (81). Nav2's rule with
  // thresholds 1.0 / 0.0: round(100 * (1 - g / 255)) -> 0, 20, 40, 70, 100.
  const OccupancyGridData g = io::loadMapFile(kSpeedMask, io::MapMode::Nav2Scale);
  const auto c = io::countValues(g);
  EXPECT_EQ(count(c, 0), 8181u);
  EXPECT_EQ(count(c, 20), 138514u);
  EXPECT_EQ(count(c, 40), 500u);
  EXPECT_EQ(count(c, 70), 180u);
  EXPECT_EQ(count(c, 100), 81u);
  EXPECT_EQ(io::describeValues(c), "0 x 8181, 20 x 138514, 40 x 500, 70 x 180, 100 x 81");
  EXPECT_EQ(io::pixelRuleWarning(c, io::MapMode::Nav2Scale), "");
}

TEST(MaskSummary, TutorialSpeedMaskWithRos1RuleIsFlagged)
{
  // ROS 1's rule: 1 + 98 * occ truncated, nothing strictly beyond 1.0 / 0.0: white 1, black 99.
  const OccupancyGridData g = io::loadMapFile(kSpeedMask, io::MapMode::Scale);
  const auto c = io::countValues(g);
  EXPECT_EQ(count(c, 0), 0u);
  EXPECT_EQ(count(c, 100), 0u);
  EXPECT_EQ(count(c, 1), 8181u);
  EXPECT_EQ(count(c, 99), 81u);
  const std::string w = io::pixelRuleWarning(c, io::MapMode::Scale);
  EXPECT_NE(w.find("8181 cells of 1 and 81 of 99"), std::string::npos) << w;
  EXPECT_NE(w.find("pixel_rule: nav2"), std::string::npos) << w;
}

TEST(MaskSummary, TrinaryMasksAreNotFlagged)
{
  std::array<uint64_t, 256> c{};
  c[128 + 0] = 10;
  c[128 + 100] = 5;
  EXPECT_EQ(io::pixelRuleWarning(c, io::MapMode::Scale), "");
  c[128 + 0] = 0;
  c[128 + 100] = 0;
  c[128 + 1] = 3;
  EXPECT_EQ(io::pixelRuleWarning(c, io::MapMode::Trinary), "");  // only the scale rule gives 1 for white
  EXPECT_NE(io::pixelRuleWarning(c, io::MapMode::Scale), "");
}

TEST(MaskSummary, HistogramWhenManyValues)
{
  std::array<uint64_t, 256> c{};
  for (int v = 0; v <= 100; ++v)
    c[static_cast<std::size_t>(v + 128)] = 2;
  c[128 - 1] = 7;
  c[128 + 120] = 1;
  const std::string d = io::describeValues(c);
  EXPECT_EQ(d.rfind("103 distinct values, histogram: ", 0), 0u) << d;
  EXPECT_NE(d.find("-1 x 7, 0 x 2, 1-10 x 20 (10 values)"), std::string::npos) << d;
  EXPECT_NE(d.find("91-99 x 18 (9 values), 100 x 2, other (outside -1..100) x 1"), std::string::npos) << d;
  EXPECT_EQ(io::describeValues(std::array<uint64_t, 256>{}), "no cells");
}
