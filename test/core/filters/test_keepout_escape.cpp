// KeepoutFilter's escape mode (override_lethal_cost): the ramp rule, the depth of every zone cell
// against a brute-force nearest way out, when the robot counts as inside a zone (footprint and
// clearance, worked by hand), and the whole cycle: in the zone -> ramp, out -> lethal again.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/filters/keepout_filter.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;
using costmap_layers_test::GridKind;

namespace
{
/// 100 x 100 cells at 0.05 m (5 m x 5 m), origin (0, 0): lethal keepout (100) for x >= 2.5 m.
OccupancyGridData halfLethalMask()
{
  OccupancyGridData m;
  m.frame_id = "map";
  m.width = 100;
  m.height = 100;
  m.resolution = 0.05;
  m.data.assign(100 * 100, 0);
  for (int j = 0; j < 100; ++j)
    for (int i = 50; i < 100; ++i)
      m.data[static_cast<std::size_t>(j) * 100 + i] = 100;
  return m;
}

/// A 0.6 m x 0.6 m square robot: inscribed radius 0.3 m, circumscribed 0.3 * sqrt(2) m.
Footprint square()
{
  return {{0.3, 0.3}, {-0.3, 0.3}, {-0.3, -0.3}, {0.3, -0.3}};
}

ParamValue escapeOn(int top = 252)
{
  ParamValue p = ParamValue::makeMap();
  p.set("override_lethal_cost", ParamValue::makeBool(true));
  p.set("lethal_override_cost", ParamValue::makeInt(top));
  return p;
}

struct Rig
{
  LayeredCostmap lc{"map", false, false};
  std::shared_ptr<FakeContext> ctx;
  std::shared_ptr<KeepoutFilter> filter = std::make_shared<KeepoutFilter>();

  explicit Rig(ParamValue p) : ctx(std::make_shared<FakeContext>(std::move(p)))
  {
    lc.resizeMap(100, 100, 0.05, 0.0, 0.0);
    filter->initialize(&lc, "keepout", ctx);
    ctx->bind(*filter);
    lc.addFilter(filter);
    lc.setFootprint(square());
    ctx->publishGrid(GridKind::Mask, halfLethalMask());
  }
  uint8_t cost(double x, double y) const
  {
    return lc.getCostmap().getCost(static_cast<unsigned>(x / 0.05), static_cast<unsigned>(y / 0.05));
  }
};
}  // namespace

TEST(KeepoutEscape, ConfigDefaultsAndBadValues)
{
  const ParamValue empty = ParamValue::makeMap();
  const KeepoutFilterConfig d = parseKeepoutFilterConfig(ParamReader(empty, "keepout"));
  EXPECT_FALSE(d.override_lethal_cost);
  EXPECT_EQ(d.lethal_override_cost, 252);  // Nav2: MAX_NON_OBSTACLE
  for (const ParamValue& bad : {ParamValue::makeInt(253), ParamValue::makeInt(0), ParamValue::makeInt(-5),
                                ParamValue::makeDouble(std::nan("")), ParamValue::makeString("high")})
  {
    ParamValue p = ParamValue::makeMap();
    p.set("lethal_override_cost", bad);
    try
    {
      parseKeepoutFilterConfig(ParamReader(p, "keepout"));
      ADD_FAILURE() << "accepted " << bad.toString();
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find("'lethal_override_cost'"), std::string::npos) << e.what();
    }
  }
}

TEST(KeepoutEscape, RampCostByHand)
{
  // ceil(252 * depth / 1.0): 0.1 -> 25.2 -> 26; 0.5 -> 126; 0.999 -> 251.7 -> 252; from 1.0 on 252.
  EXPECT_EQ(escapeRampCost(0.1, 1.0, 252), 26);
  EXPECT_EQ(escapeRampCost(0.5, 1.0, 252), 126);
  EXPECT_EQ(escapeRampCost(0.999, 1.0, 252), 252);
  EXPECT_EQ(escapeRampCost(1.0, 1.0, 252), 252);
  EXPECT_EQ(escapeRampCost(7.0, 1.0, 252), 252);
  EXPECT_EQ(escapeRampCost(0.001, 1.0, 252), 1);  // 0.252 -> at least 1
  EXPECT_EQ(escapeRampCost(0.5, 1.0, 200), 100);
  EXPECT_EQ(escapeRampCost(0.5, 0.0, 200), 200);  // no ramp length: the top
  EXPECT_EQ(escapeRampCost(0.5, std::nan(""), 200), 200);
}

