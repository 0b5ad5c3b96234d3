// LanesFilter: the cost profile against the exact distance to the nearest lane cell (checked by hand
// for straight lanes and by brute force for a diagonal one, on each distance engine), what is left
// untouched, soft values, the unknown-master rule, and recomputation only on a new mask; the vector
// kernels of the last step against its definition.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/filters/lanes_filter.hpp"
#include "costmap_layers/core/rules/cost_rules.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/kernels/simd_targets.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;
using costmap_layers_test::GridKind;

namespace
{
OccupancyGridData makeMask(uint32_t w, uint32_t h, double res, int8_t fill, double ox = 0.0, double oy = 0.0)
{
  OccupancyGridData m;
  m.frame_id = "map";
  m.width = w;
  m.height = h;
  m.resolution = res;
  m.origin_x = ox;
  m.origin_y = oy;
  m.data.assign(static_cast<std::size_t>(w) * h, fill);
  return m;
}

int8_t& at(OccupancyGridData& m, int x, int y)
{
  return m.data[static_cast<std::size_t>(y) * m.width + x];
}

struct Params
{
  double width = 0.5;
  int border = 1;
  const char* profile = "linear";
  double decay = 10.0;
  ParamValue value() const
  {
    ParamValue p = ParamValue::makeMap();
    p.set("lane_border_width", ParamValue::makeDouble(width));
    p.set("border_cost", ParamValue::makeInt(border));
    p.set("cost_profile", ParamValue::makeString(profile));
    p.set("decay", ParamValue::makeDouble(decay));
    return p;
  }
};

struct Rig
{
  LayeredCostmap lc{"map", false, false};
  std::shared_ptr<FakeContext> ctx;
  std::shared_ptr<LanesFilter> filter = std::make_shared<LanesFilter>();

  explicit Rig(const Params& p = Params{}) : ctx(std::make_shared<FakeContext>(p.value()))
  {
    filter->initialize(&lc, "lanes", ctx);
    ctx->bind(*filter);
  }
  void cycle()
  {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    filter->updateBounds(0, 0, 0, &x0, &y0, &x1, &y1);
  }
  /// Publishes the mask, runs one cycle and updates all of master.
  void apply(const OccupancyGridData& mask, Costmap2D& master)
  {
    ctx->publishGrid(GridKind::Mask, mask);
    cycle();
    filter->updateCosts(master, 0, 0, static_cast<int>(master.getSizeInCellsX()),
                        static_cast<int>(master.getSizeInCellsY()));
  }
};

/// A master grid with the mask's geometry, every cell `fill`.
Costmap2D masterFor(const OccupancyGridData& m, uint8_t fill)
{
  return Costmap2D(m.width, m.height, m.resolution, m.origin_x, m.origin_y, fill);
}

/// Brute force: the squared distance [cells^2] from (x, y) to the nearest lane (0) cell, or -1.
int64_t nearestLaneSq(const OccupancyGridData& m, int x, int y)
{
  int64_t best = -1;
  for (int v = 0; v < static_cast<int>(m.height); ++v)
    for (int u = 0; u < static_cast<int>(m.width); ++u)
      if (m.data[static_cast<std::size_t>(v) * m.width + u] == 0)
      {
        const int64_t d2 = int64_t{u - x} * (u - x) + int64_t{v - y} * (v - y);
        if (best < 0 || d2 < best) best = d2;
      }
  return best;
}

/// The filter's documented cost written out directly (unnormalised exponential form): for tests.
double referenceCost(const Params& p, double d, double r)
{
  if (d >= p.width) return 254;
  double s;
  if (std::string(p.profile) == "linear")
    s = (d - r) / (p.width - r);
  else
    s = (std::exp(p.decay * (d - r)) - 1.0) / (std::exp(p.decay * (p.width - r)) - 1.0);
  return std::min(253.0, std::round(p.border + (253 - p.border) * s));
}

LanesFilterConfig configOf(const Params& p)
{
  const ParamValue v = p.value();
  return parseLanesFilterConfig(ParamReader(v, "lanes"));
}
}  // namespace

// ---------------------------------------------------------------- configuration and formula

