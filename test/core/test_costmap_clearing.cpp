// The "clear costmaps" helpers behind the node's ~clear and ~clear_around_robot services.
#include <gtest/gtest.h>

#include <memory>

#include "costmap_layers/core/cost_values.hpp"
#include "costmap_layers/core/costmap_clearing.hpp"
#include "costmap_layers/core/costmap_layer.hpp"
#include "costmap_layers/core/layered_costmap.hpp"
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
