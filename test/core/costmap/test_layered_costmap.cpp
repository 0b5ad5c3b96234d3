// Unit tests of LayeredCostmap and the Layer contract, with a test-only layer that records calls.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/costmap/costmap_layer.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;

namespace
{
using EventLog = std::vector<std::string>;
using Bounds = std::array<double, 4>;  // min_x, min_y, max_x, max_y

class RecordingLayer : public Layer
{
public:
  explicit RecordingLayer(std::shared_ptr<EventLog> log) : log_(std::move(log)) {}

  void updateBounds(double rx, double ry, double ryaw, double* min_x, double* min_y, double* max_x,
                    double* max_y) override
  {
    log_->push_back(getName() + ":bounds");
    seen_bounds.push_back({*min_x, *min_y, *max_x, *max_y});
    seen_pose.push_back({rx, ry, ryaw, 0.0});
    if (bounds_fn) bounds_fn(min_x, min_y, max_x, max_y);
  }
  void updateCosts(Costmap2D& master, int min_i, int min_j, int max_i, int max_j) override
  {
    log_->push_back(getName() + ":costs");
    seen_windows.push_back({min_i, min_j, max_i, max_j});
    seen_grids.push_back(&master);
    seen_origins.push_back({master.getOriginX(), master.getOriginY()});
    if (costs_fn) costs_fn(master, min_i, min_j, max_i, max_j);
  }
  void matchSize() override { log_->push_back(getName() + ":matchSize"); }
  void onFootprintChanged() override
  {
    log_->push_back(getName() + ":footprint");
    footprint_seen = getFootprint();
  }
  void setCurrent(bool c) { current_ = c; }

  std::function<void(double*, double*, double*, double*)> bounds_fn;
  std::function<void(Costmap2D&, int, int, int, int)> costs_fn;
  std::vector<Bounds> seen_bounds;
  std::vector<Bounds> seen_pose;
  std::vector<CellWindow> seen_windows;
  std::vector<const Costmap2D*> seen_grids;
  std::vector<std::pair<double, double>> seen_origins;
  Footprint footprint_seen;

  // What onInitialize() saw.
  int init_calls = 0;
  std::string init_name;
  bool init_had_context = false;
  bool init_had_parent = false;
  bool init_was_initialized = true;
  bool init_enabled = false;

protected:
  void onInitialize() override
  {
    log_->push_back(getName() + ":init");
    ++init_calls;
    init_name = name_;
    init_had_context = context_ != nullptr;
    init_had_parent = layered_costmap_ != nullptr;
    init_was_initialized = isInitialized();
    init_enabled = enabled();
  }

private:
  std::shared_ptr<EventLog> log_;
};

/// Bounds that cover everything.
void growToAll(double* a, double* b, double* c, double* d)
{
  *a = std::min(*a, -1e6);
  *b = std::min(*b, -1e6);
  *c = std::max(*c, 1e6);
  *d = std::max(*d, 1e6);
}

/// Bounds that grow to include the box [x0, x1] x [y0, y1].
std::function<void(double*, double*, double*, double*)> growTo(double x0, double y0, double x1, double y1)
{
  return [=](double* a, double* b, double* c, double* d)
  {
    *a = std::min(*a, x0);
    *b = std::min(*b, y0);
    *c = std::max(*c, x1);
    *d = std::max(*d, y1);
  };
}

struct Harness
{
  std::shared_ptr<EventLog> log = std::make_shared<EventLog>();
  LayeredCostmap lc;

  explicit Harness(bool rolling = false, bool track_unknown = false) : lc("map", rolling, track_unknown) {}

  std::shared_ptr<RecordingLayer> make(const std::string& name, ParamValue params = ParamValue::makeMap())
  {
    auto layer = std::make_shared<RecordingLayer>(log);
    layer->initialize(&lc, name, std::make_shared<FakeContext>(params));
    return layer;
  }
  std::shared_ptr<RecordingLayer> plugin(const std::string& name, ParamValue params = ParamValue::makeMap())
  {
    auto layer = make(name, std::move(params));
    lc.addPlugin(layer);
    return layer;
  }
  std::shared_ptr<RecordingLayer> filter(const std::string& name, ParamValue params = ParamValue::makeMap())
  {
    auto layer = make(name, std::move(params));
    lc.addFilter(layer);
    return layer;
  }
  /// The events of one layer, in order.
  std::vector<std::string> of(const std::string& name) const
  {
    std::vector<std::string> out;
    for (const auto& e : *log)
      if (e.rfind(name + ":", 0) == 0) out.push_back(e);
    return out;
  }
};

ParamValue disabledParams()
{
  ParamValue p = ParamValue::makeMap();
  p.set("enabled", ParamValue::makeBool(false));
  return p;
}
}  // namespace

