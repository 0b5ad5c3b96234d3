// Unit tests of GradientLayer (Nav2's tutorial layer): parameters, bounds protocol and the ramp.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "costmap_layers/core/layers/gradient_layer.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;

namespace
{
std::shared_ptr<GradientLayer> makeGradient(LayeredCostmap& lc, ParamValue params = ParamValue::makeMap())
{
  auto layer = std::make_shared<GradientLayer>();
  layer->initialize(&lc, "gradient", std::make_shared<FakeContext>(params));
  return layer;
}

ParamValue withParam(const std::string& key, ParamValue v)
{
  ParamValue p = ParamValue::makeMap();
  p.set(key, std::move(v));
  return p;
}

/// One period of the tutorial's ramp, (254 - k * factor) % 255 stored in an unsigned char for
/// k = 0 .. size + 1, worked out by hand for the sizes and factors the tests use.
const std::vector<int> kRampSize20Factor10 = {254, 244, 234, 224, 214, 204, 194, 184, 174, 164, 154,
                                              144, 134, 124, 114, 104, 94,  84,  74,  64,  54,  44};
/// From k = 13, 254 - 20 k is negative: -6 % 255 = -6, stored as 250; then 230, 210, 190.
const std::vector<int> kRampSize15Factor20 = {254, 234, 214, 194, 174, 154, 134, 114, 94,
                                              74,  54,  34,  14,  250, 230, 210, 190};
const std::vector<int> kRampSize0Factor10 = {254, 244};

/// Checks that every row of [x0, xn) x [y0, yn) holds `ramp` (one period) restarting at x0, and that
/// every other cell still holds `untouched`.
void expectRamp(const Costmap2D& g, int x0, int y0, int xn, int yn, const std::vector<int>& ramp, uint8_t untouched)
{
  for (int y = 0; y < static_cast<int>(g.getSizeInCellsY()); ++y)
  {
    std::size_t k = 0;
    for (int x = 0; x < static_cast<int>(g.getSizeInCellsX()); ++x)
    {
      const bool inside = x >= x0 && x < xn && y >= y0 && y < yn;
      if (!inside)
      {
        EXPECT_EQ(g.getCost(x, y), untouched) << x << "," << y;
        continue;
      }
      EXPECT_EQ(static_cast<int>(g.getCost(x, y)), ramp[k]) << "cell " << x << "," << y << " k " << k;
      k = (k + 1 == ramp.size()) ? 0 : k + 1;  // k runs 0, 1, ..., size + 1, then restarts at 0
    }
  }
}

constexpr double kF = std::numeric_limits<float>::max();
}  // namespace

// ---------------------------------------------------------------- parameters

TEST(GradientLayerParams, Defaults)
{
  LayeredCostmap lc("map", false, false);
  auto layer = makeGradient(lc);
  EXPECT_TRUE(layer->enabled());
  EXPECT_EQ(layer->config().gradient_size, 20);
  EXPECT_EQ(layer->config().gradient_factor, 10);
  EXPECT_TRUE(layer->isInitialized());
  EXPECT_FALSE(layer->isClearable());
}

TEST(GradientLayerParams, ValuesAreRead)
{
  LayeredCostmap lc("map", false, false);
  ParamValue p = ParamValue::makeMap();
  p.set("enabled", ParamValue::makeBool(false));
  p.set("gradient_size", ParamValue::makeInt(5));
  p.set("gradient_factor", ParamValue::makeInt(40));
  auto layer = makeGradient(lc, p);
  EXPECT_FALSE(layer->enabled());
  EXPECT_EQ(layer->config().gradient_size, 5);
  EXPECT_EQ(layer->config().gradient_factor, 40);

  // A whole double counts as an integer; limits are inclusive.
  auto b = makeGradient(lc, withParam("gradient_size", ParamValue::makeDouble(7.0)));
  EXPECT_EQ(b->config().gradient_size, 7);
  EXPECT_EQ(makeGradient(lc, withParam("gradient_factor", ParamValue::makeInt(254)))->config().gradient_factor, 254);
  EXPECT_EQ(makeGradient(lc, withParam("gradient_factor", ParamValue::makeInt(0)))->config().gradient_factor, 0);
  EXPECT_EQ(makeGradient(lc, withParam("gradient_size", ParamValue::makeInt(0)))->config().gradient_size, 0);
}

TEST(GradientLayerParams, InvalidValuesThrowNamingTheParameter)
{
  LayeredCostmap lc("map", false, false);
  const std::vector<std::pair<std::string, ParamValue>> bad = {
      {"gradient_size", ParamValue::makeInt(-1)},      {"gradient_size", ParamValue::makeDouble(2.5)},
      {"gradient_size", ParamValue::makeString("20")}, {"gradient_factor", ParamValue::makeInt(255)},
      {"gradient_factor", ParamValue::makeInt(-3)},    {"gradient_factor", ParamValue::makeBool(true)},
      {"enabled", ParamValue::makeString("yes")},      {"enabled", ParamValue::makeInt(2)},
  };
  for (const auto& b : bad)
  {
    try
    {
      makeGradient(lc, withParam(b.first, b.second));
      ADD_FAILURE() << b.first << " = " << b.second.toString() << " was accepted";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find(b.first), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("gradient"), std::string::npos) << e.what();  // the owner
    }
  }
}

TEST(GradientLayerParams, ParseGradientConfigDirectly)
{
  ParamValue p = ParamValue::makeMap();
  p.set("gradient_size", ParamValue::makeInt(3));
  const GradientConfig c = parseGradientConfig(ParamReader(p, "g"));
  EXPECT_EQ(c.gradient_size, 3);
  EXPECT_EQ(c.gradient_factor, 10);
}

// ---------------------------------------------------------------- bounds

TEST(GradientLayerBounds, FirstWholeMapThenPreviousBoundsUnited)
{
  LayeredCostmap lc("map", false, false);
  auto layer = makeGradient(lc);

  // Call 1: the whole map, whatever came in.
  double a = 1, b = 2, c = 3, d = 4;
  layer->updateBounds(0, 0, 0, &a, &b, &c, &d);
  EXPECT_EQ(a, -kF);
  EXPECT_EQ(b, -kF);
  EXPECT_EQ(c, kF);
  EXPECT_EQ(d, kF);

  // Call 2: the union of what came in on call 1 and what comes in now.
  a = 5, b = 6, c = 7, d = 8;
  layer->updateBounds(0, 0, 0, &a, &b, &c, &d);
  EXPECT_EQ(a, 1);
  EXPECT_EQ(b, 2);
  EXPECT_EQ(c, 7);
  EXPECT_EQ(d, 8);

  // Call 3: the union of call 2's input (5, 6, 7, 8) and this input.
  a = 0, b = 10, c = 6, d = 12;
  layer->updateBounds(0, 0, 0, &a, &b, &c, &d);
  EXPECT_EQ(a, 0);
  EXPECT_EQ(b, 6);
  EXPECT_EQ(c, 7);
  EXPECT_EQ(d, 12);

  // Call 4: call 3's input (0, 10, 6, 12) with a small box inside it.
  a = 3, b = 11, c = 4, d = 11.5;
  layer->updateBounds(0, 0, 0, &a, &b, &c, &d);
  EXPECT_EQ(a, 0);
  EXPECT_EQ(b, 10);
  EXPECT_EQ(c, 6);
  EXPECT_EQ(d, 12);
}

TEST(GradientLayerBounds, FootprintChangeAndResetAskForTheWholeMapAgain)
{
  LayeredCostmap lc("map", false, false);
  auto layer = makeGradient(lc);
  double a = 1, b = 1, c = 2, d = 2;
  layer->updateBounds(0, 0, 0, &a, &b, &c, &d);
  a = 1, b = 1, c = 2, d = 2;
  layer->updateBounds(0, 0, 0, &a, &b, &c, &d);
  EXPECT_EQ(a, 1);

  layer->onFootprintChanged();
  a = 1, b = 1, c = 2, d = 2;
  layer->updateBounds(0, 0, 0, &a, &b, &c, &d);
  EXPECT_EQ(a, -kF);
  EXPECT_EQ(d, kF);

  // Through LayeredCostmap::setFootprint as well.
  a = 1, b = 1, c = 2, d = 2;
  layer->updateBounds(0, 0, 0, &a, &b, &c, &d);
  EXPECT_EQ(a, 1);
  lc.addPlugin(layer);
  lc.setFootprint(makeFootprintFromRadius(0.2));
  a = 1, b = 1, c = 2, d = 2;
  layer->updateBounds(0, 0, 0, &a, &b, &c, &d);
  EXPECT_EQ(a, -kF);
  EXPECT_EQ(b, -kF);
  EXPECT_EQ(c, kF);
  EXPECT_EQ(d, kF);

  layer->reset();
  a = 1, b = 1, c = 2, d = 2;
  layer->updateBounds(0, 0, 0, &a, &b, &c, &d);
  EXPECT_EQ(a, -kF);
}

// ---------------------------------------------------------------- costs

TEST(GradientLayerCosts, WholeMapDefaultRamp)
{
  LayeredCostmap lc("map", false, false);
  auto layer = makeGradient(lc);
  Costmap2D g(60, 4, 0.05, 0, 0, 1);
  layer->updateCosts(g, 0, 0, 60, 4);
  expectRamp(g, 0, 0, 60, 4, kRampSize20Factor10, 1);
  // Values written out: 254, 244, ..., the 22nd cell (k = 21) is 44, then back to 254.
  EXPECT_EQ(g.getCost(0, 0), 254);
  EXPECT_EQ(g.getCost(1, 0), 244);
  EXPECT_EQ(g.getCost(21, 2), 44);
  EXPECT_EQ(g.getCost(22, 3), 254);
  EXPECT_EQ(g.getCost(44, 1), 254);
}

TEST(GradientLayerCosts, PartialWindowStartsAtItsFirstColumn)
{
  LayeredCostmap lc("map", false, false);
  auto layer = makeGradient(lc);
  Costmap2D g(50, 6, 1.0, 0, 0, 77);
  layer->updateCosts(g, 7, 1, 40, 4);
  expectRamp(g, 7, 1, 40, 4, kRampSize20Factor10, 77);
  EXPECT_EQ(g.getCost(7, 1), 254);
  EXPECT_EQ(g.getCost(6, 1), 77);
  EXPECT_EQ(g.getCost(7, 0), 77);
  EXPECT_EQ(g.getCost(40, 3), 77);
}

TEST(GradientLayerCosts, WindowIsClampedToTheGrid)
{
  LayeredCostmap lc("map", false, false);
  auto layer = makeGradient(lc);
  Costmap2D g(30, 5, 1.0, 0, 0, 77);
  layer->updateCosts(g, -10, -3, 100, 2);  // clamped to [0, 30) x [0, 2)
  expectRamp(g, 0, 0, 30, 2, kRampSize20Factor10, 77);
  Costmap2D h(10, 10, 1.0, 0, 0, 77);
  layer->updateCosts(h, 5, 5, 5, 9);     // empty
  layer->updateCosts(h, 20, 0, 30, 10);  // outside
  for (unsigned int i = 0; i < h.cellCount(); ++i)
    EXPECT_EQ(h.getCost(i), 77);
}

TEST(GradientLayerCosts, CustomSizeAndFactorIncludingWrap)
{
  LayeredCostmap lc("map", false, false);
  ParamValue p = ParamValue::makeMap();
  p.set("gradient_size", ParamValue::makeInt(15));
  p.set("gradient_factor", ParamValue::makeInt(20));  // 254 - k*20 goes negative from k = 13
  auto layer = makeGradient(lc, p);
  Costmap2D g(45, 3, 1.0, 0, 0, 0);
  layer->updateCosts(g, 2, 0, 43, 3);
  expectRamp(g, 2, 0, 43, 3, kRampSize15Factor20, 0);
  EXPECT_EQ(g.getCost(2 + 12, 0), 14);        // 254 - 240
  EXPECT_EQ(g.getCost(2 + 13, 0), 256 - 6);   // -6 stored in an unsigned char
  EXPECT_EQ(g.getCost(2 + 16, 0), 256 - 66);  // k = 16 = size + 1 is the last of the ramp
  EXPECT_EQ(g.getCost(2 + 17, 0), 254);       // restarted at k = 0

  auto zero = makeGradient(lc, withParam("gradient_size", ParamValue::makeInt(0)));
  Costmap2D z(6, 1, 1.0, 0, 0, 0);
  zero->updateCosts(z, 0, 0, 6, 1);
  expectRamp(z, 0, 0, 6, 1, kRampSize0Factor10, 0);
  EXPECT_EQ(z.getCost(0, 0), 254);
  EXPECT_EQ(z.getCost(1, 0), 244);
  EXPECT_EQ(z.getCost(2, 0), 254);
}

TEST(GradientLayerCosts, GradientCostMatchesFormula)
{
  // (254 - k * f) % 255 in int arithmetic (the remainder keeps the sign), stored in an unsigned char.
  EXPECT_EQ(gradientCost(39, 0), 254);
  EXPECT_EQ(gradientCost(39, 1), 215);
  EXPECT_EQ(gradientCost(25, 10), 4);
  EXPECT_EQ(gradientCost(30, 10), 210);   // -46 -> 210
  EXPECT_EQ(gradientCost(13, 20), 250);   // -6 -> 250
  EXPECT_EQ(gradientCost(2, 127), 0);
  EXPECT_EQ(gradientCost(3, 127), 129);   // -127 -> 129
  EXPECT_EQ(gradientCost(1, 254), 0);
  EXPECT_EQ(gradientCost(2, 254), 2);     // -254 -> 2
  EXPECT_EQ(gradientCost(3, 254), 3);     // -508 % 255 = -253 -> 3
  EXPECT_EQ(gradientCost(300, 1), 210);   // -46 -> 210
}

TEST(GradientLayerCosts, ThroughLayeredCostmap)
{
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(50, 3, 0.1, 0.0, 0.0);
  auto layer = makeGradient(lc);
  lc.addPlugin(layer);
  lc.updateMap(0, 0, 0);
  const CellWindow w = lc.getUpdatedBounds();
  EXPECT_EQ(w.x0, 0);
  EXPECT_EQ(w.y0, 0);
  EXPECT_EQ(w.xn, 50);
  EXPECT_EQ(w.yn, 3);
  expectRamp(lc.getCostmap(), 0, 0, 50, 3, kRampSize20Factor10, 0);
  // Alone in the costmap, later cycles repeat "nothing": the map stays as it is.
  lc.updateMap(0, 0, 0);
  EXPECT_TRUE(lc.getUpdatedBounds().empty());
  expectRamp(lc.getCostmap(), 0, 0, 50, 3, kRampSize20Factor10, 0);
  // A footprint change redraws everything.
  lc.getCostmap().fillWindow(0, 0, 50, 3, 9);
  lc.setFootprint(makeFootprintFromRadius(0.3));
  lc.updateMap(0, 0, 0);
  expectRamp(lc.getCostmap(), 0, 0, 50, 3, kRampSize20Factor10, 0);
}
