// The distance engine against an exhaustive search, on every SIMD target this build compiled that this
// CPU runs (simdTargets(): each Highway target, the scalar one included), at every radius and
// resolution of the benchmark sweep, through each of its paths (cost domain, 16-bit, envelope), with
// windows, strides, the merge rule, streamed rows and threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "costmap_layers/core/rules/cost_rules.hpp"
#include "costmap_layers/core/kernels/distance_transform.hpp"
#include "costmap_layers/core/kernels/simd_targets.hpp"

using namespace costmap_layers;

namespace
{
constexpr uint64_t kNone = std::numeric_limits<uint64_t>::max();

/// Squared distance to the nearest source by exhaustive search over every source, or kNone.
std::vector<uint64_t> bruteForce(const std::vector<uint8_t>& grid, int w, int h, std::ptrdiff_t stride, SourceRange src)
{
  std::vector<std::pair<int64_t, int64_t>> sources;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (src.contains(grid[static_cast<std::size_t>(y * stride + x)])) sources.emplace_back(x, y);
  std::vector<uint64_t> out(static_cast<std::size_t>(w) * h, kNone);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
    {
      uint64_t best = kNone;
      for (const auto& s : sources)
        best = std::min<uint64_t>(
            best, static_cast<uint64_t>((s.first - x) * (s.first - x) + (s.second - y) * (s.second - y)));
      out[static_cast<std::size_t>(y) * w + x] = best;
    }
  return out;
}

/// A grid of free-ish values with sparse sources (254) and unknown cells (255).
std::vector<uint8_t> randomGrid(std::mt19937& rng, std::size_t cells, double density)
{
  std::vector<uint8_t> g(cells);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> v(0, 253);
  for (auto& c : g)
  {
    const double r = u(rng);
    c = r < density ? 254 : (r < 2 * density ? 255 : static_cast<uint8_t>(v(rng) % 60));
  }
  return g;
}

/// The merge the engine must do, cell by cell from brute-force distances of the original grid; the
/// cost by the rule itself (cost_fn), 0 past max_cells.
std::vector<uint8_t> mergeReference(const std::vector<uint8_t>& grid, int w, int h, std::ptrdiff_t stride,
                                    SourceRange src, DistanceWindow win, int64_t max_cells,
                                    const std::function<uint8_t(uint64_t)>& cost_fn, CostMergeRule rule)
{
  // The exhaustive search depends on the grid and the sources only: one search for the checks of one
  // grid in a row.
  static std::vector<uint8_t> last_grid;
  static std::vector<uint64_t> d;
  static int last_w = -1, last_h = -1;
  static std::ptrdiff_t last_stride = -1;
  static SourceRange last_src{0, 0};
  if (grid != last_grid || w != last_w || h != last_h || stride != last_stride || src.lo != last_src.lo ||
      src.hi != last_src.hi)
  {
    d = bruteForce(grid, w, h, stride, src);
    last_grid = grid;
    last_w = w;
    last_h = h;
    last_stride = stride;
    last_src = src;
  }
  std::vector<uint8_t> out = grid;
  const uint64_t max_sq = static_cast<uint64_t>(max_cells) * static_cast<uint64_t>(max_cells);
  for (int y = std::max(0, win.y0); y < std::min(h, win.y1); ++y)
    for (int x = std::max(0, win.x0); x < std::min(w, win.x1); ++x)
    {
      const uint64_t d2 = d[static_cast<std::size_t>(y) * w + x];
      const uint8_t c = d2 <= max_sq ? cost_fn(d2) : uint8_t{0};
      uint8_t& cell = out[static_cast<std::size_t>(y * stride + x)];
      cell = cell == rule.special ? (c >= rule.special_threshold ? c : cell) : std::max(cell, c);
    }
  return out;
}

/// The inflation rule (costmap_2d's, cost_rules.hpp) for a robot of inscribed radius 0.2256 m.
std::function<uint8_t(uint64_t)> inflationRule(double resolution, double factor)
{
  return [=](uint64_t d2) { return inflationCost(std::sqrt(static_cast<double>(d2)), resolution, 0.2256, factor); };
}

class Engine : public ::testing::TestWithParam<std::string>
{
protected:
  void SetUp() override { ASSERT_TRUE(setSimdTarget(GetParam())); }
  void TearDown() override { setSimdTarget(""); }
  unsigned seed(unsigned base) const
  {
    return base + static_cast<unsigned>(std::hash<std::string>()(GetParam()) % 1000);
  }

  /// Merges with `threads` threads and compares with the reference; returns the mismatch count.
  void checkMerge(const std::vector<uint8_t>& grid, int w, int h, std::ptrdiff_t stride, SourceRange src,
                  DistanceWindow win, int64_t max_cells, const std::function<uint8_t(uint64_t)>& cost_fn,
                  CostMergeRule rule, int threads, const std::string& what)
  {
    const DistanceCosts costs(max_cells, [&](uint64_t d2) { return cost_fn(d2); });
    const auto expected = mergeReference(grid, w, h, stride, src, win, max_cells, cost_fn, rule);
    std::vector<uint8_t> got = grid;
    distanceCostMerge(got.data(), w, h, stride, src, costs, win, rule, scratch_, threads);
    int bad = 0;
    for (std::size_t i = 0; i < got.size(); ++i)
      if (got[i] != expected[i] && bad++ < 3)
        ADD_FAILURE() << what << ": cell " << i % stride << "," << i / stride << " got " << int{got[i]} << " expected "
                      << int{expected[i]} << " (reach " << costs.reach() << ")";
    EXPECT_EQ(bad, 0) << what;
  }

  DistanceTransformScratch scratch_;
};

std::vector<std::string> targets()
{
  return simdTargets();
}
}  // namespace

TEST(SimdTargets, ListedSwitchableAndScalarLast)
{
  const auto names = simdTargets();
  ASSERT_FALSE(names.empty());
  // The scalar fallback is always compiled and always runs (Highway's SCALAR or EMU128).
  EXPECT_TRUE(names.back() == "SCALAR" || names.back() == "EMU128") << names.back();
  EXPECT_EQ(simdTarget(), names.front());  // the best one by default
  for (const auto& n : names)
  {
    ASSERT_TRUE(setSimdTarget(n));
    EXPECT_EQ(simdTarget(), n);
    EXPECT_EQ(simdTargets(), names);  // the list is what the CPU runs, not the restriction
  }
  EXPECT_FALSE(setSimdTarget("NO_SUCH_TARGET"));
  EXPECT_EQ(simdTarget(), names.back());  // unchanged
  ASSERT_TRUE(setSimdTarget(""));
  EXPECT_EQ(simdTarget(), names.front());
}

TEST(DistanceCosts, ReachIsTheLastNonZeroCost)
{
  // 100 - d2 for d2 < 100: the last non-zero cost is at d2 = 99, 10 cells (10^2 >= 99 > 9^2).
  const DistanceCosts c(50, [](uint64_t d2) { return static_cast<uint8_t>(d2 < 100 ? 100 - d2 : 0); });
  EXPECT_TRUE(c.any());
  EXPECT_EQ(c.reachSquared(), 99u);
  EXPECT_EQ(c.reach(), 10);
  EXPECT_EQ(c.at(0), 100);
  EXPECT_EQ(c.at(99), 1);
  EXPECT_EQ(c.at(100), 0);
  // The cap cuts first: max_cells 3 -> d2 <= 9.
  const DistanceCosts capped(3, [](uint64_t d2) { return static_cast<uint8_t>(d2 < 100 ? 100 - d2 : 0); });
  EXPECT_EQ(capped.reachSquared(), 9u);
  EXPECT_EQ(capped.reach(), 3);
  EXPECT_EQ(capped.at(10), 0);
  EXPECT_FALSE(DistanceCosts(5, [](uint64_t) { return uint8_t{0}; }).any());
  EXPECT_FALSE(DistanceCosts().any());
  EXPECT_THROW(DistanceCosts(5, [](uint64_t d2) { return static_cast<uint8_t>(d2 == 3 ? 9 : 5); }),
               std::invalid_argument);
  EXPECT_THROW(DistanceCosts(-1, [](uint64_t) { return uint8_t{1}; }), std::invalid_argument);
}

TEST(DistanceCosts, InflationReachIsWhereTheCostRoundsToZero)
{
  // With factor 3 the cost (uchar)(252 exp(-3 (d - 0.2256))) is 0 once 252 exp(...) < 1, i.e. past
  // d = 0.2256 + ln(252) / 3 = 2.0687 m = 41.37 cells at 0.05 m: the last squared cell distance with a
  // cost is floor(41.37^2) = 1711, and the band is 42 cells (41^2 = 1681 < 1711 <= 42^2).
  const double res = 0.05, factor = 3.0;
  const double limit_cells = (0.2256 + std::log(252.0) / factor) / res;  // 41.37 cells
  const uint64_t last = static_cast<uint64_t>(std::floor(limit_cells * limit_cells));
  const DistanceCosts c(60, inflationRule(res, factor));
  EXPECT_EQ(c.reachSquared(), last);
  EXPECT_EQ(c.reach(), 42);  // 41^2 = 1681 < 1711 = floor(41.37^2) <= 42^2
  // A radius below that limit cuts first.
  EXPECT_EQ(DistanceCosts(20, inflationRule(res, factor)).reach(), 20);
}

// Every radius and resolution of the benchmark sweep, three scaling factors (the factor-bound reach at
// 3 and 10, the radius-bound one at 1), against the exhaustive search.
TEST_P(Engine, SweepRadiiAndResolutionsEqualBruteForce)
{
  std::mt19937 rng(seed(7));
  for (const double res : {0.025, 0.05, 0.1})
    for (const double radius : {0.3, 0.55, 1.0, 2.0, 3.0})
      for (const double factor : {1.0, 3.0, 10.0})
      {
        const int64_t cells = static_cast<int64_t>(std::ceil(radius / res));
        // Wide enough for the band to matter on every side, sparse enough for long distances.
        const int w = static_cast<int>(std::min<int64_t>(2 * cells + 37, 280));
        const int h = static_cast<int>(std::min<int64_t>(2 * cells + 21, 170));
        const auto grid = randomGrid(rng, static_cast<std::size_t>(w) * h, 0.6 / (cells + 3));
        const double r = res, f = factor;
        const auto rule_fn = [&](uint64_t d2)
        { return d2 > static_cast<uint64_t>(cells * cells) ? uint8_t{0} : inflationRule(r, f)(d2); };
        checkMerge(
            grid, w, h, w, SourceRange{254, 254}, DistanceWindow{0, 0, w, h}, cells, rule_fn, CostMergeRule{255, 253},
            1,
            "res " + std::to_string(res) + " radius " + std::to_string(radius) + " factor " + std::to_string(factor));
      }
}

// The switches between the engine's paths: reach 14 / 15 / 30 / 31 / 46 / 47 (one to four tables per
// offset in the cost domain: bands of 16 vertical distances up to reach + 1), 59 / 60 (cost domain /
// 16-bit) and 254 / 255 (16-bit / envelope); on AVX3_DL also 30 / 31 (16-entry tables / one permute),
// 62 / 63 (a 64-entry / 128-entry permute) and 126 / 127 (permute / 16-bit). A flat cost, so that the
// reach is exactly the cap.
TEST_P(Engine, PathBoundariesEqualBruteForce)
{
  std::mt19937 rng(seed(21));
  for (const int64_t cap : {0,  1,  2,  13, 14, 15, 16, 29,  30,  31,  32,  44,  45,  46,  47,
                            48, 59, 60, 61, 62, 63, 64, 125, 126, 127, 128, 253, 254, 255, 300})
  {
    const int w = cap > 100 ? 300 : 97, h = cap > 100 ? 260 : 61;
    const auto grid = randomGrid(rng, static_cast<std::size_t>(w) * h, cap > 100 ? 0.00005 : 0.01);
    // A cost falling in steps, so that different distances give different costs.
    const auto fn = [cap](uint64_t d2) -> uint8_t
    {
      if (d2 > static_cast<uint64_t>(cap * cap)) return 0;
      return static_cast<uint8_t>(250 - (d2 * 240) / static_cast<uint64_t>(cap * cap + 1));
    };
    checkMerge(grid, w, h, w, SourceRange{254, 255}, DistanceWindow{0, 0, w, h}, cap, fn, CostMergeRule{255, 253}, 1,
               "cap " + std::to_string(cap));
  }
}