// ---------------------------------------------------------------- initialization

TEST(LayeredCostmapContract, NothingIsCalledBeforeInitialize)
{
  auto log = std::make_shared<EventLog>();
  LayeredCostmap lc("map", false, false);
  auto layer = std::make_shared<RecordingLayer>(log);
  EXPECT_TRUE(log->empty());
  EXPECT_FALSE(layer->isInitialized());
  EXPECT_EQ(layer->getName(), "");
  EXPECT_TRUE(layer->getFootprint().empty());  // no parent yet

  layer->initialize(&lc, "a", std::make_shared<FakeContext>());
  EXPECT_EQ(*log, (EventLog{"a:init"}));
  EXPECT_EQ(layer->init_calls, 1);
  EXPECT_TRUE(layer->isInitialized());
  EXPECT_EQ(layer->getName(), "a");
}

TEST(LayeredCostmapContract, OnInitializeSeesNameContextParentAndEnabled)
{
  Harness h;
  auto a = h.make("a");
  EXPECT_EQ(a->init_name, "a");
  EXPECT_TRUE(a->init_had_context);
  EXPECT_TRUE(a->init_had_parent);
  EXPECT_FALSE(a->init_was_initialized);  // onInitialize ends initialize(), not the other way round
  EXPECT_TRUE(a->init_enabled);           // default enabled: true
  EXPECT_TRUE(a->enabled());

  auto b = h.make("b", disabledParams());
  EXPECT_FALSE(b->init_enabled);  // "enabled" is read before onInitialize()
  EXPECT_FALSE(b->enabled());
}

TEST(LayeredCostmapContract, FirstEventOfEveryLayerIsInit)
{
  Harness h;
  h.lc.resizeMap(5, 5, 1.0, 0, 0);
  auto a = h.plugin("a");
  auto f = h.filter("f");
  a->bounds_fn = growToAll;
  h.lc.resizeMap(6, 6, 1.0, 0, 0);
  h.lc.updateMap(0, 0, 0);
  h.lc.setFootprint(makeFootprintFromRadius(0.3));
  for (const std::string name : {"a", "f"})
  {
    const auto events = h.of(name);
    ASSERT_FALSE(events.empty());
    EXPECT_EQ(events.front(), name + ":init");
    EXPECT_EQ(std::count(events.begin(), events.end(), name + ":init"), 1);
  }
}

// ---------------------------------------------------------------- update order

TEST(LayeredCostmapUpdate, AllBoundsBeforeAnyCostsInConfiguredOrderFiltersLast)
{
  Harness h;
  h.lc.resizeMap(10, 10, 1.0, 0, 0);
  auto f1 = h.filter("f1");  // added first, but filters always run after plugins
  auto p1 = h.plugin("p1");
  auto p2 = h.plugin("p2");
  auto p3 = h.plugin("p3");
  auto f2 = h.filter("f2");
  p2->bounds_fn = growToAll;
  for (int cycle = 0; cycle < 3; ++cycle)
  {
    h.log->clear();
    h.lc.updateMap(1.0, 2.0, 0.5);
    const EventLog expected = {"p1:bounds", "p2:bounds", "p3:bounds", "f1:bounds", "f2:bounds",
                               "p1:costs",  "p2:costs",  "p3:costs",  "f1:costs",  "f2:costs"};
    EXPECT_EQ(*h.log, expected) << "cycle " << cycle;
  }
  // The robot pose reaches every layer.
  EXPECT_EQ(p3->seen_pose.back(), (Bounds{1.0, 2.0, 0.5, 0.0}));
  EXPECT_EQ(f2->seen_pose.back(), (Bounds{1.0, 2.0, 0.5, 0.0}));
  ASSERT_EQ(h.lc.getPlugins().size(), 3u);
  EXPECT_EQ(h.lc.getPlugins()[0]->getName(), "p1");
  EXPECT_EQ(h.lc.getPlugins()[2]->getName(), "p3");
  ASSERT_EQ(h.lc.getFilters().size(), 2u);
  EXPECT_EQ(h.lc.getFilters()[0]->getName(), "f1");
}

