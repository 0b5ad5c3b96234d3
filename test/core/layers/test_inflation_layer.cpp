#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/costmap/costmap_layer.hpp"
#include "costmap_layers/core/layers/inflation_layer.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/kernels/simd_targets.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;

namespace
{
/// The layer below: its own grid, copied into the master (unknown included) inside the window. Every
/// change asks for its cell to be updated.
class MarkLayer : public CostmapLayer
{
public:
  void set(unsigned x, unsigned y, uint8_t cost)
  {
    costmap_.setCost(x, y, cost);
    double wx, wy;
    costmap_.mapToWorld(x, y, wx, wy);
    addExtraBounds(wx, wy, wx, wy);
  }
  void fillAll(uint8_t cost)
  {
    costmap_.fillWindow(0, 0, costmap_.getSizeInCellsX(), costmap_.getSizeInCellsY(), cost);
    addExtraBounds(costmap_.getOriginX(), costmap_.getOriginY(),
                   costmap_.getOriginX() + costmap_.getSizeInMetersX() - 1e-9,
                   costmap_.getOriginY() + costmap_.getSizeInMetersY() - 1e-9);
  }
  void updateBounds(double, double, double, double* min_x, double* min_y, double* max_x, double* max_y) override
  {
    useExtraBounds(min_x, min_y, max_x, max_y);
  }
  void updateCosts(Costmap2D& master, int min_i, int min_j, int max_i, int max_j) override
  {
    updateWithTrueOverwrite(master, min_i, min_j, max_i, max_j);
  }
};

/// A layer doing whatever the test says, with the whole map as its bounds.
class FunctionLayer : public Layer
{
public:
  std::function<void(Costmap2D&, int, int, int, int)> fn;
  void updateBounds(double, double, double, double* min_x, double* min_y, double* max_x, double* max_y) override
  {
    *min_x = *min_y = -std::numeric_limits<float>::max();
    *max_x = *max_y = std::numeric_limits<float>::max();
  }
  void updateCosts(Costmap2D& master, int min_i, int min_j, int max_i, int max_j) override
  {
    if (fn) fn(master, min_i, min_j, max_i, max_j);
  }
};

Footprint square(double half)
{
  return {{-half, -half}, {half, -half}, {half, half}, {-half, half}};
}

ParamValue inflationParams(double radius, double factor, bool inflate_unknown = false, bool around = false)
{
  ParamValue p = ParamValue::makeMap();
  p.set("inflation_radius", ParamValue::makeDouble(radius));
  p.set("cost_scaling_factor", ParamValue::makeDouble(factor));
  p.set("inflate_unknown", ParamValue::makeBool(inflate_unknown));
  p.set("inflate_around_unknown", ParamValue::makeBool(around));
  return p;
}

/// A costmap with a MarkLayer below an InflationLayer.
struct Rig
{
  Rig(unsigned w, unsigned h, double res, const ParamValue& params, double inscribed, bool track_unknown = false,
      uint8_t fill = FREE_SPACE)
      : lc("map", false, track_unknown)
  {
    lc.resizeMap(w, h, res, 0.0, 0.0);
    ctx = std::make_shared<FakeContext>(params);
    marks = std::make_shared<MarkLayer>();
    marks->initialize(&lc, "marks", std::make_shared<FakeContext>());
    marks->matchSize();
    if (fill != FREE_SPACE) marks->fillAll(fill);
    lc.addPlugin(marks);
    inflation = std::make_shared<InflationLayer>();
    inflation->initialize(&lc, "inflation", ctx);
    ctx->bind(*inflation);
    lc.addPlugin(inflation);
    lc.setFootprint(square(inscribed));
  }
  void update() { lc.updateMap(0, 0, 0); }
  uint8_t at(unsigned x, unsigned y) const { return lc.getCostmap().getCost(x, y); }