TEST(LanesFilterConfig, DefaultsParsingAndBadValues)
{
  const ParamValue empty = ParamValue::makeMap();
  const LanesFilterConfig d = parseLanesFilterConfig(ParamReader(empty, "lanes"));
  EXPECT_EQ(d.lane_border_width, 0.5);
  EXPECT_EQ(d.border_cost, 1);
  EXPECT_EQ(d.cost_profile, LaneCostProfile::Linear);
  EXPECT_EQ(d.decay, 10.0);

  const LanesFilterConfig c = configOf({1.25, 30, "exponential", 4.0});
  EXPECT_EQ(c.lane_border_width, 1.25);
  EXPECT_EQ(c.border_cost, 30);
  EXPECT_EQ(c.cost_profile, LaneCostProfile::Exponential);
  EXPECT_EQ(c.decay, 4.0);

  auto expectThrows = [](const char* name, ParamValue v)
  {
    ParamValue p = ParamValue::makeMap();
    p.set(name, std::move(v));
    try
    {
      parseLanesFilterConfig(ParamReader(p, "lanes"));
      ADD_FAILURE() << name << " accepted";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  expectThrows("lane_border_width", ParamValue::makeDouble(-0.1));
  expectThrows("border_cost", ParamValue::makeInt(0));
  expectThrows("border_cost", ParamValue::makeInt(254));
  expectThrows("cost_profile", ParamValue::makeString("quadratic"));
  expectThrows("decay", ParamValue::makeDouble(0.0));

  // A bad configuration fails initialize().
  LayeredCostmap lc("map", false, false);
  auto f = std::make_shared<LanesFilter>();
  ParamValue bad = ParamValue::makeMap();
  bad.set("border_cost", ParamValue::makeInt(300));
  EXPECT_THROW(f->initialize(&lc, "lanes", std::make_shared<FakeContext>(bad)), std::invalid_argument);
}

TEST(LanesFilterFormula, LinearByHand)
{
  const LanesFilterConfig c = configOf({0.5, 1, "linear", 10.0});
  const double r = 0.05;
  EXPECT_EQ(lanesForbiddenCost(c, 0.05, r), 1);     // the border: border_cost
  EXPECT_EQ(lanesForbiddenCost(c, 0.275, r), 127);  // half way: 1 + 252 / 2 = 127
  EXPECT_EQ(lanesForbiddenCost(c, 0.45, r), 225);   // 1 + 252 * 0.4 / 0.45 = 225
  EXPECT_EQ(lanesForbiddenCost(c, 0.4999, r), 253);
  EXPECT_EQ(lanesForbiddenCost(c, 0.5, r), 254);
  EXPECT_EQ(lanesForbiddenCost(c, 7.0, r), 254);
  EXPECT_EQ(lanesForbiddenCost(c, std::numeric_limits<double>::infinity(), r), 254);
  const LanesFilterConfig b = configOf({0.5, 100, "linear", 10.0});
  EXPECT_EQ(lanesForbiddenCost(b, 0.05, r), 100);
  EXPECT_EQ(lanesForbiddenCost(b, 0.275, r), 177);  // 100 + 153 / 2 = 176.5 -> 177
  // Lethal squared distances: (0.5 / 0.05)^2 = 100 cells^2.
  EXPECT_EQ(lanesLethalSquaredDistance(c, 0.05), 100u);
  EXPECT_EQ(lanesLethalSquaredDistance(c, 0.1), 25u);
  EXPECT_EQ(lanesLethalSquaredDistance(c, 0.3), 3u);  // sqrt(3) * 0.3 = 0.52 >= 0.5 > sqrt(2) * 0.3
  EXPECT_EQ(lanesLethalSquaredDistance(c, 0.5), 1u);
  EXPECT_EQ(lanesLethalSquaredDistance(configOf({0.0, 1, "linear", 1.0}), 0.05), 0u);
}

TEST(LanesFilterFormula, ExponentialByHandAndMonotonic)
{
  const Params p{0.5, 1, "exponential", 10.0};
  const LanesFilterConfig c = configOf(p);
  const double r = 0.05;
  EXPECT_EQ(lanesForbiddenCost(c, 0.05, r), 1);
  // (e^2.25 - 1) / (e^4.5 - 1) = 0.09535 -> 1 + 252 * 0.09535 = 25.03
  EXPECT_EQ(lanesForbiddenCost(c, 0.275, r), 25);
  EXPECT_EQ(lanesForbiddenCost(c, 0.5, r), 254);
  for (const double decay : {1e-6, 0.5, 10.0, 80.0, 1e4})
  {
    Params q = p;
    q.decay = decay;
    const LanesFilterConfig e = configOf(q);
    int prev = 0;
    for (double d = r; d < 0.6; d += 0.001)
    {
      const int cost = lanesForbiddenCost(e, d, r);
      EXPECT_GE(cost, prev) << "decay " << decay << " d " << d;
      EXPECT_GE(cost, 1);
      if (d < 0.5)
      {
        EXPECT_LE(cost, 253);
      }
      if (decay < 100)
      {
        EXPECT_NEAR(cost, referenceCost(q, d, r), 1.0) << decay << " " << d;
      }
      prev = cost;
    }
  }
  // Tiny decay: the linear profile; huge decay: border_cost until right before the wall.
  EXPECT_EQ(lanesForbiddenCost(configOf({0.5, 1, "exponential", 1e-6}), 0.275, r), 127);
  EXPECT_EQ(lanesForbiddenCost(configOf({0.5, 1, "exponential", 1e4}), 0.45, r), 1);
}

// ---------------------------------------------------------------- straight lanes

namespace
{
/// A 40 x 24 mask at 5 cm: forbidden everywhere but a vertical lane in columns 10..13 (4 cells wide).
OccupancyGridData straightLane()
{
  OccupancyGridData m = makeMask(40, 24, 0.05, 100);
  for (int y = 0; y < 24; ++y)
    for (int x = 10; x <= 13; ++x)
      at(m, x, y) = 0;
  return m;
}

void checkStraightLaneProfile(const Params& p)
{
  SCOPED_TRACE(std::string(p.profile) + " border " + std::to_string(p.border));
  Rig rig(p);
  const OccupancyGridData m = straightLane();
  Costmap2D master = masterFor(m, 0);
  for (int y = 0; y < 24; ++y)
    for (int x = 10; x <= 13; ++x)
      master.setCost(x, y, static_cast<uint8_t>(x * 3));  // others' costs
  rig.apply(m, master);
  const double r = 0.05;
  for (int y = 0; y < 24; ++y)
  {
    int prev_right = 0;
    for (int x = 0; x < 40; ++x)
    {
      const int cost = master.getCost(x, y);
      if (x >= 10 && x <= 13)
      {
        EXPECT_EQ(cost, x * 3) << "lane cell " << x << "," << y;  // untouched
        continue;
      }
      const int dx = x < 10 ? 10 - x : x - 13;  // [cells] to the nearest lane cell
      const double d = dx * r;
      EXPECT_EQ(cost, referenceCost(p, d, r)) << x << "," << y;
      if (dx == 1)
      {
        EXPECT_EQ(cost, p.border) << x << "," << y;
      }
      if (d >= p.width)
      {
        EXPECT_EQ(cost, 254) << x << "," << y;
      }
      if (d < p.width)
      {
        EXPECT_LT(cost, 254) << x << "," << y;
      }
      if (x > 13)
      {
        EXPECT_GE(cost, prev_right) << x << "," << y;  // never falls moving away
        prev_right = cost;
      }
      if (x <= 23)
      {
        EXPECT_EQ(cost, master.getCost(23 - x, y)) << "symmetric " << x << "," << y;
      }
    }
  }
}
}  // namespace

TEST(LanesFilter, StraightLaneLinearProfile)
{
  checkStraightLaneProfile({0.5, 1, "linear", 10.0});
  checkStraightLaneProfile({0.5, 60, "linear", 10.0});
  checkStraightLaneProfile({0.3, 1, "linear", 10.0});
  checkStraightLaneProfile({0.52, 1, "linear", 10.0});  // W between cell centres
}

TEST(LanesFilter, StraightLaneExponentialProfile)
{
  checkStraightLaneProfile({0.5, 1, "exponential", 10.0});
  checkStraightLaneProfile({0.5, 20, "exponential", 3.0});
  checkStraightLaneProfile({0.4, 1, "exponential", 40.0});
}

TEST(LanesFilter, StraightLaneValuesSpotChecked)
{
  // Default parameters, 5 cm cells: the border costs 1, ten cells out is lethal.
  Rig rig;
  const OccupancyGridData m = straightLane();
  Costmap2D master = masterFor(m, 0);
  rig.apply(m, master);
  const int expected[] = {1, 29, 57, 85, 113, 141, 169, 197, 225, 254, 254};  // dx = 1 .. 10, 10+
  for (int dx = 1; dx <= 9; ++dx)
    EXPECT_EQ(master.getCost(13 + dx, 5), expected[dx - 1]) << dx;
  EXPECT_EQ(master.getCost(13 + 10, 5), 254);
  EXPECT_EQ(master.getCost(39, 5), 254);
  EXPECT_EQ(master.getCost(0, 5), 254);  // 10 cells to the left of column 10
  EXPECT_EQ(master.getCost(1, 5), 225);
}

TEST(LanesFilter, DiagonalNeighboursOfALaneCostALittleMore)
{
  // A single lane cell: its 4-neighbours are at d = r, its diagonal neighbours at r * sqrt(2).
  Rig rig;
  OccupancyGridData m = makeMask(21, 21, 0.05, 100);
  at(m, 10, 10) = 0;
  Costmap2D master = masterFor(m, 0);
  rig.apply(m, master);
  EXPECT_EQ(master.getCost(10, 10), 0);
  for (const auto& n : {std::pair<int, int>{9, 10}, {11, 10}, {10, 9}, {10, 11}})
    EXPECT_EQ(master.getCost(n.first, n.second), 1);
  const int diag = master.getCost(11, 11);
  EXPECT_EQ(diag, static_cast<int>(std::lround(1 + 252 * (0.05 * std::sqrt(2.0) - 0.05) / 0.45)));  // 12
  EXPECT_GT(diag, 1);
  EXPECT_LT(diag, 20);
  EXPECT_EQ(master.getCost(9, 9), diag);
  EXPECT_EQ(master.getCost(10, 20), 254);  // d = 0.5: lethal
  EXPECT_EQ(master.getCost(10, 19), 225);  // d = 0.45
  EXPECT_EQ(master.getCost(17, 17), 250);  // d^2 = 98 cells^2: 0.495 m, just inside
  EXPECT_EQ(master.getCost(18, 17), 254);  // d^2 = 113 cells^2: beyond
}

TEST(LanesFilter, UnknownAndSoftCellsAndNoLanes)
{
  Rig rig;
  OccupancyGridData m = straightLane();
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 40; ++x)
      at(m, x, y) = -1;  // rows 0..5: no opinion (lane cells too)
  for (int x = 0; x < 40; ++x)
    at(m, x, 20) = static_cast<int8_t>(x % 2 ? 50 : 99);  // row 20: soft
  at(m, 30, 21) = 1;
  Costmap2D master = masterFor(m, 0);
  for (unsigned j = 0; j < 24; ++j)
    for (unsigned i = 0; i < 40; ++i)
      master.setCost(i, j, static_cast<uint8_t>((i * 7 + j) % 200));
  const Costmap2D before = master;
  rig.apply(m, master);
  for (unsigned i = 0; i < 40; ++i)
  {
    for (unsigned j = 0; j < 6; ++j)
      EXPECT_EQ(master.getCost(i, j), before.getCost(i, j)) << i << "," << j;
    const int soft = i % 2 ? 127 : 251;
    EXPECT_EQ(master.getCost(i, 20), std::max<int>(soft, before.getCost(i, 20))) << i;
  }
  EXPECT_EQ(master.getCost(30, 21), std::max<int>(3, before.getCost(30, 21)));
  // -1 cells are not lanes: row 6 right of the lane is costed by its distance to the lane only.
  EXPECT_EQ(master.getCost(14, 6), std::max<int>(1, before.getCost(14, 6)));
  EXPECT_EQ(master.getCost(30, 6), 254);

  // No lane cell at all: every forbidden cell is lethal; soft stays soft, -1 untouched.
  Rig none;
  OccupancyGridData n = makeMask(12, 8, 0.05, 100);
  at(n, 3, 3) = -1;
  at(n, 4, 4) = 50;
  Costmap2D g = masterFor(n, 9);
  none.apply(n, g);
  for (unsigned j = 0; j < 8; ++j)
    for (unsigned i = 0; i < 12; ++i)
    {
      const int expected = (i == 3 && j == 3) ? 9 : (i == 4 && j == 4) ? 127 : 254;
      EXPECT_EQ(g.getCost(i, j), expected) << i << "," << j;
    }
}

TEST(LanesFilter, UnknownMasterCellsTakeOnlyLethalCosts)
{
  Rig rig;
  OccupancyGridData m = straightLane();
  at(m, 30, 3) = 99;   // soft 251: not enough for unknown space
  at(m, 31, 3) = 100;  // forbidden and far: lethal
  Costmap2D master = masterFor(m, NO_INFORMATION);
  rig.apply(m, master);
  for (unsigned j = 0; j < 24; ++j)
    for (unsigned i = 0; i < 40; ++i)
    {
      const int dx = i < 10 ? 10 - static_cast<int>(i) : static_cast<int>(i) - 13;
      const bool lethal = (i < 10 || i > 13) && dx >= 10 && !(i == 30 && j == 3);
      EXPECT_EQ(master.getCost(i, j), lethal ? 254 : 255) << i << "," << j;
    }
  // W just beyond a cell centre gives 253 at dx = 10 (1 + 252 * 0.45 / 0.4505 = 252.7): taken too.
  Rig wide(Params{0.5005, 1, "linear", 10.0});
  Costmap2D g = masterFor(m, NO_INFORMATION);
  wide.apply(m, g);
  EXPECT_EQ(g.getCost(23, 5), 253);
  EXPECT_EQ(g.getCost(22, 5), 255);  // dx = 9: 225
  EXPECT_EQ(g.getCost(24, 5), 254);
}

// ---------------------------------------------------------------- brute force, every engine

namespace
{
/// A diagonal lane about 3 cells wide, plus -1 and soft patches, on a w x h mask (57 x 43 unless said).
OccupancyGridData diagonalLane(double res, int w = 57, int h = 43)
{
  OccupancyGridData m = makeMask(w, h, res, 100, -1.3, 0.7);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
    {
      const double off = x - 1.3 * y - 4.0;
      if (std::fabs(off) < 2.0) at(m, x, y) = 0;
      if (x >= 45 && y < 8) at(m, x, y) = -1;
      if (x < 6 && y > 36) at(m, x, y) = static_cast<int8_t>(20 + x);
    }
  at(m, 50, 30) = 0;  // a lone lane cell
  return m;
}

void checkAgainstBruteForce(const Params& p, double res, int w = 57, int h = 43)
{
  SCOPED_TRACE(std::string(p.profile) + " W " + std::to_string(p.width) + " res " + std::to_string(res));
  Rig rig(p);
  const OccupancyGridData m = diagonalLane(res, w, h);
  Costmap2D master = masterFor(m, 0);
  rig.apply(m, master);
  const LanesFilterConfig c = configOf(p);
  int lethal = 0, graded = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
    {
      const int8_t v = m.data[static_cast<std::size_t>(y) * w + x];
      int expected = 0;
      if (v == 100)
      {
        const int64_t d2 = nearestLaneSq(m, x, y);
        const double d = std::sqrt(static_cast<double>(d2)) * res;
        expected = lanesForbiddenCost(c, d, res);
        EXPECT_NEAR(expected, referenceCost(p, d, res), 1.0);
        (expected == 254 ? lethal : graded) += 1;
      }
      else if (v > 0)
        expected = static_cast<int>(std::lround(v * 254.0 / 100.0));
      ASSERT_EQ(master.getCost(x, y), expected) << x << "," << y;
    }
  if (p.width < 100)
  {
    EXPECT_GT(lethal, 0);
  }
  EXPECT_GT(graded, 0);
}
}  // namespace

TEST(LanesFilter, DiagonalLaneMatchesBruteForce8BitBand)
{
  checkAgainstBruteForce({0.5, 1, "linear", 10.0}, 0.05);  // cap 10
  checkAgainstBruteForce({0.5, 5, "exponential", 10.0}, 0.05);
  checkAgainstBruteForce({0.33, 1, "linear", 10.0}, 0.1);  // cap 4, W off the grid of distances
}

TEST(LanesFilter, DiagonalLaneMatchesBruteForce16BitBand)
{
  checkAgainstBruteForce({1.3, 1, "linear", 10.0}, 0.1);            // cap 13
  checkAgainstBruteForce({2.0, 7, "exponential", 2.0}, 0.1);        // cap 20
  checkAgainstBruteForce({2.35, 1, "linear", 2.0}, 0.05, 120, 90);  // cap 47
}

TEST(LanesFilter, DiagonalLaneMatchesBruteForceFullTransform)
{
  checkAgainstBruteForce({3.5, 1, "linear", 10.0}, 0.06, 140, 110);  // cap 59: lookup table
  checkAgainstBruteForce({3.5, 1, "exponential", 1.5}, 0.06, 140, 110);
  checkAgainstBruteForce({300.0, 1, "linear", 10.0}, 0.1);  // q = 9e6: per-cell costs
}

// ---------------------------------------------------------------- mapping, recomputation, reports

TEST(LanesFilter, SampledAtMasterCellCentres)
{
  Rig rig;
  const OccupancyGridData m = diagonalLane(0.05);  // origin (-1.3, 0.7)
  Costmap2D mask_grid = masterFor(m, 0);           // the costs on the mask grid itself
  Rig direct;
  direct.apply(m, mask_grid);
  Costmap2D master(30, 20, 0.13, -1.61, 0.52, 0);  // coarser, shifted
  rig.apply(m, master);
  int on_mask = 0;
  for (unsigned j = 0; j < 20; ++j)
    for (unsigned i = 0; i < 30; ++i)
    {
      const double gx = (-1.61 + (i + 0.5) * 0.13 + 1.3) / 0.05;
      const double gy = (0.52 + (j + 0.5) * 0.13 - 0.7) / 0.05;
      int expected = 0;
      if (gx >= 0 && gy >= 0 && gx < 57 && gy < 43)
      {
        expected = mask_grid.getCost(static_cast<unsigned>(gx), static_cast<unsigned>(gy));
        ++on_mask;
      }
      EXPECT_EQ(master.getCost(i, j), expected) << i << "," << j;
    }
  EXPECT_GT(on_mask, 100);
}

TEST(LanesFilter, CostsAreComputedOnlyForANewMask)
{
  Rig rig;
  EXPECT_EQ(rig.filter->costComputations(), 0u);
  const OccupancyGridData m = straightLane();
  Costmap2D master = masterFor(m, 0);
  rig.apply(m, master);
  EXPECT_EQ(rig.filter->costComputations(), 1u);
  for (int k = 0; k < 5; ++k)
  {
    rig.cycle();
    rig.filter->updateCosts(master, k, k, 40 - k, 24 - k);
  }
  rig.ctx->toggle(false);
  rig.cycle();
  rig.filter->updateCosts(master, 0, 0, 40, 24);
  rig.ctx->toggle(true);
  rig.cycle();
  rig.filter->updateCosts(master, 0, 0, 40, 24);
  EXPECT_EQ(rig.filter->costComputations(), 1u);
  // A rejected mask is no new mask.
  rig.ctx->publishGrid(GridKind::Mask, makeMask(3, 3, 0.0, 0));
  rig.cycle();
  rig.filter->updateCosts(master, 0, 0, 40, 24);
  EXPECT_EQ(rig.filter->costComputations(), 1u);
  // A new mask: once more, whatever the number of updates after it.
  OccupancyGridData n = straightLane();
  for (int y = 0; y < 24; ++y)
    at(n, 30, y) = 0;  // a second lane
  Costmap2D g = masterFor(n, 0);
  rig.apply(n, g);
  rig.filter->updateCosts(g, 0, 0, 40, 24);
  rig.cycle();
  rig.filter->updateCosts(g, 0, 0, 40, 24);
  EXPECT_EQ(rig.filter->costComputations(), 2u);
  EXPECT_EQ(g.getCost(29, 3), 1);  // the new lane's border
  EXPECT_EQ(g.getCost(25, 3), 113);
  // No computation before any update.
  Rig idle;
  idle.ctx->publishGrid(GridKind::Mask, m);
  idle.cycle();
  EXPECT_EQ(idle.filter->costComputations(), 0u);
}

TEST(LanesFilter, InvalidValuesSkippedAndWarnedOncePerMask)
{
  Rig rig;
  OccupancyGridData m = straightLane();
  at(m, 30, 3) = 120;
  at(m, 31, 3) = -20;
  Costmap2D master = masterFor(m, 5);
  rig.apply(m, master);
  EXPECT_EQ(master.getCost(30, 3), 5);
  EXPECT_EQ(master.getCost(31, 3), 5);
  EXPECT_EQ(master.getCost(32, 3), 254);
  EXPECT_EQ(rig.ctx->countReports("2 values outside -1..100"), 1);
  rig.filter->updateCosts(master, 0, 0, static_cast<int>(master.getSizeInCellsX()),
                          static_cast<int>(master.getSizeInCellsY()));
  EXPECT_EQ(rig.ctx->reports.size(), 1u);  // the same mask: once
  rig.apply(m, master);                    // a mask received again is warned again (the node throttles)
  EXPECT_EQ(rig.ctx->countReports("2 values outside -1..100"), 2);
  EXPECT_EQ(rig.ctx->reports.size(), 2u);
  EXPECT_FALSE(rig.filter->isClearable());
}

// ---------------------------------------------------------------- the last step's kernels

TEST(LanesFilter, FinishKernelsMatchTheDefinition)
{
  std::mt19937 rng(11);
  const int8_t plain[] = {0, 100, -1};
  for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{15}, std::size_t{16}, std::size_t{33},
                              std::size_t{64}, std::size_t{517}})
    for (int trial = 0; trial < 6; ++trial)
    {
      // Trial 0: every byte value in turn; others: blocks of lane / forbidden / unknown cells only (the
      // fast path) between blocks of any value.
      std::vector<int8_t> mask(n);
      std::vector<uint8_t> c(n);
      for (std::size_t k = 0; k < n; ++k)
      {
        if (trial == 0)
          mask[k] = static_cast<int8_t>(static_cast<uint8_t>(k * 37 % 256));
        else if ((k / (8u << (trial % 3))) % 2 == 0)
          mask[k] = plain[rng() % 3];
        else
          mask[k] = static_cast<int8_t>(static_cast<uint8_t>(rng() % 256));
        c[k] = static_cast<uint8_t>(rng() % 256);
      }
      std::vector<uint8_t> expected(n);
      std::size_t invalid = 0;
      for (std::size_t k = 0; k < n; ++k)
      {
        invalid += mask[k] < -1 || mask[k] > 100 ? 1 : 0;
        expected[k] = mask[k] == 100 ? static_cast<uint8_t>(254 - c[k]) : maskValueCost(mask[k]);
      }
      for (const std::string& target : simdTargets())
        for (const bool stream : {false, true})
          for (const std::size_t offset : {0, 1, 13, 32})
          {
            SCOPED_TRACE(target + " n " + std::to_string(n) + " trial " + std::to_string(trial) +
                         (stream ? " streamed" : "") + " offset " + std::to_string(offset));
            ASSERT_TRUE(setSimdTarget(target));
            std::vector<uint8_t> buf(n + 96, 0xAB);
            uint8_t* out = buf.data() + offset;
            const std::size_t got = lanesFinishCosts(mask.data(), c.data(), out, n, stream);
            EXPECT_EQ(got, invalid);
            for (std::size_t k = 0; k < n; ++k)
              ASSERT_EQ(out[k], expected[k]) << "cell " << k << " value " << int{mask[k]};
            for (std::size_t k = 0; k < buf.size(); ++k)
              if (k < offset || k >= offset + n)
              {
                ASSERT_EQ(buf[k], 0xAB) << "outside, byte " << k;
              }
            // In place (out == c).
            std::vector<uint8_t> inplace = c;
            EXPECT_EQ(lanesFinishCosts(mask.data(), inplace.data(), inplace.data(), n, stream), invalid);
            EXPECT_EQ(inplace, expected);
          }
    }
  setSimdTarget("");
}