TEST(LayeredCostmapUpdate, DisabledLayersAreNeverCalled)
{
  Harness h;
  h.lc.resizeMap(10, 10, 1.0, 0, 0);
  auto a = h.plugin("a");
  auto b = h.plugin("b", disabledParams());
  auto c = h.plugin("c");
  auto f = h.filter("f");
  auto g = h.filter("g", disabledParams());
  a->bounds_fn = growToAll;
  c->setEnabled(false);
  b->bounds_fn = growToAll;
  for (int cycle = 0; cycle < 2; ++cycle)
    h.lc.updateMap(0, 0, 0);
  EXPECT_EQ(h.of("b"), EventLog{"b:init"});
  for (const std::string name : {"b", "c", "g"})
  {
    for (const auto& e : h.of(name))
    {
      EXPECT_NE(e, name + ":bounds");
      EXPECT_NE(e, name + ":costs");
    }
  }
  EXPECT_EQ(a->seen_windows.size(), 2u);
  EXPECT_EQ(f->seen_windows.size(), 2u);

  // Switched on again, it takes part from the next cycle.
  c->setEnabled(true);
  h.log->clear();
  h.lc.updateMap(0, 0, 0);
  EXPECT_EQ(*h.log, (EventLog{"a:bounds", "c:bounds", "f:bounds", "a:costs", "c:costs", "f:costs"}));
}

TEST(LayeredCostmapUpdate, FiltersRunOnACombinedCopyThatIsNotFedBack)
{
  Harness h;
  h.lc.resizeMap(6, 5, 1.0, 0, 0);
  auto writer = h.plugin("writer");
  auto reader = h.plugin("reader");
  auto plus = h.filter("plus");
  writer->bounds_fn = growToAll;
  writer->costs_fn = [](Costmap2D& m, int x0, int y0, int xn, int yn)
  {
    for (int y = y0; y < yn; ++y)
      for (int x = x0; x < xn; ++x)
        m.setCost(x, y, 10);
  };
  std::vector<int> reader_saw;  // what a later plugin (inflation-like) reads from the master grid
  reader->costs_fn = [&](Costmap2D& m, int x0, int y0, int xn, int yn)
  {
    int lo = 255, hi = 0;
    for (int y = y0; y < yn; ++y)
      for (int x = x0; x < xn; ++x)
      {
        lo = std::min<int>(lo, m.getCost(x, y));
        hi = std::max<int>(hi, m.getCost(x, y));
      }
    reader_saw.push_back(lo == hi ? lo : -1);
  };
  plus->costs_fn = [](Costmap2D& m, int x0, int y0, int xn, int yn)
  {
    for (int y = y0; y < yn; ++y)
      for (int x = x0; x < xn; ++x)
        m.setCost(x, y, static_cast<uint8_t>(m.getCost(x, y) + 1));
  };
  for (int cycle = 0; cycle < 4; ++cycle)
  {
    h.lc.updateMap(0, 0, 0);
    const Costmap2D& out = h.lc.getCostmap();
    for (unsigned int i = 0; i < out.cellCount(); ++i)
      ASSERT_EQ(out.getCost(i), 11) << "cycle " << cycle;
  }
  EXPECT_EQ(reader_saw, (std::vector<int>{10, 10, 10, 10}));
  // Plugins write into the primary grid, filters into the grid getCostmap() returns, and they differ.
  ASSERT_FALSE(writer->seen_grids.empty());
  ASSERT_FALSE(plus->seen_grids.empty());
  EXPECT_NE(writer->seen_grids.back(), plus->seen_grids.back());
  EXPECT_EQ(plus->seen_grids.back(), &h.lc.getCostmap());
}

TEST(LayeredCostmapUpdate, PartialWindowWithFiltersDoesNotAccumulate)
{
  Harness h;
  h.lc.resizeMap(8, 4, 1.0, 0, 0);
  auto writer = h.plugin("writer");
  auto plus = h.filter("plus");
  int cycle = 0;
  writer->bounds_fn = [&](double* a, double* b, double* c, double* d)
  {
    if (cycle == 0)
      growToAll(a, b, c, d);
    else
      growTo(2.5, 0.5, 4.5, 2.5)(a, b, c, d);  // cells [2, 5) x [0, 3)
  };
  writer->costs_fn = [](Costmap2D& m, int x0, int y0, int xn, int yn)
  {
    for (int y = y0; y < yn; ++y)
      for (int x = x0; x < xn; ++x)
        m.setCost(x, y, 50);
  };
  plus->costs_fn = [](Costmap2D& m, int x0, int y0, int xn, int yn)
  {
    for (int y = y0; y < yn; ++y)
      for (int x = x0; x < xn; ++x)
        m.setCost(x, y, static_cast<uint8_t>(m.getCost(x, y) + 1));
  };
  for (cycle = 0; cycle < 5; ++cycle)
  {
    h.lc.updateMap(0, 0, 0);
    if (cycle > 0)
    {
      EXPECT_EQ(h.lc.getUpdatedBounds().x0, 2);
      EXPECT_EQ(h.lc.getUpdatedBounds().xn, 5);
      EXPECT_EQ(h.lc.getUpdatedBounds().yn, 3);
    }
    for (unsigned int i = 0; i < h.lc.getCostmap().cellCount(); ++i)
      ASSERT_EQ(h.lc.getCostmap().getCost(i), 51);
  }
}

TEST(LayeredCostmapUpdate, NoFiltersMeansPluginsWriteTheResult)
{
  Harness h;
  h.lc.resizeMap(4, 4, 1.0, 0, 0);
  auto a = h.plugin("a");
  a->bounds_fn = growToAll;
  h.lc.updateMap(0, 0, 0);
  ASSERT_EQ(a->seen_grids.size(), 1u);
  EXPECT_EQ(a->seen_grids[0], &h.lc.getCostmap());
}

// ---------------------------------------------------------------- bounds

TEST(LayeredCostmapBounds, EmptyBeforeFirstUpdate)
{
  Harness h;
  h.lc.resizeMap(10, 10, 1.0, 0, 0);
  EXPECT_TRUE(h.lc.getUpdatedBounds().empty());
  EXPECT_FALSE(h.lc.isInitialized());
}

TEST(LayeredCostmapBounds, UpdatedWindowFromWorldBounds)
{
  Harness h;
  h.lc.resizeMap(10, 10, 1.0, 0, 0);
  auto a = h.plugin("a");
  auto b = h.plugin("b");
  a->bounds_fn = growTo(1.2, 0.5, 3.7, 2.2);
  // The first layer receives "nothing yet" bounds.
  h.lc.getCostmap().fillWindow(0, 0, 10, 10, 99);
  h.lc.updateMap(0, 0, 0);
  ASSERT_EQ(a->seen_bounds.size(), 1u);
  EXPECT_EQ(a->seen_bounds[0][0], std::numeric_limits<double>::max());
  EXPECT_EQ(a->seen_bounds[0][2], std::numeric_limits<double>::lowest());
  EXPECT_EQ(b->seen_bounds[0], (Bounds{1.2, 0.5, 3.7, 2.2}));  // the next layer sees what a asked for

  const CellWindow w = h.lc.getUpdatedBounds();
  EXPECT_EQ(w.x0, 1);
  EXPECT_EQ(w.y0, 0);
  EXPECT_EQ(w.xn, 4);
  EXPECT_EQ(w.yn, 3);
  EXPECT_TRUE(h.lc.isInitialized());
  ASSERT_EQ(b->seen_windows.size(), 1u);
  EXPECT_EQ(b->seen_windows[0].x0, 1);
  EXPECT_EQ(b->seen_windows[0].y0, 0);
  EXPECT_EQ(b->seen_windows[0].xn, 4);
  EXPECT_EQ(b->seen_windows[0].yn, 3);
  // The window was reset to the default before the layers wrote; the rest kept its cells.
  for (unsigned int y = 0; y < 10; ++y)
    for (unsigned int x = 0; x < 10; ++x)
    {
      const bool inside = x >= 1 && x < 4 && y < 3;
      EXPECT_EQ(h.lc.getCostmap().getCost(x, y), inside ? FREE_SPACE : 99) << x << "," << y;
    }
}

TEST(LayeredCostmapBounds, ResetUsesUnknownWhenTrackingUnknown)
{
  Harness h(false, true);
  h.lc.resizeMap(5, 5, 0.5, -1.0, -1.0);
  EXPECT_EQ(h.lc.getCostmap().getCost(0, 0), NO_INFORMATION);
  auto a = h.plugin("a");
  a->bounds_fn = growTo(-1.0, -1.0, -0.1, -0.1);  // cells [0, 2) x [0, 2)
  h.lc.getCostmap().fillWindow(0, 0, 5, 5, 7);
  h.lc.updateMap(0, 0, 0);
  const CellWindow w = h.lc.getUpdatedBounds();
  EXPECT_EQ(w.x0, 0);
  EXPECT_EQ(w.y0, 0);
  EXPECT_EQ(w.xn, 2);
  EXPECT_EQ(w.yn, 2);
  for (unsigned int y = 0; y < 5; ++y)
    for (unsigned int x = 0; x < 5; ++x)
      EXPECT_EQ(h.lc.getCostmap().getCost(x, y), (x < 2 && y < 2) ? NO_INFORMATION : 7);
}

TEST(LayeredCostmapBounds, BoundsAreClampedToTheMap)
{
  Harness h;
  h.lc.resizeMap(10, 8, 0.5, 2.0, 3.0);
  auto a = h.plugin("a");
  a->bounds_fn = growTo(-100.0, 3.6, 100.0, 1000.0);
  h.lc.updateMap(0, 0, 0);
  const CellWindow w = h.lc.getUpdatedBounds();
  EXPECT_EQ(w.x0, 0);
  EXPECT_EQ(w.y0, 1);
  EXPECT_EQ(w.xn, 10);
  EXPECT_EQ(w.yn, 8);
}

TEST(LayeredCostmapBounds, NobodyAskingMeansNoUpdate)
{
  Harness h;
  h.lc.resizeMap(10, 10, 1.0, 0, 0);
  auto a = h.plugin("a");  // leaves the bounds as they are
  h.lc.updateMap(0, 0, 0);
  EXPECT_TRUE(h.lc.getUpdatedBounds().empty());
  EXPECT_TRUE(a->seen_windows.empty());
  EXPECT_FALSE(h.lc.isInitialized());
  // Then a full update, then nothing again: the window is emptied again.
  a->bounds_fn = growToAll;
  h.lc.updateMap(0, 0, 0);
  EXPECT_FALSE(h.lc.getUpdatedBounds().empty());
  a->bounds_fn = nullptr;
  h.lc.updateMap(0, 0, 0);
  EXPECT_TRUE(h.lc.getUpdatedBounds().empty());
}

TEST(LayeredCostmapBounds, ShrinkingBoundsIsIgnored)
{
  Harness h;
  h.lc.resizeMap(10, 10, 1.0, 0, 0);
  auto a = h.plugin("a");
  auto shrinker = h.plugin("shrinker");
  auto c = h.plugin("c");
  a->bounds_fn = growTo(2.0, 2.0, 5.0, 5.0);
  shrinker->bounds_fn = [](double* x0, double* y0, double* x1, double* y1)
  {
    *x0 = 3.0;
    *y0 = 4.0;
    *x1 = 4.0;
    *y1 = 4.5;
  };
  h.lc.updateMap(0, 0, 0);
  ASSERT_EQ(c->seen_bounds.size(), 1u);
  EXPECT_EQ(c->seen_bounds[0], (Bounds{2.0, 2.0, 5.0, 5.0}));
  const CellWindow w = h.lc.getUpdatedBounds();
  EXPECT_EQ(w.x0, 2);
  EXPECT_EQ(w.y0, 2);
  EXPECT_EQ(w.xn, 6);
  EXPECT_EQ(w.yn, 6);

  // Shrinking one side while growing another never loses the earlier bounds.
  shrinker->bounds_fn = [](double* x0, double*, double* x1, double*)
  {
    *x0 = 3.0;
    *x1 = 8.0;
  };
  h.lc.updateMap(0, 0, 0);
  ASSERT_EQ(c->seen_bounds.size(), 2u);
  EXPECT_LE(c->seen_bounds[1][0], 2.0);
  EXPECT_LE(c->seen_bounds[1][1], 2.0);
  EXPECT_GE(c->seen_bounds[1][2], 5.0);
  EXPECT_GE(c->seen_bounds[1][3], 5.0);
}

// ---------------------------------------------------------------- rolling window

TEST(LayeredCostmapRolling, OriginFollowsTheRobot)
{
  Harness h(true, false);
  h.lc.resizeMap(10, 8, 0.5, 0.0, 0.0);  // 5 m x 4 m
  EXPECT_TRUE(h.lc.isRolling());
  auto a = h.plugin("a");
  a->bounds_fn = growToAll;
  const std::vector<std::pair<double, double>> poses = {{10.3, 7.6}, {10.3, 7.6}, {11.3, 7.6}, {-4.2, 3.05}};
  double ox = 0.0, oy = 0.0;
  for (const auto& p : poses)
  {
    h.lc.updateMap(p.first, p.second, 0.0);
    // Requested origin: robot minus half the size, snapped down onto the previous grid's cells.
    ox += std::floor((p.first - 2.5 - ox) / 0.5) * 0.5;
    oy += std::floor((p.second - 2.0 - oy) / 0.5) * 0.5;
    EXPECT_NEAR(h.lc.getCostmap().getOriginX(), ox, 1e-9);
    EXPECT_NEAR(h.lc.getCostmap().getOriginY(), oy, 1e-9);
    // The robot is in the middle cell (within one cell).
    unsigned int mx, my;
    ASSERT_TRUE(h.lc.getCostmap().worldToMap(p.first, p.second, mx, my));
    EXPECT_NEAR(static_cast<double>(mx), 5.0, 1.0);
    EXPECT_NEAR(static_cast<double>(my), 4.0, 1.0);
    // Layers already see the moved grid.
    EXPECT_NEAR(a->seen_origins.back().first, ox, 1e-9);
    EXPECT_NEAR(a->seen_origins.back().second, oy, 1e-9);
  }
  EXPECT_NEAR(h.lc.getCostmap().getOriginX(), -7.0, 1e-9);
  EXPECT_NEAR(h.lc.getCostmap().getOriginY(), 1.0, 1e-9);
}

TEST(LayeredCostmapRolling, KeepsOverlappingCellsAndMovesFilterGridToo)
{
  Harness h(true, false);
  h.lc.resizeMap(10, 10, 1.0, 0.0, 0.0);
  auto f = h.filter("f");         // a filter means getCostmap() is the combined copy
  h.lc.updateMap(5.0, 5.0, 0.0);  // origin stays (0, 0)
  EXPECT_DOUBLE_EQ(h.lc.getCostmap().getOriginX(), 0.0);
  h.lc.getCostmap().setCost(6, 3, 123);
  h.lc.updateMap(7.0, 4.0, 0.0);  // two cells right, one down
  EXPECT_DOUBLE_EQ(h.lc.getCostmap().getOriginX(), 2.0);
  EXPECT_DOUBLE_EQ(h.lc.getCostmap().getOriginY(), -1.0);
  EXPECT_EQ(h.lc.getCostmap().getCost(4, 4), 123);
  EXPECT_EQ(h.lc.getCostmap().getCost(6, 3), 0);
  // The primary grid moved as well: a plugin added now sees the same origin.
  auto p = h.plugin("p");
  p->bounds_fn = growToAll;
  h.lc.updateMap(7.0, 4.0, 0.0);
  ASSERT_EQ(p->seen_origins.size(), 1u);
  EXPECT_DOUBLE_EQ(p->seen_origins[0].first, 2.0);
  EXPECT_DOUBLE_EQ(p->seen_origins[0].second, -1.0);
}

TEST(LayeredCostmapRolling, StaticMapDoesNotMove)
{
  Harness h(false, false);
  h.lc.resizeMap(10, 10, 1.0, 1.0, 2.0);
  auto a = h.plugin("a");
  a->bounds_fn = growToAll;
  h.lc.updateMap(100.0, -50.0, 0.0);
  EXPECT_DOUBLE_EQ(h.lc.getCostmap().getOriginX(), 1.0);
  EXPECT_DOUBLE_EQ(h.lc.getCostmap().getOriginY(), 2.0);
}

// ---------------------------------------------------------------- resize, footprint, current

TEST(LayeredCostmapMisc, ResizeMapCallsMatchSizeOnEveryLayer)
{
  Harness h(false, true);
  auto a = h.plugin("a");
  auto b = h.plugin("b", disabledParams());
  auto f = h.filter("f");
  h.log->clear();
  h.lc.resizeMap(7, 3, 0.1, -0.3, 0.4, true);
  EXPECT_EQ(*h.log, (EventLog{"a:matchSize", "b:matchSize", "f:matchSize"}));
  const Costmap2D& g = h.lc.getCostmap();
  EXPECT_EQ(g.getSizeInCellsX(), 7u);
  EXPECT_EQ(g.getSizeInCellsY(), 3u);
  EXPECT_DOUBLE_EQ(g.getResolution(), 0.1);
  EXPECT_DOUBLE_EQ(g.getOriginX(), -0.3);
  EXPECT_DOUBLE_EQ(g.getOriginY(), 0.4);
  EXPECT_TRUE(h.lc.isSizeLocked());
  EXPECT_TRUE(h.lc.isTrackingUnknown());
  for (unsigned int i = 0; i < g.cellCount(); ++i)
    EXPECT_EQ(g.getCost(i), NO_INFORMATION);
  h.lc.resizeMap(2, 2, 1.0, 0, 0);
  EXPECT_FALSE(h.lc.isSizeLocked());
}

TEST(LayeredCostmapMisc, ResizeMatchesCostmapLayerGrid)
{
  class OwnGridLayer : public CostmapLayer
  {
  public:
    void updateBounds(double, double, double, double*, double*, double*, double*) override {}
    void updateCosts(Costmap2D&, int, int, int, int) override {}
  };
  LayeredCostmap lc("map", false, false);
  auto layer = std::make_shared<OwnGridLayer>();
  layer->initialize(&lc, "own", std::make_shared<FakeContext>());
  lc.addPlugin(layer);
  lc.resizeMap(9, 4, 0.25, 1.0, -1.0);
  EXPECT_EQ(layer->costmap().getSizeInCellsX(), 9u);
  EXPECT_EQ(layer->costmap().getSizeInCellsY(), 4u);
  EXPECT_DOUBLE_EQ(layer->costmap().getResolution(), 0.25);
  EXPECT_DOUBLE_EQ(layer->costmap().getOriginY(), -1.0);
}

TEST(LayeredCostmapMisc, SetFootprintNotifiesLayersAndComputesRadii)
{
  Harness h;
  auto a = h.plugin("a");
  auto f = h.filter("f");
  h.log->clear();
  const Footprint square = {{0.5, 0.5}, {0.5, -0.5}, {-0.5, -0.5}, {-0.5, 0.5}};
  h.lc.setFootprint(square);
  EXPECT_EQ(*h.log, (EventLog{"a:footprint", "f:footprint"}));
  EXPECT_NEAR(h.lc.getInscribedRadius(), 0.5, 1e-12);
  EXPECT_NEAR(h.lc.getCircumscribedRadius(), std::sqrt(0.5), 1e-12);
  ASSERT_EQ(a->footprint_seen.size(), 4u);  // the layer already sees the new footprint
  EXPECT_EQ(a->getFootprint().size(), 4u);
  EXPECT_DOUBLE_EQ(a->getFootprint()[1].y(), -0.5);

  const Footprint rect = {{0.7, 0.2}, {0.7, -0.2}, {-0.3, -0.2}, {-0.3, 0.2}};
  h.lc.setFootprint(rect);
  EXPECT_NEAR(h.lc.getInscribedRadius(), 0.2, 1e-12);
  EXPECT_NEAR(h.lc.getCircumscribedRadius(), std::hypot(0.7, 0.2), 1e-12);
  EXPECT_EQ(std::count(h.log->begin(), h.log->end(), "a:footprint"), 2);

  // A triangle whose nearest edge is closer than any vertex.
  const Footprint tri = {{1.0, -1.0}, {1.0, 1.0}, {-2.0, 0.0}};
  h.lc.setFootprint(tri);
  EXPECT_NEAR(h.lc.getInscribedRadius(), 2.0 / std::sqrt(10.0), 1e-12);  // edge (1,1)-(-2,0)
  EXPECT_NEAR(h.lc.getCircumscribedRadius(), 2.0, 1e-12);
}

TEST(LayeredCostmapMisc, IsCurrentConsidersEnabledLayersAndFilters)
{
  Harness h;
  auto a = h.plugin("a");
  auto b = h.plugin("b");
  auto f = h.filter("f");
  EXPECT_TRUE(h.lc.isCurrent());
  b->setCurrent(false);
  EXPECT_FALSE(h.lc.isCurrent());
  EXPECT_FALSE(b->isCurrent());
  b->setEnabled(false);
  EXPECT_TRUE(h.lc.isCurrent());  // a disabled layer does not count
  f->setCurrent(false);
  EXPECT_FALSE(h.lc.isCurrent());
  f->setCurrent(true);
  EXPECT_TRUE(h.lc.isCurrent());
}

TEST(LayeredCostmapMisc, FindLayerAndEmptyCostmap)
{
  Harness h;
  h.lc.resizeMap(3, 3, 1.0, 0, 0);
  EXPECT_EQ(h.lc.findLayer("a"), nullptr);
  h.lc.updateMap(0, 0, 0);  // no layers: nothing happens
  EXPECT_TRUE(h.lc.getUpdatedBounds().empty());
  auto a = h.plugin("a");
  auto f = h.filter("f");
  EXPECT_EQ(h.lc.findLayer("a"), a);
  EXPECT_EQ(h.lc.findLayer("f"), f);
  EXPECT_EQ(h.lc.findLayer("x"), nullptr);
  EXPECT_EQ(h.lc.getGlobalFrameID(), "map");
  // Adding a filter after resizing keeps the result grid's geometry.
  EXPECT_EQ(h.lc.getCostmap().getSizeInCellsX(), 3u);
}

// ---------------------------------------------------------------- a master owned by another host
// (move_base's costmap_2d master, viewed by LayerBridge)

TEST(Costmap2DView, WritesGoToTheViewedMemoryAndCopiesOwnTheirs)
{
  std::vector<uint8_t> outside(6 * 4, 7);
  Costmap2D view;
  view.viewMemory(outside.data(), 6, 4, 0.5, -1.0, 2.0);
  EXPECT_TRUE(view.isView());
  EXPECT_EQ(view.data(), outside.data());
  EXPECT_EQ(view.cellCount(), 24u);
  EXPECT_EQ(view.getCost(5, 3), 7);
  view.setCost(2, 1, 99);
  EXPECT_EQ(outside[1 * 6 + 2], 99);  // row-major, row 0 = lowest y
  view.fillWindow(0, 3, 6, 4, 5);
  for (int x = 0; x < 6; ++x)
    EXPECT_EQ(outside[3 * 6 + x], 5);

  Costmap2D copy = view;  // a copy is independent of the viewed memory
  EXPECT_FALSE(copy.isView());
  EXPECT_NE(copy.data(), outside.data());
  copy.setCost(0, 0, 1);
  EXPECT_EQ(outside[0], 7);
  EXPECT_EQ(copy.getCost(2, 1), 99);

  Costmap2D moved = std::move(view);  // a move keeps viewing the same memory
  EXPECT_TRUE(moved.isView());
  EXPECT_EQ(moved.data(), outside.data());

  moved.resizeMap(3, 3, 0.5, 0.0, 0.0);  // a resize owns its cells again, the viewed memory is left alone
  EXPECT_FALSE(moved.isView());
  EXPECT_NE(moved.data(), outside.data());
  EXPECT_EQ(outside[1 * 6 + 2], 99);
}

TEST(Costmap2DView, UpdateOriginShiftsTheViewedCellsInPlace)
{
  std::vector<uint8_t> outside(4 * 3, 0);
  for (std::size_t k = 0; k < outside.size(); ++k)
    outside[k] = static_cast<uint8_t>(k + 1);
  Costmap2D view;
  view.setDefaultValue(255);
  view.viewMemory(outside.data(), 4, 3, 1.0, 0.0, 0.0);
  view.updateOrigin(1.0, 1.0);  // one cell right and up: old (1,1) becomes (0,0)
  EXPECT_EQ(view.data(), outside.data());
  EXPECT_EQ(outside[0], 1 * 4 + 1 + 1);
  EXPECT_EQ(outside[1], 1 * 4 + 2 + 1);
  EXPECT_EQ(outside[3], 255);          // column 3 is new
  EXPECT_EQ(outside[2 * 4 + 0], 255);  // row 2 is new
  EXPECT_DOUBLE_EQ(view.getOriginX(), 1.0);
}

TEST(LayeredCostmapView, LayersMatchSizeOnlyWhenTheGeometryChanges)
{
  Harness h;
  auto a = h.plugin("a");
  std::vector<uint8_t> first(10 * 8, 0), second(20 * 8, 0);
  h.log->clear();
  h.lc.viewMaster(first.data(), 10, 8, 0.1, 0.0, 0.0);
  EXPECT_EQ(h.of("a"), std::vector<std::string>({"a:matchSize"}));
  EXPECT_EQ(h.lc.getCostmap().data(), first.data());
  h.lc.viewMaster(first.data(), 10, 8, 0.1, 0.0, 0.0);  // the same: nothing to match
  EXPECT_EQ(h.of("a").size(), 1u);
  h.lc.viewMaster(second.data(), 20, 8, 0.1, 0.0, 0.0);
  EXPECT_EQ(h.of("a").size(), 2u);
  EXPECT_EQ(h.lc.getCostmap().data(), second.data());
  h.lc.viewMaster(second.data(), 20, 8, 0.1, 1.0, 0.0);  // not rolling: a new origin is a resize
  EXPECT_EQ(h.of("a").size(), 3u);

  Harness rolling(true);
  auto b = rolling.plugin("b");
  rolling.lc.viewMaster(first.data(), 10, 8, 0.1, 0.0, 0.0);
  rolling.log->clear();
  rolling.lc.viewMaster(first.data(), 10, 8, 0.1, 0.3, -0.2);  // a rolling window moving: no resize
  EXPECT_TRUE(rolling.of("b").empty());
  EXPECT_DOUBLE_EQ(rolling.lc.getCostmap().getOriginX(), 0.3);
}

TEST(LayeredCostmapView, ResizeGoesToTheHostWhenItOwnsTheMaster)
{
  Harness h;
  auto a = h.plugin("a");
  std::vector<uint8_t> cells(4 * 4, 0);
  h.lc.viewMaster(cells.data(), 4, 4, 1.0, 0.0, 0.0);
  std::vector<double> asked;
  bool locked = false;
  h.lc.setResizeHandler(
      [&](unsigned int sx, unsigned int sy, double res, double ox, double oy, bool size_locked)
      {
        asked = {static_cast<double>(sx), static_cast<double>(sy), res, ox, oy};
        locked = size_locked;
      });
  h.lc.resizeMap(30, 20, 0.05, -1.0, -2.0, true);
  EXPECT_EQ(asked, std::vector<double>({30, 20, 0.05, -1.0, -2.0}));
  EXPECT_TRUE(locked);
  // The master is still the host's until the host views its resized grid.
  EXPECT_EQ(h.lc.getCostmap().data(), cells.data());
  EXPECT_EQ(h.lc.getCostmap().getSizeInCellsX(), 4u);
}

TEST(LayeredCostmapView, AFullUpdateRequestIsTakenOnce)
{
  Harness h;
  EXPECT_FALSE(h.lc.takeFullUpdateRequest());
  h.lc.requestFullUpdate();
  EXPECT_TRUE(h.lc.takeFullUpdateRequest());
  EXPECT_FALSE(h.lc.takeFullUpdateRequest());
}