  LayeredCostmap lc;
  std::shared_ptr<FakeContext> ctx;
  std::shared_ptr<MarkLayer> marks;
  std::shared_ptr<InflationLayer> inflation;
};

/// The layer's contract computed the slow way: for each cell of the window, the nearest source by
/// exhaustive search over every source of the grid, the formula, and the write rule.
void naiveInflate(const Costmap2D& base, Costmap2D& out, const InflationConfig& cfg, double inscribed, int x0, int y0,
                  int x1, int y1)
{
  const int w = static_cast<int>(base.getSizeInCellsX()), h = static_cast<int>(base.getSizeInCellsY());
  const double res = base.getResolution();
  const int cap = static_cast<int>(std::ceil(cfg.inflation_radius / res));
  if (cap <= 0) return;
  auto is_source = [&](uint8_t c)
  { return c == LETHAL_OBSTACLE || (cfg.inflate_around_unknown && c == NO_INFORMATION); };
  std::vector<std::pair<long, long>> sources;
  for (int sy = 0; sy < h; ++sy)
    for (int sx = 0; sx < w; ++sx)
      if (is_source(base.getCost(static_cast<unsigned>(sx), static_cast<unsigned>(sy)))) sources.emplace_back(sx, sy);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
    {
      long best = std::numeric_limits<long>::max();
      for (const auto& [sx, sy] : sources)
        best = std::min(best, (sx - x) * (sx - x) + (sy - y) * (sy - y));
      if (best > static_cast<long>(cap) * cap) continue;
      const uint8_t cost = inflationCost(std::sqrt(static_cast<double>(best)), res, inscribed, cfg.cost_scaling_factor);
      const uint8_t old_cost = base.getCost(static_cast<unsigned>(x), static_cast<unsigned>(y));
      uint8_t result;
      if (old_cost == NO_INFORMATION)
        result = (cfg.inflate_unknown ? cost > 0 : cost >= INSCRIBED_INFLATED_OBSTACLE) ? cost : old_cost;
      else
        result = std::max(old_cost, cost);
      out.setCost(static_cast<unsigned>(x), static_cast<unsigned>(y), result);
    }
}

/// A full recomputation of the whole map from the base grid.
Costmap2D naiveFull(const Costmap2D& base, const InflationConfig& cfg, double inscribed)
{
  Costmap2D out = base;
  naiveInflate(base, out, cfg, inscribed, 0, 0, static_cast<int>(base.getSizeInCellsX()),
               static_cast<int>(base.getSizeInCellsY()));
  return out;
}

::testing::AssertionResult sameCells(const Costmap2D& a, const Costmap2D& b)
{
  if (a.getSizeInCellsX() != b.getSizeInCellsX() || a.getSizeInCellsY() != b.getSizeInCellsY())
    return ::testing::AssertionFailure() << "sizes differ";
  for (unsigned y = 0; y < a.getSizeInCellsY(); ++y)
    for (unsigned x = 0; x < a.getSizeInCellsX(); ++x)
      if (a.getCost(x, y) != b.getCost(x, y))
        return ::testing::AssertionFailure()
               << "cell (" << x << ", " << y << "): " << int(a.getCost(x, y)) << " vs " << int(b.getCost(x, y));
  return ::testing::AssertionSuccess();
}
}  // namespace

TEST(InflationCost, Formula)
{
  EXPECT_EQ(inflationCost(0.0, 1.0, 2.1, 10.0), LETHAL_OBSTACLE);
  EXPECT_EQ(inflationCost(2.0, 1.0, 2.1, 10.0), INSCRIBED_INFLATED_OBSTACLE);
  // 3 cells of 1 m: 252 e^(-1 (3 - 2.1)) = 252 * 0.40657 = 102.46, truncated as costmap_2d does.
  EXPECT_EQ(inflationCost(3.0, 1.0, 2.1, 1.0), 102);
  EXPECT_EQ(inflationCost(4.0, 0.05, 0.22, 10.0), INSCRIBED_INFLATED_OBSTACLE);  // 0.2 m <= 0.22 m
  // 10 cells of 0.05 m = 0.5 m: 252 e^(-10 (0.5 - 0.22)) = 252 * 0.060810 = 15.32 -> 15.
  EXPECT_EQ(inflationCost(10.0, 0.05, 0.22, 10.0), 15);
  // Just outside the inscribed radius the cost falls below 253: 252 e^(-10 * 0.03) = 186.69 -> 186.
  EXPECT_EQ(inflationCost(5.0, 0.05, 0.22, 10.0), 186);
}