// From reach 15 a block is costed from the columns that can matter to it (a column next to one nearer
// a source is left out) when there are few of them, otherwise offset by offset. One grid with both: a
// dense left part (many columns per block), and shapes where most columns are left out: a long flat
// wall (only its ends), a staircase diagonal, single sources, and the vertical distances 3 5 3 and
// 3 3 (a column between or beside equal ones).
TEST_P(Engine, PaintedAndScannedBlocksEqualBruteForce)
{
  std::mt19937 rng(seed(31));
  const int w = 420, h = 150;
  std::vector<uint8_t> grid(static_cast<std::size_t>(w) * h, 0);
  {
    auto set = [&](int x, int y, uint8_t v)
    {
      if (x >= 0 && x < w && y >= 0 && y < h) grid[static_cast<std::size_t>(y) * w + x] = v;
    };
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < 110; ++x)
        if (u(rng) < 0.2) set(x, y, u(rng) < 0.8 ? 254 : 255);
    for (int x = 140; x < 330; ++x)
      set(x, 30, 254);  // flat wall
    for (int t = 0; t < 120; ++t)
      set(150 + t, 60 + t / 3, 254);  // staircase
    set(200, 117, 254);               // 3 5 3 at row 120 (columns 200-202)
    set(201, 115, 254);
    set(202, 117, 254);
    set(230, 117, 254);  // 3 3 at row 120
    set(231, 117, 254);
    for (int x = 340; x < w; x += 23)
      set(x, 20 + (x * 7) % 110, 254);  // single sources
  }
  for (const int64_t cap : {15, 16, 20, 22, 31, 40, 59, 60, 62, 63, 100, 126})
  {
    const auto fn = [cap](uint64_t d2) -> uint8_t
    {
      if (d2 > static_cast<uint64_t>(cap * cap)) return 0;
      return static_cast<uint8_t>(250 - (d2 * 240) / static_cast<uint64_t>(cap * cap + 1));
    };
    checkMerge(grid, w, h, w, SourceRange{254, 254}, DistanceWindow{0, 0, w, h}, cap, fn, CostMergeRule{255, 253}, 1,
               "cap " + std::to_string(cap));
    checkMerge(grid, w, h, w, SourceRange{254, 254}, DistanceWindow{37, 11, w - 5, h - 3}, cap, fn,
               CostMergeRule{255, 253}, 2, "cap " + std::to_string(cap) + ", window, 2 threads");
  }
}

// Sub-windows of a grid with a row stride: sources outside the window count, cells outside stay.
TEST_P(Engine, WindowsAndStrideEqualBruteForce)
{
  std::mt19937 rng(seed(3));
  for (int trial = 0; trial < 24; ++trial)
  {
    const int w = 20 + static_cast<int>(rng() % 150), h = 10 + static_cast<int>(rng() % 90);
    const int stride = w + static_cast<int>(rng() % 9);
    const auto grid = randomGrid(rng, static_cast<std::size_t>(stride) * h, 0.004 + 0.01 * (rng() % 3));
    const int64_t cap = static_cast<int64_t>(rng() % 40);
    DistanceWindow win{static_cast<int>(rng() % w) - 5, static_cast<int>(rng() % h) - 5, 0, 0};
    win.x1 = win.x0 + 1 + static_cast<int>(rng() % w);
    win.y1 = win.y0 + 1 + static_cast<int>(rng() % h);
    const CostMergeRule rule{static_cast<uint8_t>(trial % 2 ? 255 : 200), static_cast<uint8_t>(1 + rng() % 253)};
    const auto fn = [cap](uint64_t d2) -> uint8_t
    { return d2 > static_cast<uint64_t>(cap * cap) ? 0 : static_cast<uint8_t>(254 - std::min<uint64_t>(d2, 200)); };
    checkMerge(grid, w, h, stride, SourceRange{254, 255}, win, cap, fn, rule, 1, "trial " + std::to_string(trial));
  }
}

// Bands of rows on several threads give exactly the single-thread (and brute-force) result.
TEST_P(Engine, ThreadsGiveTheSameResult)
{
  std::mt19937 rng(seed(5));
  const int w = 230, h = 400;
  const auto grid = randomGrid(rng, static_cast<std::size_t>(w) * h, 0.003);
  for (const int64_t cap : {9, 30})
    for (const int threads : {1, 2, 3, 4})
    {
      const auto fn = [cap](uint64_t d2) -> uint8_t
      { return d2 > static_cast<uint64_t>(cap * cap) ? 0 : static_cast<uint8_t>(252 - d2 / 8); };
      checkMerge(grid, w, h, w, SourceRange{254, 255}, DistanceWindow{0, 13, w, h - 7}, cap, fn,
                 CostMergeRule{255, 253}, threads,
                 "cap " + std::to_string(cap) + " threads " + std::to_string(threads));
    }
}