TEST(LanesFilter, RandomMaskOfEveryValueMatchesBruteForce)
{
  // Wider than several vector blocks and not a multiple of any, every byte value, lanes sprinkled:
  // the 8-bit band (cap 10) with its row-wise last step.
  std::mt19937 rng(29);
  const int w = 203, h = 41;
  OccupancyGridData m = makeMask(w, h, 0.05, 100);
  std::size_t invalid = 0;
  for (auto& v : m.data)
  {
    const unsigned r = rng() % 100;
    v = r < 2 ? int8_t{0} : r < 70 ? int8_t{100} : static_cast<int8_t>(static_cast<uint8_t>(rng() % 256));
    invalid += v < -1 || v > 100 ? 1 : 0;
  }
  ASSERT_GT(invalid, 0u);
  const Params p{0.5, 1, "linear", 10.0};
  Rig rig(p);
  Costmap2D master = masterFor(m, 0);
  rig.apply(m, master);
  const LanesFilterConfig c = configOf(p);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
    {
      const int8_t v = m.data[static_cast<std::size_t>(y) * w + x];
      int expected = maskValueCost(v);
      if (v == 100)
        expected = lanesForbiddenCost(c, std::sqrt(static_cast<double>(nearestLaneSq(m, x, y))) * 0.05, 0.05);
      ASSERT_EQ(master.getCost(x, y), expected) << x << "," << y << " value " << int{v};
    }
  EXPECT_EQ(rig.ctx->countReports(std::to_string(invalid) + " values outside -1..100"), 1);
}

TEST(LanesFilter, ReconfigureChangesTheBorderAndRecomputes)
{
  // A lane along row 0 of a 1 x 20 strip at 0.1 m: forbidden cell k (k >= 1) is k * 0.1 m from it.
  Rig r(Params{0.5, 1, "linear", 10.0});
  OccupancyGridData mask = makeMask(1, 20, 0.1, 100);
  at(mask, 0, 0) = 0;
  Costmap2D master = masterFor(mask, 0);
  r.apply(mask, master);
  const std::size_t computed = r.filter->costComputations();
  EXPECT_EQ(master.getCost(0, 5), LETHAL_OBSTACLE);  // 0.5 m: lethal with a 0.5 m border
  EXPECT_LT(master.getCost(0, 4), LETHAL_OBSTACLE);

  // Every tunable parameter is described, with the parse function's defaults and the current values.
  const auto specs = r.filter->tunableParameters(Params{0.5, 1, "linear", 10.0}.value());
  std::vector<std::string> names;
  for (const auto& s : specs)
    names.push_back(s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"enabled", "lane_border_width", "border_cost", "cost_profile", "decay"}));
  EXPECT_DOUBLE_EQ(specs[1].default_value.asDouble(), 0.5);

  // A bad value is refused and changes nothing.
  ParamValue bad = Params{-1.0, 1, "linear", 10.0}.value();
  EXPECT_THROW(r.filter->reconfigure(bad), std::invalid_argument);
  EXPECT_DOUBLE_EQ(r.filter->config().lane_border_width, 0.5);

  // A wider border: the costs are recomputed (once) and cell 5 is no longer lethal.
  r.filter->reconfigure(Params{1.0, 1, "linear", 10.0}.value());
  Costmap2D again = masterFor(mask, 0);
  r.cycle();
  r.filter->updateCosts(again, 0, 0, 1, 20);
  EXPECT_EQ(r.filter->costComputations(), computed + 1);
  EXPECT_LT(again.getCost(0, 5), LETHAL_OBSTACLE);
  EXPECT_EQ(again.getCost(0, 5), static_cast<uint8_t>(referenceCost(Params{1.0, 1, "linear", 10.0}, 0.5, 0.1)));
  EXPECT_EQ(again.getCost(0, 10), LETHAL_OBSTACLE);
}