TEST(InflationConfig, DefaultsAndValidation)
{
  const ParamValue empty = ParamValue::makeMap();
  const InflationConfig d = parseInflationConfig(ParamReader(empty, "inflation"));
  EXPECT_DOUBLE_EQ(d.inflation_radius, 0.55);
  EXPECT_DOUBLE_EQ(d.cost_scaling_factor, 10.0);
  EXPECT_FALSE(d.inflate_unknown);
  EXPECT_FALSE(d.inflate_around_unknown);

  ParamValue p = inflationParams(1.5, 3.0, true, true);
  const InflationConfig c = parseInflationConfig(ParamReader(p, "inflation"));
  EXPECT_DOUBLE_EQ(c.inflation_radius, 1.5);
  EXPECT_DOUBLE_EQ(c.cost_scaling_factor, 3.0);
  EXPECT_TRUE(c.inflate_unknown);
  EXPECT_TRUE(c.inflate_around_unknown);

  for (const char* name : {"inflation_radius", "cost_scaling_factor"})
  {
    ParamValue bad = ParamValue::makeMap();
    bad.set(name, ParamValue::makeDouble(-1.0));
    EXPECT_THROW(parseInflationConfig(ParamReader(bad, "inflation")), std::invalid_argument) << name;
    bad.set(name, ParamValue::makeString("big"));
    EXPECT_THROW(parseInflationConfig(ParamReader(bad, "inflation")), std::invalid_argument) << name;
  }
  ParamValue bad = ParamValue::makeMap();
  bad.set("inflate_unknown", ParamValue::makeString("yes"));
  EXPECT_THROW(parseInflationConfig(ParamReader(bad, "inflation")), std::invalid_argument);
}

TEST(InflationLayer, ReadsParametersAndInscribedRadius)
{
  Rig rig(10, 10, 1.0, inflationParams(4.1, 1.0), 2.1);
  EXPECT_DOUBLE_EQ(rig.inflation->inscribedRadius(), 2.1);
  EXPECT_EQ(rig.inflation->cellInflationRadius(), 5);
  rig.lc.setFootprint(square(1.0));
  EXPECT_DOUBLE_EQ(rig.inflation->inscribedRadius(), 1.0);
  rig.lc.resizeMap(20, 20, 0.5, 0, 0);
  EXPECT_EQ(rig.inflation->cellInflationRadius(), 9);
}

// costmap_2d's testCostFunctionCorrectness-style case: an obstacle at (0,0) on a 1 m grid.
TEST(InflationLayer, ObstacleAtOrigin)
{
  Rig rig(10, 10, 1.0, inflationParams(4.1, 10.0), 2.1);
  rig.marks->set(0, 0, LETHAL_OBSTACLE);
  rig.update();
  EXPECT_EQ(rig.at(0, 0), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.at(1, 0), INSCRIBED_INFLATED_OBSTACLE);
  EXPECT_EQ(rig.at(2, 0), INSCRIBED_INFLATED_OBSTACLE);
  EXPECT_EQ(rig.at(1, 1), INSCRIBED_INFLATED_OBSTACLE);
  EXPECT_LT(rig.at(3, 0), INSCRIBED_INFLATED_OBSTACLE);
  EXPECT_LT(rig.at(2, 1), INSCRIBED_INFLATED_OBSTACLE);
  EXPECT_EQ(rig.at(3, 0), inflationCost(3.0, 1.0, 2.1, 10.0));
  EXPECT_EQ(rig.at(2, 1), inflationCost(std::sqrt(5.0), 1.0, 2.1, 10.0));
  for (unsigned y = 0; y < 10; ++y)
    for (unsigned x = 0; x < 10; ++x)
    {
      EXPECT_NE(rig.at(x, y), NO_INFORMATION);
      const double d = std::hypot(double(x), double(y));
      EXPECT_EQ(rig.at(x, y), d <= 5.0 ? inflationCost(d, 1.0, 2.1, 10.0) : FREE_SPACE) << x << "," << y;
    }
}