TEST(KeepoutEscape, RampDepthIsTheBruteForceNearestWayOut)
{
  // A zone on the grid's edge (which is no way out) with a costly cell inside it (which is one).
  const uint32_t w = 13, h = 9;
  std::vector<uint8_t> costs(w * h, 0);
  for (uint32_t j = 0; j < h; ++j)
    for (uint32_t i = 3; i < w; ++i)
      costs[j * w + i] = LETHAL_OBSTACLE;
  costs[4 * w + 8] = 127;  // a costly, not lethal, cell: a way out
  std::vector<uint8_t> ramp = costs;
  std::vector<uint8_t> d2;
  DistanceTransformScratch scratch;
  const double res = 0.1, length = 0.45;
  writeEscapeRamp(ramp, w, h, res, length, 200, d2, scratch);
  std::vector<uint8_t> all(w * h, LETHAL_OBSTACLE);  // no way out anywhere: the top everywhere
  writeEscapeRamp(all, w, h, res, length, 200, d2, scratch);
  EXPECT_EQ(all, std::vector<uint8_t>(w * h, 200));
  for (uint32_t j = 0; j < h; ++j)
    for (uint32_t i = 0; i < w; ++i)
    {
      const uint8_t c = costs[j * w + i];
      if (c != LETHAL_OBSTACLE)
      {
        EXPECT_EQ(ramp[j * w + i], c) << i << "," << j;  // untouched
        continue;
      }
      // Brute force over every cell of the grid.
      double best = std::numeric_limits<double>::infinity();
      for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
        {
          if (costs[y * w + x] == LETHAL_OBSTACLE) continue;
          best = std::min(best, std::hypot(static_cast<double>(x) - i, static_cast<double>(y) - j));
        }
      const double depth = best * res;
      const uint8_t expected = depth >= length ? 200 : static_cast<uint8_t>(std::ceil(200 * depth / length));
      EXPECT_EQ(ramp[j * w + i], expected) << i << "," << j << " depth " << depth;
    }
}

TEST(KeepoutEscape, InsideByFootprintOrClearanceWorkedByHand)
{
  const OccupancyGridData mask = halfLethalMask();
  // Clearance: inscribed 0.3 + sqrt(2) * 0.05 = 0.3707 m. The nearest lethal cell centre is x = 2.525.
  const double clearance = escapeClearance(0.3, 0.05);
  EXPECT_NEAR(clearance, 0.370711, 1e-6);
  const Transform2D id;
  // Footprint to x = 1.3, 1.225 m from the zone: out.
  EXPECT_FALSE(robotInLethalKeepout(mask, id, 1.0, 2.5, 0.0, square(), clearance));
  // Footprint to x = 2.6: the cells centred at 2.525 and 2.575 lie under it: in.
  EXPECT_TRUE(robotInLethalKeepout(mask, id, 2.3, 2.5, 0.0, square(), clearance));
  // Footprint to 2.4 (clear), centre 0.425 m from 2.525 (> 0.3707): out.
  EXPECT_FALSE(robotInLethalKeepout(mask, id, 2.1, 2.5, 0.0, square(), clearance));
  // Footprint to 2.46 (clear), but the centre is 0.365 m from 2.525 (<= 0.3707): in, by the clearance.
  EXPECT_TRUE(robotInLethalKeepout(mask, id, 2.16, 2.5, 0.0, square(), clearance));
  // Turned by 45 degrees the square reaches 2.0 + 0.4243 = 2.424 from x = 2.0: clear; at 2.12 it reaches
  // 2.544, over the cell centred at 2.525 (the clearance alone, 0.405 m away, would not catch it).
  EXPECT_FALSE(robotInLethalKeepout(mask, id, 2.0, 2.5, M_PI / 4, square(), 0.0));
  EXPECT_TRUE(robotInLethalKeepout(mask, id, 2.12, 2.5, M_PI / 4, square(), 0.0));
  // Deep inside, and off the mask entirely.
  EXPECT_TRUE(robotInLethalKeepout(mask, id, 4.0, 4.0, 0.0, square(), clearance));
  EXPECT_FALSE(robotInLethalKeepout(mask, id, -5.0, 2.5, 0.0, square(), clearance));
  // A point robot (no footprint) at the centre of a lethal cell.
  EXPECT_TRUE(robotInLethalKeepout(mask, id, 2.51, 2.5, 0.0, {}, 0.0));
  EXPECT_FALSE(robotInLethalKeepout(mask, id, 2.49, 2.5, 0.0, {}, 0.0));
  // In a shifted mask frame: the mask frame's origin lies 1 m further along x (global = mask + 1).
  Transform2D to_mask;
  to_mask.x = -1.0;
  EXPECT_FALSE(robotInLethalKeepout(mask, to_mask, 3.1, 2.5, 0.0, square(), clearance));  // 2.1 in the mask
  EXPECT_TRUE(robotInLethalKeepout(mask, to_mask, 3.3, 2.5, 0.0, square(), clearance));   // 2.3
  // A non-finite pose is never inside.
  EXPECT_FALSE(robotInLethalKeepout(mask, id, std::nan(""), 2.5, 0.0, square(), clearance));
}

TEST(KeepoutEscape, RobotHalfInsideGetsARampAndTheZoneIsLethalAgainBehindIt)
{
  Rig rig(escapeOn());
  rig.lc.updateMap(1.0, 2.5, 0.0);  // well clear: lethal
  EXPECT_FALSE(rig.filter->escaping());
  EXPECT_EQ(rig.cost(2.525, 2.5), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.cost(4.0, 1.0), LETHAL_OBSTACLE);

  rig.lc.updateMap(2.5, 2.5, 0.0);  // centre on the edge, half of the footprint in the zone
  EXPECT_TRUE(rig.filter->escaping());
  EXPECT_EQ(rig.ctx->countKey("escape"), 1);
  // Ramp length: the circumscribed radius 0.3 sqrt(2) = 0.42426 m. Depths 0.05 k for the k-th column
  // into the zone: ceil(252 * 0.05 k / 0.42426) = 30, 60, 90, 119, 149, 179, 208, 238, then 252.
  const std::vector<int> expected{30, 60, 90, 119, 149, 179, 208, 238, 252, 252};
  for (int k = 1; k <= 10; ++k)
    for (double y : {0.025, 2.5, 4.975})
      EXPECT_EQ(rig.cost(2.5 + 0.05 * (k - 1) + 0.025, y), expected[static_cast<std::size_t>(k - 1)])
          << "column " << k << " y " << y;
  EXPECT_EQ(rig.cost(4.975, 2.5), 252);  // on the mask's edge, which is no way out: 2.5 m deep
  EXPECT_EQ(rig.cost(1.0, 2.5), FREE_SPACE);

  rig.lc.updateMap(2.16, 2.5, 0.0);  // footprint clear, but within the clearance: still escaping
  EXPECT_TRUE(rig.filter->escaping());
  rig.lc.updateMap(2.1, 2.5, 0.0);  // out: lethal again behind it
  EXPECT_FALSE(rig.filter->escaping());
  for (double x : {2.525, 2.775, 4.975})
    EXPECT_EQ(rig.cost(x, 2.5), LETHAL_OBSTACLE) << x;
  EXPECT_EQ(rig.ctx->countKey("escape"), 2);
}

TEST(KeepoutEscape, OffByDefaultAndTopFromTheParameter)
{
  Rig off{ParamValue::makeMap()};
  off.lc.updateMap(2.5, 2.5, 0.0);
  EXPECT_FALSE(off.filter->escaping());
  EXPECT_EQ(off.cost(2.525, 2.5), LETHAL_OBSTACLE);

  Rig low(escapeOn(100));
  low.lc.updateMap(4.0, 4.0, 0.0);
  EXPECT_TRUE(low.filter->escaping());
  // ceil(100 * 0.05 / 0.42426) = 12; deep cells at the top, 100.
  EXPECT_EQ(low.cost(2.525, 4.0), 12);
  EXPECT_EQ(low.cost(4.0, 4.0), 100);
}
