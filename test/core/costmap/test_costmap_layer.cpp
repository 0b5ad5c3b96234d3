// Unit tests of CostmapLayer: the five merge rules (every own/master combination, window only),
// matchSize, and the extra-bounds bookkeeping.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/costmap/costmap_layer.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;

namespace
{
class MergeTestLayer : public CostmapLayer
{
public:
  void updateBounds(double, double, double, double* min_x, double* min_y, double* max_x, double* max_y) override
  {
    useExtraBounds(min_x, min_y, max_x, max_y);
  }
  void updateCosts(Costmap2D&, int, int, int, int) override {}
  static void callTouch(double x, double y, double* a, double* b, double* c, double* d) { touch(x, y, a, b, c, d); }
};

const std::vector<uint8_t> kValues = {0, 100, 252, 253, 254, 255};
constexpr uint8_t U = 255;  // NO_INFORMATION, spelled out independently of the header

// The rules, written from the header comments.
uint8_t ruleMax(uint8_t own, uint8_t master)
{
  if (own == U) return master;   // an unknown own cell changes nothing
  if (master == U) return own;   // an unknown master takes the own cost
  return std::max(own, master);  // otherwise the higher one
}
uint8_t ruleTrueOverwrite(uint8_t own, uint8_t)
{
  return own;
}
uint8_t ruleOverwrite(uint8_t own, uint8_t master)
{
  return own == U ? master : own;
}
uint8_t ruleAddition(uint8_t own, uint8_t master)
{
  if (own == U) return master;
  if (master == U) return own;
  const int sum = own + master;
  return static_cast<uint8_t>(sum > 252 ? 252 : sum);
}
uint8_t ruleMaxWithoutUnknownOverwrite(uint8_t own, uint8_t master)
{
  if (own == U) return master;
  if (master == U) return U;  // unknown master cells stay unknown
  return std::max(own, master);
}

using MergeFn = void (CostmapLayer::*)(Costmap2D&, int, int, int, int) const;
using RuleFn = uint8_t (*)(uint8_t, uint8_t);

/// A 10x9 grid pair; the window [2, 8) x [1, 7) holds all 36 (own, master) combinations, cell
/// (2 + a, 1 + b) having own = kValues[a] and master = kValues[b]. Outside the window own is 254 /
/// 100 / 0 in a pattern and master is 7, so any write outside shows.
struct MergeFixture
{
  std::shared_ptr<MergeTestLayer> layer = std::make_shared<MergeTestLayer>();
  Costmap2D master{10, 9, 0.5, 0.0, 0.0, 7};

  MergeFixture()
  {
    Costmap2D& own = layer->costmap();
    own.resizeMap(10, 9, 0.5, 0.0, 0.0);
    for (unsigned int y = 0; y < 9; ++y)
      for (unsigned int x = 0; x < 10; ++x)
        own.setCost(x, y, static_cast<uint8_t>((x + y) % 3 == 0 ? 254 : (x % 2 ? 100 : 0)));
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b)
      {
        own.setCost(2 + a, 1 + b, kValues[a]);
        master.setCost(2 + a, 1 + b, kValues[b]);
      }
  }

  void check(MergeFn merge, RuleFn rule)
  {
    const Costmap2D before = master;
    (layer.get()->*merge)(master, 2, 1, 8, 7);
    for (unsigned int y = 0; y < 9; ++y)
      for (unsigned int x = 0; x < 10; ++x)
      {
        const bool inside = x >= 2 && x < 8 && y >= 1 && y < 7;
        const uint8_t expected =
            inside ? rule(layer->costmap().getCost(x, y), before.getCost(x, y)) : before.getCost(x, y);
        EXPECT_EQ(static_cast<int>(master.getCost(x, y)), static_cast<int>(expected))
            << "cell " << x << "," << y << " own " << int(layer->costmap().getCost(x, y)) << " master "
            << int(before.getCost(x, y));
      }
  }
};
}  // namespace

TEST(CostmapLayerMerge, UpdateWithMaxAllCombinations)
{
  MergeFixture f;
  f.check(&CostmapLayer::updateWithMax, ruleMax);
}

TEST(CostmapLayerMerge, UpdateWithTrueOverwriteAllCombinations)
{
  MergeFixture f;
  f.check(&CostmapLayer::updateWithTrueOverwrite, ruleTrueOverwrite);
}

TEST(CostmapLayerMerge, UpdateWithOverwriteAllCombinations)
{
  MergeFixture f;
  f.check(&CostmapLayer::updateWithOverwrite, ruleOverwrite);
}

TEST(CostmapLayerMerge, UpdateWithAdditionAllCombinations)
{
  MergeFixture f;
  f.check(&CostmapLayer::updateWithAddition, ruleAddition);
}

TEST(CostmapLayerMerge, UpdateWithMaxWithoutUnknownOverwriteAllCombinations)
{
  MergeFixture f;
  f.check(&CostmapLayer::updateWithMaxWithoutUnknownOverwrite, ruleMaxWithoutUnknownOverwrite);
}

TEST(CostmapLayerMerge, SpotValuesWrittenOut)
{
  // A few combinations spelled out literally, so that a mistake shared by rule and code still shows.
  auto one = [](MergeFn merge, uint8_t own, uint8_t master)
  {
    MergeTestLayer layer;
    layer.costmap().resizeMap(1, 1, 1.0, 0, 0);
    layer.costmap().setCost(0, 0, own);
    Costmap2D m(1, 1, 1.0, 0, 0, master);
    (layer.*merge)(m, 0, 0, 1, 1);
    return static_cast<int>(m.getCost(0, 0));
  };
  EXPECT_EQ(one(&CostmapLayer::updateWithMax, 100, 252), 252);
  EXPECT_EQ(one(&CostmapLayer::updateWithMax, 255, 0), 0);
  EXPECT_EQ(one(&CostmapLayer::updateWithMax, 0, 255), 0);
  EXPECT_EQ(one(&CostmapLayer::updateWithTrueOverwrite, 255, 254), 255);
  EXPECT_EQ(one(&CostmapLayer::updateWithOverwrite, 255, 254), 254);
  EXPECT_EQ(one(&CostmapLayer::updateWithOverwrite, 0, 254), 0);
  EXPECT_EQ(one(&CostmapLayer::updateWithAddition, 100, 100), 200);
  EXPECT_EQ(one(&CostmapLayer::updateWithAddition, 100, 152), 252);
  EXPECT_EQ(one(&CostmapLayer::updateWithAddition, 100, 153), 252);
  EXPECT_EQ(one(&CostmapLayer::updateWithAddition, 254, 0), 252);
  EXPECT_EQ(one(&CostmapLayer::updateWithAddition, 254, 255), 254);
  EXPECT_EQ(one(&CostmapLayer::updateWithAddition, 255, 100), 100);
  EXPECT_EQ(one(&CostmapLayer::updateWithMaxWithoutUnknownOverwrite, 254, 255), 255);
  EXPECT_EQ(one(&CostmapLayer::updateWithMaxWithoutUnknownOverwrite, 255, 10), 10);
  EXPECT_EQ(one(&CostmapLayer::updateWithMaxWithoutUnknownOverwrite, 254, 10), 254);
}

TEST(CostmapLayerMerge, WindowIsClampedToTheGrid)
{
  MergeFixture f;
  const Costmap2D before = f.master;
  f.layer->updateWithTrueOverwrite(f.master, -5, -5, 3, 100);  // effectively [0, 3) x [0, 9)
  for (unsigned int y = 0; y < 9; ++y)
    for (unsigned int x = 0; x < 10; ++x)
      EXPECT_EQ(f.master.getCost(x, y), x < 3 ? f.layer->costmap().getCost(x, y) : before.getCost(x, y));
}

TEST(CostmapLayerMerge, EmptyOrInvertedWindowChangesNothing)
{
  MergeFixture f;
  const Costmap2D before = f.master;
  f.layer->updateWithTrueOverwrite(f.master, 5, 1, 5, 7);
  f.layer->updateWithTrueOverwrite(f.master, 6, 7, 2, 1);
  f.layer->updateWithTrueOverwrite(f.master, 20, 20, 30, 30);
  f.layer->updateWithMax(f.master, -10, -10, -1, -1);
  for (unsigned int i = 0; i < f.master.cellCount(); ++i)
    EXPECT_EQ(f.master.getCost(i), before.getCost(i));
}

TEST(CostmapLayerMerge, OwnGridSmallerThanMasterMergesSharedCellsOnly)
{
  MergeTestLayer layer;
  layer.costmap().resizeMap(3, 2, 1.0, 0, 0);
  for (unsigned int i = 0; i < 6; ++i)
    layer.costmap().setCost(i % 3, i / 3, static_cast<uint8_t>(10 + i));
  Costmap2D master(5, 4, 1.0, 0, 0, 1);
  layer.updateWithTrueOverwrite(master, 0, 0, 5, 4);
  for (unsigned int y = 0; y < 4; ++y)
    for (unsigned int x = 0; x < 5; ++x)
      EXPECT_EQ(master.getCost(x, y), (x < 3 && y < 2) ? 10 + x + 3 * y : 1) << x << "," << y;
}

TEST(CostmapLayerBasics, MatchSizeFollowsTheMasterGrid)
{
  LayeredCostmap lc("map", false, true);
  auto layer = std::make_shared<MergeTestLayer>();
  layer->initialize(&lc, "merge", std::make_shared<FakeContext>());
  lc.addPlugin(layer);
  lc.resizeMap(12, 7, 0.2, -1.0, 3.0);
  const Costmap2D& own = layer->costmap();
  EXPECT_EQ(own.getSizeInCellsX(), 12u);
  EXPECT_EQ(own.getSizeInCellsY(), 7u);
  EXPECT_DOUBLE_EQ(own.getResolution(), 0.2);
  EXPECT_DOUBLE_EQ(own.getOriginX(), -1.0);
  EXPECT_DOUBLE_EQ(own.getOriginY(), 3.0);
  lc.resizeMap(4, 5, 1.0, 0.0, 0.0);
  EXPECT_EQ(layer->costmap().getSizeInCellsX(), 4u);
  EXPECT_EQ(layer->costmap().getSizeInCellsY(), 5u);
  EXPECT_EQ(layer->costmap().cellCount(), 20u);
}

TEST(CostmapLayerBasics, TouchGrowsBounds)
{
  double a = std::numeric_limits<double>::max(), b = a;
  double c = std::numeric_limits<double>::lowest(), d = c;
  MergeTestLayer::callTouch(1.0, 2.0, &a, &b, &c, &d);
  EXPECT_DOUBLE_EQ(a, 1.0);
  EXPECT_DOUBLE_EQ(b, 2.0);
  EXPECT_DOUBLE_EQ(c, 1.0);
  EXPECT_DOUBLE_EQ(d, 2.0);
  MergeTestLayer::callTouch(-3.0, 5.0, &a, &b, &c, &d);
  MergeTestLayer::callTouch(0.0, 0.0, &a, &b, &c, &d);
  EXPECT_DOUBLE_EQ(a, -3.0);
  EXPECT_DOUBLE_EQ(b, 0.0);
  EXPECT_DOUBLE_EQ(c, 1.0);
  EXPECT_DOUBLE_EQ(d, 5.0);
}

TEST(CostmapLayerBasics, ExtraBoundsAreUnitedOnceThenForgotten)
{
  MergeTestLayer layer;
  double a = 0, b = 0, c = 1, d = 1;
  layer.updateBounds(0, 0, 0, &a, &b, &c, &d);  // nothing requested: unchanged
  EXPECT_DOUBLE_EQ(a, 0);
  EXPECT_DOUBLE_EQ(d, 1);

  layer.addExtraBounds(2, 3, 4, 5);
  layer.addExtraBounds(-1, 4, 3, 9);  // united with the first request
  layer.updateBounds(0, 0, 0, &a, &b, &c, &d);
  EXPECT_DOUBLE_EQ(a, -1);
  EXPECT_DOUBLE_EQ(b, 0);
  EXPECT_DOUBLE_EQ(c, 4);
  EXPECT_DOUBLE_EQ(d, 9);

  double e = 0, f = 0, g = 1, h = 1;
  layer.updateBounds(0, 0, 0, &e, &f, &g, &h);  // used up
  EXPECT_DOUBLE_EQ(e, 0);
  EXPECT_DOUBLE_EQ(f, 0);
  EXPECT_DOUBLE_EQ(g, 1);
  EXPECT_DOUBLE_EQ(h, 1);

  layer.addExtraBounds(10, 10, 11, 11);  // a fresh request after use is not merged with the old one
  layer.updateBounds(0, 0, 0, &e, &f, &g, &h);
  EXPECT_DOUBLE_EQ(e, 0);
  EXPECT_DOUBLE_EQ(f, 0);
  EXPECT_DOUBLE_EQ(g, 11);
  EXPECT_DOUBLE_EQ(h, 11);
}