TEST(InflationLayer, LargerRangeFollowsFormulaExactly)
{
  for (double factor : {10.0, 1.0, 0.3})
  {
    Rig rig(100, 100, 1.0, inflationParams(10.5, factor), 5.0);
    rig.marks->set(50, 50, LETHAL_OBSTACLE);
    rig.update();
    ASSERT_EQ(rig.inflation->cellInflationRadius(), 11);
    for (int k = 0; k <= 5; ++k)
    {
      EXPECT_GE(rig.at(50 + k, 50), INSCRIBED_INFLATED_OBSTACLE);
      EXPECT_GE(rig.at(50, 50 - k), INSCRIBED_INFLATED_OBSTACLE);
    }
    for (int k = 6; k <= 11; ++k)
    {
      EXPECT_EQ(rig.at(50 + k, 50), inflationCost(k, 1.0, 5.0, factor)) << k;
      EXPECT_EQ(rig.at(50 - k, 50), inflationCost(k, 1.0, 5.0, factor)) << k;
      EXPECT_EQ(rig.at(50, 50 + k), inflationCost(k, 1.0, 5.0, factor)) << k;
      EXPECT_EQ(rig.at(50, 50 - k), inflationCost(k, 1.0, 5.0, factor)) << k;
    }
    EXPECT_EQ(rig.at(62, 50), FREE_SPACE);
    for (unsigned y = 0; y < 100; ++y)
      for (unsigned x = 0; x < 100; ++x)
      {
        const double d = std::hypot(double(x) - 50, double(y) - 50);
        ASSERT_EQ(rig.at(x, y), d <= 11.0 ? inflationCost(d, 1.0, 5.0, factor) : FREE_SPACE) << x << "," << y;
      }
  }
}

TEST(InflationLayer, LShapedWall)
{
  Rig rig(10, 10, 1.0, inflationParams(4.1, 10.0), 2.1);
  rig.marks->set(1, 1, LETHAL_OBSTACLE);
  rig.marks->set(2, 1, LETHAL_OBSTACLE);
  rig.marks->set(2, 2, LETHAL_OBSTACLE);
  rig.update();
  EXPECT_EQ(rig.at(2, 3), INSCRIBED_INFLATED_OBSTACLE);
  EXPECT_EQ(rig.at(3, 3), INSCRIBED_INFLATED_OBSTACLE);
  EXPECT_TRUE(sameCells(rig.lc.getCostmap(), naiveFull(rig.marks->costmap(), rig.inflation->config(), 2.1)));
}

TEST(InflationLayer, InflateUnknownLeavesOnlyCorners)
{
  Rig rig(9, 9, 1.0, inflationParams(4.1, 1.0, true), 2.1, true, NO_INFORMATION);
  rig.marks->set(4, 4, LETHAL_OBSTACLE);
  rig.update();
  for (unsigned y = 0; y < 9; ++y)
    for (unsigned x = 0; x < 9; ++x)
    {
      const bool corner = (x == 0 || x == 8) && (y == 0 || y == 8);
      EXPECT_EQ(rig.at(x, y) == NO_INFORMATION, corner) << x << "," << y << " = " << int(rig.at(x, y));
    }
}

TEST(InflationLayer, UnknownCellsTakeOnlyInscribedCostsByDefault)
{
  Rig rig(9, 9, 1.0, inflationParams(4.1, 1.0, false), 2.1, true, NO_INFORMATION);
  rig.marks->set(4, 4, LETHAL_OBSTACLE);
  rig.update();
  for (unsigned y = 0; y < 9; ++y)
    for (unsigned x = 0; x < 9; ++x)
    {
      const double d = std::hypot(double(x) - 4, double(y) - 4);
      if (d == 0)
        EXPECT_EQ(rig.at(x, y), LETHAL_OBSTACLE);
      else if (d <= 2.1)
        EXPECT_EQ(rig.at(x, y), INSCRIBED_INFLATED_OBSTACLE);
      else
        EXPECT_EQ(rig.at(x, y), NO_INFORMATION) << x << "," << y;
    }
}

TEST(InflationLayer, InflateAroundUnknown)
{
  Rig rig(15, 15, 1.0, inflationParams(3.0, 1.0, false, true), 1.5);
  rig.marks->set(7, 7, NO_INFORMATION);
  rig.update();
  EXPECT_EQ(rig.at(7, 7), LETHAL_OBSTACLE);  // as costmap_2d: the source cell takes 254
  EXPECT_EQ(rig.at(8, 7), INSCRIBED_INFLATED_OBSTACLE);
  EXPECT_EQ(rig.at(10, 7), inflationCost(3.0, 1.0, 1.5, 1.0));
  EXPECT_EQ(rig.at(11, 7), FREE_SPACE);
  EXPECT_TRUE(sameCells(rig.lc.getCostmap(), naiveFull(rig.marks->costmap(), rig.inflation->config(), 1.5)));
}

TEST(InflationLayer, ZeroRadiusWritesNothing)
{
  Rig rig(10, 10, 1.0, inflationParams(0.0, 1.0), 0.5);
  rig.marks->set(3, 3, LETHAL_OBSTACLE);
  rig.update();
  EXPECT_EQ(rig.at(3, 3), LETHAL_OBSTACLE);
  EXPECT_EQ(rig.at(4, 3), FREE_SPACE);
}

TEST(InflationLayer, BoundsGrowByTheRadiusAndReinflateOnChange)
{
  Rig rig(100, 100, 0.05, inflationParams(0.52, 10.0), 0.2);
  rig.update();
  double x0 = 1.0, y0 = 2.0, x1 = 1.5, y1 = 2.5;
  rig.inflation->updateBounds(0, 0, 0, &x0, &y0, &x1, &y1);
  // ceil(0.52 / 0.05) = 11 cells.
  EXPECT_NEAR(x0, 1.0 - 0.55, 1e-12);
  EXPECT_NEAR(y0, 2.0 - 0.55, 1e-12);
  EXPECT_NEAR(x1, 1.5 + 0.55, 1e-12);
  EXPECT_NEAR(y1, 2.5 + 0.55, 1e-12);
  // Nothing asked for: nothing added.
  double e0 = std::numeric_limits<double>::max(), e1 = std::numeric_limits<double>::lowest();
  double f0 = e0, f1 = e1;
  rig.inflation->updateBounds(0, 0, 0, &e0, &f0, &e1, &f1);
  EXPECT_GT(e0, e1);
  // A footprint change asks for the whole map once.
  rig.lc.setFootprint(square(0.1));
  rig.inflation->updateBounds(0, 0, 0, &e0, &f0, &e1, &f1);
  EXPECT_LT(e0, -1e30);
  EXPECT_GT(e1, 1e30);
}

TEST(InflationLayer, FootprintChangeReinflatesEverything)
{
  Rig rig(30, 30, 1.0, inflationParams(6.0, 1.0), 2.0);
  rig.marks->set(10, 10, LETHAL_OBSTACLE);
  rig.update();
  rig.lc.setFootprint(square(4.0));
  rig.update();
  EXPECT_EQ(rig.at(14, 10), INSCRIBED_INFLATED_OBSTACLE);
  EXPECT_TRUE(sameCells(rig.lc.getCostmap(), naiveFull(rig.marks->costmap(), rig.inflation->config(), 4.0)));
}

TEST(InflationLayer, DisabledLayerWritesNothing)
{
  ParamValue p = inflationParams(3.0, 1.0);
  p.set("enabled", ParamValue::makeBool(false));
  Rig rig(10, 10, 1.0, p, 1.0);
  rig.marks->set(5, 5, LETHAL_OBSTACLE);
  rig.update();
  EXPECT_FALSE(rig.inflation->enabled());
  EXPECT_EQ(rig.at(6, 5), FREE_SPACE);
}