// The streamed form: every window row exactly once, with the costs of the brute-force distances.
TEST_P(Engine, RowsEqualBruteForce)
{
  std::mt19937 rng(seed(11));
  for (const int64_t cap : {0, 5, 14, 15, 31, 62, 63, 126, 260})
  {
    const int w = 150 + static_cast<int>(rng() % 40), h = 120;
    auto grid = randomGrid(rng, static_cast<std::size_t>(w) * h, cap > 100 ? 0.0002 : 0.004);
    // Long identical rows (what lanes look like), so that row reuse is exercised.
    for (int y = 40; y < 80; ++y)
      std::copy(grid.begin() + 40 * w, grid.begin() + 41 * w, grid.begin() + static_cast<std::ptrdiff_t>(y) * w);
    const auto fn = [cap](uint64_t d2) -> uint8_t
    { return d2 > static_cast<uint64_t>(cap * cap) ? 0 : static_cast<uint8_t>(200 - std::min<uint64_t>(d2, 199)); };
    const DistanceCosts costs(cap, fn);
    const auto d = bruteForce(grid, w, h, w, SourceRange{254, 254});
    const DistanceWindow win{3, 2, w - 1, h - 5};
    std::vector<int> seen(static_cast<std::size_t>(h), 0);
    int bad = 0;
    distanceCostRows(grid.data(), w, h, w, SourceRange{254, 254}, costs, win, scratch_,
                     [&](int y, const uint8_t* row)
                     {
                       ASSERT_GE(y, win.y0);
                       ASSERT_LT(y, win.y1);
                       ++seen[static_cast<std::size_t>(y)];
                       for (int x = win.x0; x < win.x1; ++x)
                       {
                         const uint64_t d2 = d[static_cast<std::size_t>(y) * w + x];
                         const uint8_t expected = d2 <= static_cast<uint64_t>(cap * cap) ? fn(d2) : uint8_t{0};
                         if (row[x - win.x0] != expected && bad++ < 3)
                           ADD_FAILURE() << "cap " << cap << " cell " << x << "," << y << " got "
                                         << int{row[x - win.x0]} << " expected " << int{expected};
                       }
                     });
    EXPECT_EQ(bad, 0);
    for (int y = 0; y < h; ++y)
      EXPECT_EQ(seen[static_cast<std::size_t>(y)], y >= win.y0 && y < win.y1 ? 1 : 0) << "row " << y;
  }
}

TEST_P(Engine, EmptyAndDegenerateInputs)
{
  const auto fn = [](uint64_t d2) { return static_cast<uint8_t>(d2 <= 4 ? 200 : 0); };
  const DistanceCosts costs(2, fn);
  std::vector<uint8_t> g = {254, 0, 0, 0};
  distanceCostMerge(g.data(), 0, 0, 0, SourceRange{254, 254}, costs, DistanceWindow{0, 0, 0, 0}, CostMergeRule{},
                    scratch_);
  distanceCostMerge(g.data(), 4, 1, 4, SourceRange{254, 254}, costs, DistanceWindow{3, 0, 1, 1}, CostMergeRule{},
                    scratch_);  // empty window
  EXPECT_EQ(g, (std::vector<uint8_t>{254, 0, 0, 0}));
  distanceCostMerge(g.data(), 4, 1, 4, SourceRange{254, 254}, costs, DistanceWindow{-9, -9, 99, 99}, CostMergeRule{},
                    scratch_);  // clipped
  EXPECT_EQ(g, (std::vector<uint8_t>{254, 200, 200, 0}));
  // Nothing costs anything: the grid stays, the rows are zero.
  std::vector<uint8_t> h = {254, 3, 0, 255};
  distanceCostMerge(h.data(), 4, 1, 4, SourceRange{254, 254}, DistanceCosts(), DistanceWindow{0, 0, 4, 1},
                    CostMergeRule{}, scratch_);
  EXPECT_EQ(h, (std::vector<uint8_t>{254, 3, 0, 255}));
  int rows = 0;
  distanceCostRows(h.data(), 4, 1, 4, SourceRange{254, 254}, DistanceCosts(), DistanceWindow{0, 0, 4, 1}, scratch_,
                   [&](int, const uint8_t* row)
                   {
                     ++rows;
                     EXPECT_EQ(std::count(row, row + 4, 0), 4);
                   });
  EXPECT_EQ(rows, 1);
  EXPECT_THROW(distanceCostMerge(h.data(), 4, 1, 4, SourceRange{254, 254}, costs, DistanceWindow{0, 0, 4, 1},
                                 CostMergeRule{255, 0}, scratch_),
               std::invalid_argument);
  EXPECT_THROW(distanceCostMerge(h.data(), 4, 1, 4, SourceRange{254, 254}, costs, DistanceWindow{0, 0, 4, 1},
                                 CostMergeRule{}, scratch_, 0),
               std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Targets, Engine, ::testing::ValuesIn(targets()),
                         [](const ::testing::TestParamInfo<std::string>& info)
                         {
                           std::string name = info.param;
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });
