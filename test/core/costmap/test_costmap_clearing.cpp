// The "clear costmaps" helpers behind the node's ~clear and ~clear_around_robot services.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <memory>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/costmap/costmap_clearing.hpp"
#include "costmap_layers/core/costmap/costmap_layer.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;

namespace
{
/// A sensor-like layer: marks cells on request, asks only for what it marked, and is clearable.
class MarkLayer : public CostmapLayer
{
public:
  explicit MarkLayer(bool clearable) : clearable_(clearable) {}
  void mark(unsigned x, unsigned y)
  {
    costmap_.setCost(x, y, LETHAL_OBSTACLE);
    double wx, wy;
    costmap_.mapToWorld(x, y, wx, wy);
    addExtraBounds(wx, wy, wx, wy);
  }
  void updateBounds(double, double, double, double* x0, double* y0, double* x1, double* y1) override
  {
    useExtraBounds(x0, y0, x1, y1);
  }
  void updateCosts(Costmap2D& master, int i0, int j0, int i1, int j1) override
  {
    updateWithMax(master, i0, j0, i1, j1);
  }
  void reset() override { costmap_.resetMaps(); }
  bool isClearable() override { return clearable_; }

private:
  bool clearable_;
};

struct Rig
{
  LayeredCostmap lc{"map", false, false};
  std::shared_ptr<MarkLayer> sensor = std::make_shared<MarkLayer>(true);
  std::shared_ptr<MarkLayer> fixed = std::make_shared<MarkLayer>(false);
  Rig()
  {
    lc.resizeMap(20, 20, 1.0, 0.0, 0.0);
    for (auto& l : {sensor, fixed})
    {
      l->initialize(&lc, l == sensor ? "sensor" : "fixed", std::make_shared<FakeContext>());
      lc.addPlugin(l);
      l->matchSize();
    }
    sensor->mark(1, 1);    // far from the robot
    sensor->mark(10, 10);  // next to the robot
    fixed->mark(18, 18);   // not clearable
    lc.updateMap(10.5, 10.5, 0.0);
  }
};
}  // namespace

TEST(CostmapClearing, ResetClearsOnlyClearableLayersAndTheMasterFollows)
{
  Rig r;
  ASSERT_EQ(r.lc.getCostmap().getCost(1, 1), LETHAL_OBSTACLE);
  EXPECT_EQ(resetClearableLayers(r.lc), 1);
  r.lc.updateMap(10.5, 10.5, 0.0);  // the whole grid is redrawn although nothing new was marked
  EXPECT_EQ(r.lc.getCostmap().getCost(1, 1), FREE_SPACE);
  EXPECT_EQ(r.lc.getCostmap().getCost(10, 10), FREE_SPACE);
  EXPECT_EQ(r.lc.getCostmap().getCost(18, 18), LETHAL_OBSTACLE);
}

TEST(CostmapClearing, AroundTheRobotKeepsTheSquare)
{
  Rig r;
  EXPECT_EQ(clearClearableLayersAround(r.lc, 10.5, 10.5, 3.0), 1);
  r.lc.updateMap(10.5, 10.5, 0.0);
  EXPECT_EQ(r.lc.getCostmap().getCost(1, 1), FREE_SPACE);         // outside the 3 m square: cleared
  EXPECT_EQ(r.lc.getCostmap().getCost(10, 10), LETHAL_OBSTACLE);  // inside: kept
  EXPECT_EQ(r.lc.getCostmap().getCost(18, 18), LETHAL_OBSTACLE);  // not clearable: kept
  // The square is [9, 12) around (10.5, 10.5): cells 9..12 kept, 8 and 13 cleared.
  r.sensor->mark(8, 10);
  r.sensor->mark(9, 10);
  r.sensor->mark(12, 10);
  r.sensor->mark(13, 10);
  r.lc.updateMap(10.5, 10.5, 0.0);
  clearClearableLayersAround(r.lc, 10.5, 10.5, 3.0);
  r.lc.updateMap(10.5, 10.5, 0.0);
  EXPECT_EQ(r.lc.getCostmap().getCost(8, 10), FREE_SPACE);
  EXPECT_EQ(r.lc.getCostmap().getCost(9, 10), LETHAL_OBSTACLE);
  EXPECT_EQ(r.lc.getCostmap().getCost(12, 10), LETHAL_OBSTACLE);
  EXPECT_EQ(r.lc.getCostmap().getCost(13, 10), FREE_SPACE);
}

namespace
{
/// A layer below that puts NO_INFORMATION on every master cell (as a static layer over an unmapped area).
class UnknownBelow : public CostmapLayer
{
public:
  void updateBounds(double, double, double, double* x0, double* y0, double* x1, double* y1) override
  {
    *x0 = std::min(*x0, costmap_.getOriginX());
    *y0 = std::min(*y0, costmap_.getOriginY());
    *x1 = std::max(*x1, costmap_.getOriginX() + costmap_.getSizeInMetersX());
    *y1 = std::max(*y1, costmap_.getOriginY() + costmap_.getSizeInMetersY());
  }
  void updateCosts(Costmap2D& master, int i0, int j0, int i1, int j1) override
  {
    costmap_.fillWindow(0, 0, costmap_.getSizeInCellsX(), costmap_.getSizeInCellsY(), NO_INFORMATION);
    updateWithTrueOverwrite(master, i0, j0, i1, j1);
  }
};
}  // namespace

// costmap_2d's clearArea (and so move_base's clear-costmap recovery) sets a cleared cell to
// NO_INFORMATION whatever the layer's default: the layer forgets it, and the master keeps what the
// layers below give there. A layer whose default is FREE_SPACE (track_unknown_space false) makes an
// unknown cell below free until it is cleared; afterwards the cell is unknown again. A reset (~clear,
// move_base's clear_costmaps) puts the default back, as costmap_2d's resetMaps does.
TEST(CostmapClearing, AClearedCellShowsWhatTheLayersBelowGive)
{
  LayeredCostmap lc{"map", false, false};
  lc.resizeMap(20, 20, 1.0, 0.0, 0.0);
  auto below = std::make_shared<UnknownBelow>();
  auto sensor = std::make_shared<MarkLayer>(true);
  for (const std::shared_ptr<CostmapLayer>& l :
       {std::shared_ptr<CostmapLayer>(below), std::shared_ptr<CostmapLayer>(sensor)})
  {
    l->initialize(&lc, l == below ? "below" : "sensor", std::make_shared<FakeContext>());
    lc.addPlugin(l);
    l->matchSize();
  }
  ASSERT_EQ(sensor->costmap().getDefaultValue(), FREE_SPACE);
  sensor->mark(1, 1);
  sensor->mark(10, 10);
  lc.updateMap(10.5, 10.5, 0.0);
  ASSERT_EQ(lc.getCostmap().getCost(1, 1), LETHAL_OBSTACLE);
  ASSERT_EQ(lc.getCostmap().getCost(5, 5), FREE_SPACE);  // the sensor layer's free over the unknown
  ASSERT_EQ(clearClearableLayersAround(lc, 10.5, 10.5, 3.0), 1);
  lc.updateMap(10.5, 10.5, 0.0);
  EXPECT_EQ(sensor->costmap().getCost(1, 1), NO_INFORMATION);
  EXPECT_EQ(lc.getCostmap().getCost(1, 1), NO_INFORMATION);     // cleared: what lies below
  EXPECT_EQ(lc.getCostmap().getCost(5, 5), NO_INFORMATION);     // cleared too (outside the square)
  EXPECT_EQ(lc.getCostmap().getCost(10, 10), LETHAL_OBSTACLE);  // kept
  EXPECT_EQ(lc.getCostmap().getCost(11, 10), FREE_SPACE);       // kept: the layer's free
  // move_base's recovery: everything outside (2, 2)..(18, 18) cleared, the cells between kept.
  sensor->mark(1, 1);
  ASSERT_TRUE(clearLayerArea(*sensor, 2, 2, 18, 18, false));
  lc.updateMap(10.5, 10.5, 0.0);
  EXPECT_EQ(lc.getCostmap().getCost(1, 1), NO_INFORMATION);
  EXPECT_EQ(lc.getCostmap().getCost(10, 10), LETHAL_OBSTACLE);
  // A reset puts the layer's default back: free over the unknown again.
  ASSERT_EQ(resetClearableLayers(lc), 1);
  lc.updateMap(10.5, 10.5, 0.0);
  EXPECT_EQ(lc.getCostmap().getCost(1, 1), FREE_SPACE);
  EXPECT_EQ(lc.getCostmap().getCost(10, 10), FREE_SPACE);
  // resetLayerCells (what the bridge's Costmap2D::resetMaps does) too.
  sensor->mark(3, 3);
  ASSERT_TRUE(clearLayerArea(*sensor, 0, 0, 0, 0, false));
  ASSERT_EQ(sensor->costmap().getCost(3, 3), NO_INFORMATION);
  ASSERT_TRUE(resetLayerCells(*sensor));
  EXPECT_EQ(sensor->costmap().getCost(3, 3), FREE_SPACE);
  lc.updateMap(10.5, 10.5, 0.0);
  EXPECT_EQ(lc.getCostmap().getCost(3, 3), FREE_SPACE);
}

namespace
{
/// A 20 x 20 grid of 0.5 m cells from (-3, 2), every cell of the clearable layer marked.
struct EdgeRig
{
  LayeredCostmap lc{"map", false, false};
  std::shared_ptr<MarkLayer> sensor = std::make_shared<MarkLayer>(true);
  EdgeRig()
  {
    lc.resizeMap(20, 20, 0.5, -3.0, 2.0);
    sensor->initialize(&lc, "sensor", std::make_shared<FakeContext>());
    lc.addPlugin(sensor);
    sensor->matchSize();
    for (unsigned j = 0; j < 20; ++j)
      for (unsigned i = 0; i < 20; ++i)
        sensor->mark(i, j);
  }
  /// Cells of the layer that differ from the reference: a cell is kept when it meets the closed square of
  /// side keep centred on (x, y), i.e. its centre lies within keep / 2 + half a cell on both axes (the
  /// cell's upper edges excluded). Computed from cell centres only.
  int mismatches(double x, double y, double keep) const
  {
    const Costmap2D& g = sensor->costmap();
    const double h = 0.5, half = keep / 2;
    int bad = 0;
    for (unsigned j = 0; j < 20; ++j)
      for (unsigned i = 0; i < 20; ++i)
      {
        const double cx = -3.0 + (i + 0.5) * h, cy = 2.0 + (j + 0.5) * h;
        const bool kept_x = cx - h / 2 <= x + half && cx + h / 2 > x - half;
        const bool kept_y = cy - h / 2 <= y + half && cy + h / 2 > y - half;
        const uint8_t want = kept_x && kept_y ? LETHAL_OBSTACLE : NO_INFORMATION;  // cleared: forgotten
        bad += g.getCost(i, j) != want;
      }
    return bad;
  }
  int lethal() const
  {
    int n = 0;
    for (std::size_t k = 0; k < sensor->costmap().cellCount(); ++k)
      n += sensor->costmap().data()[k] == LETHAL_OBSTACLE;
    return n;
  }
};
}  // namespace

TEST(CostmapClearing, AroundARobotOutsideTheGridKeepsNothingOfTheEdges)
{
  // The grid covers x in [-3, 7), y in [2, 12). The robot off each side and each corner: the kept
  // square lies wholly outside, so every cell is cleared (the edge row / column used to be kept).
  const double cases[][2] = {
      {-5.3, 7.1},  {9.2, 7.1},  {2.1, 0.2},  {2.1, 13.9},    {-5.0, 0.0},     {9.0, 0.0},
      {-5.0, 14.0}, {9.0, 14.0}, {1e12, 7.0}, {-1e12, -1e12}, {7.0 + 1.5, 7.0}};  // just off the right edge: the square
                                                                                  // ends at 7.0
  for (const auto& c : cases)
  {
    EdgeRig r;
    EXPECT_EQ(clearClearableLayersAround(r.lc, c[0], c[1], 3.0), 1);
    EXPECT_EQ(r.lethal(), 0) << c[0] << ", " << c[1];
    EXPECT_EQ(r.mismatches(c[0], c[1], 3.0), 0) << c[0] << ", " << c[1];
  }
}

TEST(CostmapClearing, AroundASquarePartlyOutsideOrDegenerate)
{
  const double cases[][3] = {
      {-2.7, 6.3, 3.0},    // partly off the left edge
      {6.6, 11.8, 3.0},    // partly off the top right corner
      {-3.4, 1.9, 1.0},    // just outside the bottom left corner, square reaching in
      {2.1, 7.3, 0.0},     // keep_size 0: the robot's cell alone
      {2.0, 7.0, 0.0},     // ... on a cell corner: the cell above and right of it (upper edges excluded)
      {2.1, 7.3, 0.2},     // smaller than a cell
      {1e12, 0.0, 1e300},  // huge: everything kept however far the robot
      {2.1, 7.3, 1e300},  {1e12, 0.0, 1e6},  // a big square far away still keeps nothing
  };
  for (const auto& c : cases)
  {
    EdgeRig r;
    EXPECT_EQ(clearClearableLayersAround(r.lc, c[0], c[1], c[2]), 1);
    EXPECT_EQ(r.mismatches(c[0], c[1], c[2]), 0) << c[0] << ", " << c[1] << " keep " << c[2];
  }
  EdgeRig all;
  clearClearableLayersAround(all.lc, 1e12, -1e12, std::numeric_limits<double>::infinity());
  EXPECT_EQ(all.lethal(), 400);
}

TEST(CostmapClearing, AroundAnInvalidPoseIsRefused)
{
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const double cases[][3] = {{nan, 7.0, 3.0},  {2.0, nan, 3.0}, {inf, 7.0, 3.0},
                             {2.0, -inf, 3.0}, {2.0, 7.0, nan}, {2.0, 7.0, -1.0}};
  for (const auto& c : cases)
  {
    EdgeRig r;
    EXPECT_LT(clearClearableLayersAround(r.lc, c[0], c[1], c[2]), 0) << c[0] << ", " << c[1] << " keep " << c[2];
    EXPECT_EQ(r.lethal(), 400) << "nothing is cleared";
  }
}

// move_base's clear-costmap recovery calls costmap_2d's CostmapLayer::clearArea(x0, y0, x1, y1, invert)
// on the layers it clears. costmap_2d's rule, cell by cell (costmap_layer.cpp): a cell is "between" when
// x0 < x < x1 and y0 < y < y1; without invert every cell not between is cleared, with invert every cell
// between, to NO_INFORMATION (whatever the layer's default: the layer forgets the cell, and the master
// keeps what the layers below give there). The reference below is that loop; clearLayerArea must give
// the same grid for windows
// anywhere, at the int limits (what worldToMapNoBounds gives far off the map) and reversed.
TEST(CostmapClearing, ClearLayerAreaIsCostmap2dsClearArea)
{
  const int kMax = std::numeric_limits<int>::max(), kMin = std::numeric_limits<int>::min();
  const int windows[][4] = {{5, 5, 15, 15},     {-3, -3, 4, 6},           {0, 0, 19, 19},
                            {-1, -1, 20, 20},   {9, 9, 11, 11},           {10, 10, 11, 11},
                            {15, 2, 5, 12},     {30, 30, 40, 40},         {kMin, kMin, kMax, kMax},
                            {kMin, 4, 7, kMax}, {kMax, kMax, kMin, kMin}, {-40, -40, -30, -30}};
  for (const auto& w : windows)
  {
    for (const bool invert : {false, true})
    {
      Rig r;
      for (unsigned y = 0; y < 20; ++y)
        for (unsigned x = 0; x < 20; ++x)
          r.sensor->costmap().setCost(x, y, static_cast<unsigned char>(1 + (x * 7 + y * 3) % 250));
      ASSERT_TRUE(clearLayerArea(*r.sensor, w[0], w[1], w[2], w[3], invert));
      for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 20; ++x)
        {
          const bool between = x > w[0] && x < w[2] && y > w[1] && y < w[3];
          const unsigned char expected =
              between != invert ? static_cast<unsigned char>(1 + (x * 7 + y * 3) % 250) : NO_INFORMATION;
          ASSERT_EQ(r.sensor->costmap().getCost(x, y), expected)
              << "window " << w[0] << ", " << w[1] << " - " << w[2] << ", " << w[3] << " invert " << invert << " cell "
              << x << ", " << y;
        }
    }
  }
  // Not clearable: nothing happens. The master follows a clear on the next update (the whole map).
  Rig r;
  EXPECT_FALSE(clearLayerArea(*r.fixed, 0, 0, 1, 1, false));
  EXPECT_EQ(r.fixed->costmap().getCost(18, 18), LETHAL_OBSTACLE);
  ASSERT_TRUE(clearLayerArea(*r.sensor, 7, 7, 13, 13, false));  // keeps 8..12: (10, 10) stays
  r.lc.updateMap(10.5, 10.5, 0.0);
  EXPECT_EQ(r.lc.getCostmap().getCost(1, 1), FREE_SPACE);
  EXPECT_EQ(r.lc.getCostmap().getCost(10, 10), LETHAL_OBSTACLE);
  EXPECT_EQ(r.lc.getCostmap().getCost(18, 18), LETHAL_OBSTACLE);
}