// A 9000 x 9000 map with a 5000 x 5000 lethal square: the 11 cells outward from every edge follow the
// formula exactly (costmap_2d's wavefront gets some of them wrong).
TEST(InflationLayer, LargeSquareIsExactAlongEveryEdge)
{
  const unsigned size = 9000, lo = 2000, hi = 7000;  // square [lo, hi)
  const double res = 0.05, inscribed = 0.22;
  LayeredCostmap lc("map", false, false);
  lc.resizeMap(size, size, res, 0.0, 0.0);
  auto below = std::make_shared<FunctionLayer>();
  below->fn = [&](Costmap2D& m, int x0, int y0, int x1, int y1)
  {
    const int a = std::max<int>(x0, lo), b = std::min<int>(x1, hi);
    if (a >= b) return;
    for (int y = std::max<int>(y0, lo); y < std::min<int>(y1, hi); ++y)
      std::fill_n(m.data() + static_cast<std::size_t>(y) * size + a, b - a, LETHAL_OBSTACLE);
  };
  below->initialize(&lc, "square", std::make_shared<FakeContext>());
  lc.addPlugin(below);
  auto inflation = std::make_shared<InflationLayer>();
  inflation->initialize(&lc, "inflation", std::make_shared<FakeContext>(inflationParams(0.55, 10.0)));
  lc.addPlugin(inflation);
  lc.setFootprint(square(inscribed));
  lc.updateMap(0, 0, 0);
  const Costmap2D& m = lc.getCostmap();
  ASSERT_EQ(inflation->cellInflationRadius(), 11);

  // Every cell of the band around the square, corners included.
  const int cap = 11;
  for (int y = int(lo) - cap - 2; y < int(hi) + cap + 2; ++y)
  {
    const bool row_in = y >= int(lo) && y < int(hi);
    for (int x = int(lo) - cap - 2; x < int(hi) + cap + 2; ++x)
    {
      if (row_in && x == int(lo) + 2) x = int(hi) - 2;  // skip the interior
      const int dx = x < int(lo) ? int(lo) - x : (x >= int(hi) ? x - int(hi) + 1 : 0);
      const int dy = y < int(lo) ? int(lo) - y : (y >= int(hi) ? y - int(hi) + 1 : 0);
      const int d2 = dx * dx + dy * dy;
      const uint8_t expected = d2 <= cap * cap ? inflationCost(std::sqrt(double(d2)), res, inscribed, 10.0) : 0;
      ASSERT_EQ(m.getCost(unsigned(x), unsigned(y)), expected) << x << "," << y;
    }
  }
  EXPECT_EQ(m.getCost(4500, 4500), LETHAL_OBSTACLE);
  EXPECT_EQ(m.getCost(100, 100), FREE_SPACE);
  EXPECT_EQ(m.getCost(8999, 8999), FREE_SPACE);
}

namespace
{
struct RandomCase
{
  unsigned w, h;
  double res;
  double radius;
  double inscribed;
  double factor;
  double density;
  bool track_unknown, inflate_unknown, around;
};

RandomCase makeCase(std::mt19937& rng, int i)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  RandomCase c;
  c.w = 5 + rng() % 70;
  c.h = 5 + rng() % 70;
  c.res = i % 3 == 0 ? 1.0 : (i % 3 == 1 ? 0.05 : 0.1);
  // Radii in cells across the engine's paths: <= 14 (cost domain), beyond (16-bit squared distances).
  const int engine = i % 5;
  const double cells = engine < 3 ? 0.5 + u(rng) * 11 : (engine == 3 ? 11.5 + u(rng) * 28 : 41 + u(rng) * 20);
  c.radius = cells * c.res;
  c.inscribed = u(rng) * c.radius;
  c.factor = u(rng) * 5.0 / c.res;
  c.density = 0.001 + u(rng) * 0.05;
  c.track_unknown = rng() % 2;
  c.inflate_unknown = rng() % 2;
  c.around = rng() % 3 == 0;
  return c;
}

void randomFill(std::mt19937& rng, MarkLayer& marks, const RandomCase& c, double density)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (unsigned y = 0; y < c.h; ++y)
    for (unsigned x = 0; x < c.w; ++x)
    {
      const double r = u(rng);
      uint8_t v = r < density ? LETHAL_OBSTACLE : (r < 2.5 * density ? NO_INFORMATION : uint8_t(rng() % 120));
      if (r > 0.7) v = FREE_SPACE;
      marks.set(x, y, v);
    }
}
}  // namespace

// Every SIMD target this build compiled that this CPU runs (the scalar one included), each against the
// naive reference.
class InflationReference : public ::testing::TestWithParam<std::string>
{
protected:
  void SetUp() override { ASSERT_TRUE(setSimdTarget(GetParam())); }
  void TearDown() override { setSimdTarget(""); }
  unsigned seed(unsigned base) const
  {
    return base + static_cast<unsigned>(std::hash<std::string>()(GetParam()) % 1000);
  }
};

namespace
{
std::vector<std::string> inflationKernels()
{
  return simdTargets();
}
}  // namespace

TEST_P(InflationReference, FullAndPartialUpdatesEqualNaiveRecomputation)
{
  std::mt19937 rng(seed(1234));
  for (int i = 0; i < 40; ++i)
  {
    const RandomCase c = makeCase(rng, i);
    Rig rig(c.w, c.h, c.res, inflationParams(c.radius, c.factor, c.inflate_unknown, c.around), c.inscribed,
            c.track_unknown);
    randomFill(rng, *rig.marks, c, c.density);
    rig.update();
    const double inscribed = rig.inflation->inscribedRadius();
    ASSERT_TRUE(sameCells(rig.lc.getCostmap(), naiveFull(rig.marks->costmap(), rig.inflation->config(), inscribed)))
        << "full, case " << i << " radius cells " << rig.inflation->cellInflationRadius();

    // Partial updates: a few cells change; only their window padded by the radius is recomputed, and
    // the whole map must still equal a full recomputation.
    for (int step = 0; step < 4; ++step)
    {
      const int changes = 1 + static_cast<int>(rng() % 4);
      const unsigned cx = rng() % c.w, cy = rng() % c.h;
      for (int k = 0; k < changes; ++k)
      {
        const unsigned x = std::min(c.w - 1, cx + static_cast<unsigned>(rng() % 6));
        const unsigned y = std::min(c.h - 1, cy + static_cast<unsigned>(rng() % 6));
        const uint8_t choices[] = {LETHAL_OBSTACLE, FREE_SPACE, NO_INFORMATION, 40};
        rig.marks->set(x, y, choices[rng() % 4]);
      }
      rig.update();
      const CellWindow win = rig.lc.getUpdatedBounds();
      ASSERT_FALSE(win.empty());
      const int cap = rig.inflation->cellInflationRadius();
      EXPECT_LE(win.xn - win.x0, 6 + 2 * cap + 2);  // only the changed window padded by the radius
      ASSERT_TRUE(sameCells(rig.lc.getCostmap(), naiveFull(rig.marks->costmap(), rig.inflation->config(), inscribed)))
          << "partial, case " << i << " step " << step;
    }
  }
}

// The benchmark sweep through the layer: every radius (0.3 .. 3 m) at every resolution (0.025, 0.05,
// 0.1 m), factors 3 and 10, a robot of inscribed radius 0.2256 m (costmap_tool's robot_radius 0.22 with
// padding), one and two threads: every cell equals the naive inflation.
TEST_P(InflationReference, SweepEqualsNaiveOnEveryCell)
{
  std::mt19937 rng(seed(555));
  for (const double res : {0.025, 0.05, 0.1})
    for (const double radius : {0.3, 0.55, 1.0, 2.0, 3.0})
      for (const double factor : {3.0, 10.0})
      {
        const int cells = static_cast<int>(std::ceil(radius / res));
        const unsigned w = static_cast<unsigned>(std::min(2 * cells + 60, 260));
        const unsigned h = static_cast<unsigned>(std::min(2 * cells + 140, 330));
        const int threads = 1 + static_cast<int>(rng() % 2);
        ParamValue params = inflationParams(radius, factor, false, false);
        params.set("num_threads", ParamValue::makeInt(threads));
        Rig rig(w, h, res, params, 0.2256, true);
        RandomCase c{w, h, res, radius, 0.2256, factor, 0.0, true, false, false};
        randomFill(rng, *rig.marks, c, 0.5 / (cells + 4));
        rig.update();
        ASSERT_TRUE(sameCells(rig.lc.getCostmap(), naiveFull(rig.marks->costmap(), rig.inflation->config(), 0.2256)))
            << "res " << res << " radius " << radius << " factor " << factor << " threads " << threads;
      }
}

// num_threads: the same result on every cell for 1 .. 4 threads, on a map tall enough for bands.
TEST(InflationLayer, ThreadsGiveTheSameResult)
{
  for (const int threads : {1, 2, 3, 4})
  {
    ParamValue params = inflationParams(0.6, 3.0, false, true);
    params.set("num_threads", ParamValue::makeInt(threads));
    Rig rig(150, 420, 0.05, params, 0.2256, true);
    std::mt19937 fill(9);
    RandomCase c{150, 420, 0.05, 0.6, 0.2256, 3.0, 0.0, true, false, true};
    randomFill(fill, *rig.marks, c, 0.01);
    rig.update();
    EXPECT_EQ(rig.inflation->config().num_threads, threads);
    ASSERT_TRUE(sameCells(rig.lc.getCostmap(), naiveFull(rig.marks->costmap(), rig.inflation->config(), 0.2256)))
        << threads << " threads";
  }
}

TEST(InflationLayer, NumThreadsOutOfRangeIsRefused)
{
  // (0 and less mean "half the cores", Nav2's -1: DropIn.Nav2InflationNumThreadsMinusOneIsAuto.)
  for (const int bad : {65, 1000})
  {
    ParamValue params = inflationParams(0.55, 10.0);
    params.set("num_threads", ParamValue::makeInt(bad));
    EXPECT_THROW(parseInflationConfig(ParamReader(params, "inflation")), std::invalid_argument) << bad;
  }
}

// A rolling window: the layer below draws world-fixed obstacles into the master each cycle, the robot
// moves, and the inflated master equals the naive inflation of what the layer below drew.
TEST_P(InflationReference, RollingWindowEqualsNaive)
{
  std::mt19937 rng(seed(99));
  std::uniform_real_distribution<double> u(-8.0, 8.0);
  std::vector<std::pair<double, double>> obstacles;
  for (int k = 0; k < 150; ++k)
    obstacles.emplace_back(u(rng), u(rng));
  for (int variant = 0; variant < 3; ++variant)
  {
    const double res = variant == 0 ? 0.05 : 0.1;
    const double radius = variant == 2 ? 2.5 : 0.55;  // 11, 6 and 25 cells
    LayeredCostmap lc("odom", true, variant == 1);
    lc.resizeMap(120, 90, res, 0.0, 0.0);
    Costmap2D base;
    auto below = std::make_shared<FunctionLayer>();
    below->fn = [&](Costmap2D& m, int x0, int y0, int x1, int y1)
    {
      for (const auto& o : obstacles)
      {
        unsigned mx, my;
        if (!m.worldToMap(o.first, o.second, mx, my)) continue;
        if (int(mx) >= x0 && int(mx) < x1 && int(my) >= y0 && int(my) < y1) m.setCost(mx, my, LETHAL_OBSTACLE);
      }
      base = m;  // what the inflation layer starts from
    };
    below->initialize(&lc, "obstacles", std::make_shared<FakeContext>());
    lc.addPlugin(below);
    auto inflation = std::make_shared<InflationLayer>();
    inflation->initialize(&lc, "inflation",
                          std::make_shared<FakeContext>(inflationParams(radius, 3.0, variant == 1, false)));
    lc.addPlugin(inflation);
    lc.setFootprint(square(0.2));
    for (int step = 0; step < 6; ++step)
    {
      lc.updateMap(-3.0 + step * 0.73, 1.0 - step * 0.41, 0.0);
      ASSERT_TRUE(sameCells(lc.getCostmap(), naiveFull(base, inflation->config(), 0.2)))
          << "variant " << variant << " step " << step;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Kernels, InflationReference, ::testing::ValuesIn(inflationKernels()),
                         [](const ::testing::TestParamInfo<std::string>& info)
                         {
                           std::string name = info.param;
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });
