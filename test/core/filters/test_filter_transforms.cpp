// A keepout mask in another frame than the costmap's, in a costmap that does not roll: the filter
// asked for its mask's extent only when the mask changed, so a mask that came before its frame's
// transform was never drawn, a cycle without the transform left a lasting hole, and a transform that
// moved (localisation correcting map -> odom) left the zone at its old place. Whole update cycles of a
// LayeredCostmap, with another layer asking for its own windows as a sensor layer does.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/filters/keepout_filter.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "fake_context.hpp"
#include "sensor_test_helpers.hpp"

using namespace costmap_layers;
using namespace costmap_layers_test;

namespace
{
/// Asks for a box when armed and writes nothing (a sensor layer's raytraced window).
class WindowLayer : public Layer
{
public:
  bool armed = false;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  void updateBounds(double, double, double, double* min_x, double* min_y, double* max_x, double* max_y) override
  {
    if (!armed) return;
    *min_x = std::min(*min_x, x0);
    *min_y = std::min(*min_y, y0);
    *max_x = std::max(*max_x, x1);
    *max_y = std::max(*max_y, y1);
  }
  void updateCosts(Costmap2D&, int, int, int, int) override {}
};

/// A 20 x 20 costmap in "odom" (1 m cells), a window layer, and a keepout filter whose mask is in "map".
struct Stack
{
  Stack() : lc("odom", false, false)
  {
    lc.resizeMap(20, 20, 1.0, 0.0, 0.0);
    window_ctx = std::make_shared<FakeContext>(ParamValue::makeMap(), "odom");
    window = std::make_shared<WindowLayer>();
    window->initialize(&lc, "window", window_ctx);
    lc.addPlugin(window);
    ctx = std::make_shared<FakeContext>(ParamValue::makeMap(), "odom");
    keepout = std::make_shared<KeepoutFilter>();
    keepout->initialize(&lc, "keepout", ctx);
    ctx->bind(*keepout);
    lc.addFilter(keepout);
  }
  /// map -> odom: a point at odom (x, y) is at map (x + dx, y).
  void setOdomInMap(double dx)
  {
    ctx->transforms[{"map", "odom"}] = Transform2D{dx, 0.0, 0.0};
    ctx->transforms[{"odom", "map"}] = Transform2D{-dx, 0.0, 0.0};
  }
  void dropTransform() { ctx->transforms.clear(); }
  /// A mask in "map" with one lethal cell, map cell (5, 5).
  void publishMask()
  {
    OccupancyGridData m;
    m.frame_id = "map";
    m.width = m.height = 20;
    m.resolution = 1.0;
    m.data.assign(400, 0);
    m.data[5 * 20 + 5] = 100;
    ctx->publishGrid(GridKind::Mask, m);
  }
  void cycles(int n)
  {
    for (int k = 0; k < n; ++k)
      lc.updateMap(10.0, 10.0, 0.0);
  }
  uint8_t at(unsigned x, unsigned y) const { return lc.getCostmap().getCost(x, y); }
  int lethalCount() const
  {
    const Costmap2D& c = lc.getCostmap();
    return static_cast<int>(std::count(c.data(), c.data() + c.cellCount(), LETHAL_OBSTACLE));
  }

  LayeredCostmap lc;
  std::shared_ptr<FakeContext> window_ctx, ctx;
  std::shared_ptr<WindowLayer> window;
  std::shared_ptr<KeepoutFilter> keepout;
};
}  // namespace

TEST(FilterTransforms, AMaskThatCameBeforeItsTransformIsDrawnOnceTheTransformComes)
{
  Stack s;
  s.publishMask();  // a latched mask, before the static transform publisher is up
  s.cycles(1);
  EXPECT_EQ(s.lethalCount(), 0);
  EXPECT_GE(s.ctx->countKey("transform"), 1);
  s.setOdomInMap(0.0);
  s.cycles(3);
  EXPECT_EQ(s.at(5, 5), LETHAL_OBSTACLE);
  EXPECT_EQ(s.lethalCount(), 1);
}

TEST(FilterTransforms, ACycleWithoutTheTransformLeavesNoLastingHole)
{
  Stack s;
  s.setOdomInMap(0.0);
  s.publishMask();
  s.cycles(1);
  ASSERT_EQ(s.at(5, 5), LETHAL_OBSTACLE);
  // One cycle without the transform while a sensor redraws 3..8: the zone's cell is redrawn without it.
  s.dropTransform();
  s.window->armed = true;
  s.window->x0 = s.window->y0 = 3.0;
  s.window->x1 = s.window->y1 = 8.0;
  s.cycles(1);
  EXPECT_EQ(s.at(5, 5), FREE_SPACE);
  // The transform is back and the sensor's window is elsewhere: the zone comes back.
  s.setOdomInMap(0.0);
  s.window->x0 = s.window->y0 = 12.0;
  s.window->x1 = s.window->y1 = 15.0;
  s.cycles(2);
  EXPECT_EQ(s.at(5, 5), LETHAL_OBSTACLE);
  EXPECT_EQ(s.lethalCount(), 1);
}

TEST(FilterTransforms, AMovedTransformMovesTheZone)
{
  Stack s;
  s.setOdomInMap(0.0);
  s.publishMask();
  s.cycles(1);
  ASSERT_EQ(s.at(5, 5), LETHAL_OBSTACLE);
  // Localisation moves odom by 3 m in the map: the zone at map (5.5, 5.5) is at odom (2.5, 5.5).
  s.setOdomInMap(3.0);
  s.cycles(2);
  EXPECT_EQ(s.at(2, 5), LETHAL_OBSTACLE);
  EXPECT_EQ(s.at(5, 5), FREE_SPACE);
  EXPECT_EQ(s.lethalCount(), 1);
  // A new mask is cleared from where the old one was drawn: still exactly one zone cell.
  s.publishMask();
  s.setOdomInMap(-2.0);
  s.cycles(1);
  EXPECT_EQ(s.at(7, 5), LETHAL_OBSTACLE);
  EXPECT_EQ(s.lethalCount(), 1);
  // An unchanged transform asks for nothing more: the filter's extent is not redrawn every cycle.
  s.cycles(1);
  EXPECT_TRUE(s.lc.getUpdatedBounds().empty());
}
