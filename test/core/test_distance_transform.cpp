#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "costmap_layers/core/distance_transform.hpp"

using namespace costmap_layers;

namespace
{
/// Squared distance to the nearest source by exhaustive search, or kFarSquaredDistance.
std::vector<uint32_t> bruteForce(const std::vector<uint8_t>& grid, int w, int h, SourceRange src)
{
  std::vector<uint32_t> out(static_cast<std::size_t>(w) * h, kFarSquaredDistance);
  std::vector<std::pair<int, int>> sources;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (src.contains(grid[static_cast<std::size_t>(y) * w + x])) sources.emplace_back(x, y);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
    {
      uint32_t best = kFarSquaredDistance;
      for (const auto& s : sources)
      {
        const uint32_t d = static_cast<uint32_t>((s.first - x) * (s.first - x) + (s.second - y) * (s.second - y));
        best = std::min(best, d);
      }
      out[static_cast<std::size_t>(y) * w + x] = best;
    }
  return out;
}

std::vector<uint8_t> randomGrid(std::mt19937& rng, int w, int h, double density)
{
  std::vector<uint8_t> g(static_cast<std::size_t>(w) * h);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> v(0, 253);
  for (auto& c : g)
  {
    const double r = u(rng);
    c = r < density ? 254 : (r < 2 * density ? 255 : static_cast<uint8_t>(v(rng)));
  }
  return g;
}

/// Runs a banded engine over the window and collects its rows into a w x h image (far outside).
template <class T>
std::vector<uint32_t> banded(const std::vector<uint8_t>& grid, int w, int h, SourceRange src, int cap,
                             DistanceWindow win, DistanceTransformScratch& scratch)
{
  std::vector<uint32_t> out(static_cast<std::size_t>(w) * h, kFarSquaredDistance);
  int expected_y = win.y0;
  auto sink = [&](int y, const T* d)
  {
    EXPECT_EQ(y, expected_y++);
    for (int x = win.x0; x < win.x1; ++x)
    {
      const uint32_t v = d[x - win.x0];
      out[static_cast<std::size_t>(y) * w + x] = v > static_cast<uint32_t>(cap * cap) ? kFarSquaredDistance : v;
    }
  };
  if constexpr (sizeof(T) == 1)
    cappedSquaredDistanceRows8(grid.data(), w, h, w, src, cap, win, scratch, sink);
  else
    cappedSquaredDistanceRows16(grid.data(), w, h, w, src, cap, win, scratch, sink);
  EXPECT_EQ(expected_y, win.y1);
  return out;
}

uint32_t capped(uint32_t d, uint32_t cap_sq)
{
  return d > cap_sq ? kFarSquaredDistance : d;
}
}  // namespace

TEST(DistanceTransform, SingleSourceIsExact)
{
  const int w = 7, h = 5;
  std::vector<uint8_t> g(w * h, 0);
  g[2 * w + 3] = 1;
  std::vector<uint32_t> out(w * h);
  DistanceTransformScratch scratch;
  squaredDistanceTransform(g.data(), w, h, out.data(), scratch);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      EXPECT_EQ(out[y * w + x], static_cast<uint32_t>((x - 3) * (x - 3) + (y - 2) * (y - 2)));
}

TEST(DistanceTransform, NoSourceIsFar)
{
  std::vector<uint8_t> g(12, 0);
  std::vector<uint32_t> out(12, 0);
  DistanceTransformScratch scratch;
  squaredDistanceTransform(g.data(), 4, 3, out.data(), scratch);
  for (uint32_t v : out)
    EXPECT_EQ(v, kFarSquaredDistance);
}

TEST(DistanceTransform, EmptyGridDoesNothing)
{
  DistanceTransformScratch scratch;
  squaredDistanceTransform(nullptr, 0, 0, nullptr, scratch);
  int calls = 0;
  cappedSquaredDistanceRows8(nullptr, 0, 0, 0, SourceRange{254, 254}, 3, DistanceWindow{0, 0, 0, 0}, scratch,
                             [&](int, const uint8_t*) { ++calls; });
  EXPECT_EQ(calls, 0);
}

TEST(DistanceTransform, ExactMatchesBruteForceOnRandomGrids)
{
  std::mt19937 rng(42);
  DistanceTransformScratch scratch;
  for (int trial = 0; trial < 60; ++trial)
  {
    const int w = 1 + static_cast<int>(rng() % 40), h = 1 + static_cast<int>(rng() % 40);
    const double density = (trial % 6) * 0.04;
    const auto grid = randomGrid(rng, w, h, density);
    const SourceRange src = trial % 2 ? SourceRange{254, 254} : SourceRange{254, 255};
    const auto ref = bruteForce(grid, w, h, src);
    std::vector<uint32_t> out(grid.size());
    squaredDistanceTransform(grid.data(), w, h, w, src, out.data(), w, kFarSquaredDistance, scratch);
    ASSERT_EQ(out, ref) << "trial " << trial << " " << w << "x" << h;
    // With a cap.
    const uint32_t cap_sq = static_cast<uint32_t>(rng() % 50);
    squaredDistanceTransform(grid.data(), w, h, w, src, out.data(), w, cap_sq, scratch);
    for (std::size_t i = 0; i < out.size(); ++i)
      ASSERT_EQ(out[i], capped(ref[i], cap_sq));
  }
}

TEST(DistanceTransform, ExactWorksOnSubWindowWithStrides)
{
  std::mt19937 rng(7);
  const int W = 50, H = 40;
  const auto grid = randomGrid(rng, W, H, 0.03);
  const int x0 = 5, y0 = 7, w = 31, h = 22;
  std::vector<uint8_t> sub(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      sub[y * w + x] = grid[(y0 + y) * W + x0 + x];
  const SourceRange src{254, 254};
  const auto ref = bruteForce(sub, w, h, src);
  const int out_stride = 37;
  std::vector<uint32_t> out(static_cast<std::size_t>(out_stride) * h, 12345u);
  DistanceTransformScratch scratch;
  squaredDistanceTransform(grid.data() + y0 * W + x0, w, h, W, src, out.data(), out_stride, kFarSquaredDistance,
                           scratch);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
      ASSERT_EQ(out[y * out_stride + x], ref[y * w + x]);
    for (int x = w; x < out_stride; ++x)
      ASSERT_EQ(out[y * out_stride + x], 12345u);  // untouched
  }
}

TEST(DistanceTransform, LargeDistancesDoNotOverflow)
{
  const int w = 3000, h = 2;
  std::vector<uint8_t> g(w * h, 0);
  g[0] = 1;
  std::vector<uint32_t> out(w * h);
  DistanceTransformScratch scratch;
  squaredDistanceTransform(g.data(), w, h, out.data(), scratch);
  EXPECT_EQ(out[w - 1], static_cast<uint32_t>((w - 1) * (w - 1)));
  EXPECT_EQ(out[2 * w - 1], static_cast<uint32_t>((w - 1) * (w - 1) + 1));
}

class BandedTest : public ::testing::TestWithParam<bool>
{
protected:
  void SetUp() override { setDistanceTransformSimd(GetParam()); }
  void TearDown() override { setDistanceTransformSimd(true); }
};

TEST_P(BandedTest, MatchesBruteForceOnWindows)
{
  std::mt19937 rng(GetParam() ? 11 : 12);
  DistanceTransformScratch scratch;
  for (int trial = 0; trial < 80; ++trial)
  {
    const int w = 1 + static_cast<int>(rng() % 70), h = 1 + static_cast<int>(rng() % 70);
    const auto grid = randomGrid(rng, w, h, (trial % 5) * 0.01 + 0.002);
    const SourceRange src = trial % 3 ? SourceRange{254, 254} : SourceRange{254, 255};
    const auto ref = bruteForce(grid, w, h, src);
    DistanceWindow win;
    win.x0 = static_cast<int>(rng() % static_cast<unsigned>(w));
    win.y0 = static_cast<int>(rng() % static_cast<unsigned>(h));
    win.x1 = win.x0 + 1 + static_cast<int>(rng() % static_cast<unsigned>(w - win.x0));
    win.y1 = win.y0 + 1 + static_cast<int>(rng() % static_cast<unsigned>(h - win.y0));
    if (trial % 4 == 0) win = DistanceWindow{0, 0, w, h};
    const int cap8 = static_cast<int>(rng() % (kMaxBandedCap8 + 1));
    const auto out8 = banded<uint8_t>(grid, w, h, src, cap8, win, scratch);
    const int cap16 = static_cast<int>(rng() % 40);
    const auto out16 = banded<uint16_t>(grid, w, h, src, cap16, win, scratch);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
      {
        const std::size_t i = static_cast<std::size_t>(y) * w + x;
        const bool inside = x >= win.x0 && x < win.x1 && y >= win.y0 && y < win.y1;
        const uint32_t e8 = inside ? capped(ref[i], static_cast<uint32_t>(cap8 * cap8)) : kFarSquaredDistance;
        const uint32_t e16 = inside ? capped(ref[i], static_cast<uint32_t>(cap16 * cap16)) : kFarSquaredDistance;
        ASSERT_EQ(out8[i], e8) << "trial " << trial << " cell " << x << "," << y << " cap " << cap8;
        ASSERT_EQ(out16[i], e16) << "trial " << trial << " cell " << x << "," << y << " cap " << cap16;
      }
  }
}

TEST_P(BandedTest, LargestCapsAreExact)
{
  const int w = 400, h = 390;
  std::vector<uint8_t> g(static_cast<std::size_t>(w) * h, 0);
  g[200 * w + 190] = 254;
  g[10 * w + 3] = 254;
  const auto ref = bruteForce(g, w, h, SourceRange{254, 254});
  DistanceTransformScratch scratch;
  const auto out8 =
      banded<uint8_t>(g, w, h, SourceRange{254, 254}, kMaxBandedCap8, DistanceWindow{0, 0, w, h}, scratch);
  const auto out16 =
      banded<uint16_t>(g, w, h, SourceRange{254, 254}, kMaxBandedCap16, DistanceWindow{0, 0, w, h}, scratch);
  for (std::size_t i = 0; i < ref.size(); ++i)
  {
    ASSERT_EQ(out8[i], capped(ref[i], kMaxBandedCap8 * kMaxBandedCap8));
    ASSERT_EQ(out16[i], capped(ref[i], kMaxBandedCap16 * kMaxBandedCap16));
  }
}

INSTANTIATE_TEST_SUITE_P(Kernels, BandedTest, ::testing::Values(true, false),
                         [](const ::testing::TestParamInfo<bool>& info)
                         { return info.param ? std::string("Dispatched") : std::string("Portable"); });

TEST(DistanceTransform, DispatchedAndPortableAgreeOnLargeGrid)
{
  std::mt19937 rng(3);
  const int w = 517, h = 301;
  const auto grid = randomGrid(rng, w, h, 0.004);
  DistanceTransformScratch scratch;
  setDistanceTransformSimd(false);
  EXPECT_STREQ(distanceTransformKernel(), "portable");
  const auto a = banded<uint8_t>(grid, w, h, SourceRange{254, 254}, 11, DistanceWindow{3, 4, 500, 290}, scratch);
  const auto a16 = banded<uint16_t>(grid, w, h, SourceRange{254, 255}, 25, DistanceWindow{0, 0, w, h}, scratch);
  setDistanceTransformSimd(true);
  const auto b = banded<uint8_t>(grid, w, h, SourceRange{254, 254}, 11, DistanceWindow{3, 4, 500, 290}, scratch);
  const auto b16 = banded<uint16_t>(grid, w, h, SourceRange{254, 255}, 25, DistanceWindow{0, 0, w, h}, scratch);
  EXPECT_EQ(a, b);
  EXPECT_EQ(a16, b16);
}

TEST(DistanceTransform, CapAboveLimitThrows)
{
  DistanceTransformScratch scratch;
  std::vector<uint8_t> g(4, 0);
  EXPECT_THROW(cappedSquaredDistanceRows8(g.data(), 2, 2, 2, SourceRange{}, kMaxBandedCap8 + 1,
                                          DistanceWindow{0, 0, 2, 2}, scratch, [](int, const uint8_t*) {}),
               std::invalid_argument);
  EXPECT_THROW(cappedSquaredDistanceRows16(g.data(), 2, 2, 2, SourceRange{}, kMaxBandedCap16 + 1,
                                           DistanceWindow{0, 0, 2, 2}, scratch, [](int, const uint16_t*) {}),
               std::invalid_argument);
}

namespace
{
/// A random non-increasing cost table of cap^2 + 1 entries.
std::vector<uint8_t> randomCosts(std::mt19937& rng, int cap)
{
  std::vector<uint8_t> costs(static_cast<std::size_t>(cap * cap + 1));
  int v = 200 + static_cast<int>(rng() % 56);
  for (auto& c : costs)
  {
    c = static_cast<uint8_t>(v);
    if (rng() % 3 == 0) v = std::max(0, v - static_cast<int>(rng() % 40));
  }
  return costs;
}

/// What cappedCostMerge8 must leave in the grid, from brute-force distances on the original grid.
std::vector<uint8_t> mergeReference(const std::vector<uint8_t>& grid, int w, int h, SourceRange src, int cap,
                                    DistanceWindow win, const std::vector<uint8_t>& costs, CostMergeRule rule)
{
  const auto d = bruteForce(grid, w, h, src);
  std::vector<uint8_t> out = grid;
  for (int y = std::max(0, win.y0); y < std::min(h, win.y1); ++y)
    for (int x = std::max(0, win.x0); x < std::min(w, win.x1); ++x)
    {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      const uint8_t c = d[i] <= static_cast<uint32_t>(cap * cap) ? costs[d[i]] : uint8_t{0};
      const uint8_t old = grid[i];
      out[i] = old == rule.special ? (c >= rule.special_threshold ? c : old) : std::max(old, c);
    }
  return out;
}

class CostMergeTest : public ::testing::TestWithParam<std::string>
{
protected:
  void SetUp() override { ASSERT_TRUE(setDistanceTransformKernel(GetParam().c_str())); }
  void TearDown() override { setDistanceTransformKernel(nullptr); }
};

std::vector<std::string> kernelNames()
{
  std::vector<std::string> names;
  for (const char* k : distanceTransformKernels())
    names.emplace_back(k);
  return names;
}
}  // namespace

TEST(DistanceTransform, KernelChoice)
{
  const auto names = distanceTransformKernels();
  ASSERT_FALSE(names.empty());
  EXPECT_STREQ(names.front(), "portable");
  for (const char* k : names)
  {
    ASSERT_TRUE(setDistanceTransformKernel(k));
    EXPECT_STREQ(distanceTransformKernel(), k);
  }
  EXPECT_FALSE(setDistanceTransformKernel("no-such-kernel"));
  EXPECT_STREQ(distanceTransformKernel(), names.back());  // unchanged
  setDistanceTransformSimd(false);
  EXPECT_STREQ(distanceTransformKernel(), "portable");
  setDistanceTransformSimd(true);
  EXPECT_STREQ(distanceTransformKernel(), names.back());  // the widest
  ASSERT_TRUE(setDistanceTransformKernel(""));
  EXPECT_STREQ(distanceTransformKernel(), names.back());
}

TEST_P(CostMergeTest, MatchesBruteForceOnWindows)
{
  std::mt19937 rng(static_cast<unsigned>(std::hash<std::string>()(GetParam()) % 1000));
  DistanceTransformScratch scratch;
  for (int trial = 0; trial < 120; ++trial)
  {
    const int w = 1 + static_cast<int>(rng() % 150), h = 1 + static_cast<int>(rng() % 60);
    const auto grid = randomGrid(rng, w, h, (trial % 5) * 0.01 + 0.002);
    const SourceRange src = trial % 3 ? SourceRange{254, 254} : SourceRange{254, 255};
    DistanceWindow win;
    win.x0 = static_cast<int>(rng() % static_cast<unsigned>(w));
    win.y0 = static_cast<int>(rng() % static_cast<unsigned>(h));
    win.x1 = win.x0 + 1 + static_cast<int>(rng() % static_cast<unsigned>(w - win.x0));
    win.y1 = win.y0 + 1 + static_cast<int>(rng() % static_cast<unsigned>(h - win.y0));
    if (trial % 4 == 0) win = DistanceWindow{0, 0, w, h};
    if (trial % 7 == 0) win = DistanceWindow{-5, -3, w + 4, h + 9};  // clipped to the grid
    const int cap = static_cast<int>(rng() % (kMaxBandedCap8 + 1));
    const auto costs = randomCosts(rng, cap);
    CostMergeRule rule;
    rule.special = trial % 2 ? uint8_t{255} : static_cast<uint8_t>(rng() % 256);
    rule.special_threshold = static_cast<uint8_t>(1 + rng() % 255);
    const auto expected = mergeReference(grid, w, h, src, cap, win, costs, rule);
    auto out = grid;
    cappedCostMerge8(out.data(), w, h, w, src, cap, win, costs.data(), rule, scratch);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        ASSERT_EQ(out[static_cast<std::size_t>(y) * w + x], expected[static_cast<std::size_t>(y) * w + x])
            << "trial " << trial << " cell " << x << "," << y << " cap " << cap << " grid " << w << "x" << h;
  }
}

TEST_P(CostMergeTest, AgreesWithPortableOnLargeGridWithStride)
{
  std::mt19937 rng(5);
  const int w = 1290, h = 333, stride = 1301;  // several stripes, a partial last block
  std::vector<uint8_t> grid(static_cast<std::size_t>(stride) * h);
  const auto cells = randomGrid(rng, stride, h, 0.003);
  std::copy(cells.begin(), cells.end(), grid.begin());
  const auto costs = randomCosts(rng, kMaxBandedCap8);
  const DistanceWindow win{7, 3, 1283, 330};
  const CostMergeRule rule{255, 253};
  DistanceTransformScratch scratch;
  auto mine = grid;
  cappedCostMerge8(mine.data(), w, h, stride, SourceRange{254, 255}, kMaxBandedCap8, win, costs.data(), rule, scratch);
  ASSERT_TRUE(setDistanceTransformKernel("portable"));
  auto portable = grid;
  cappedCostMerge8(portable.data(), w, h, stride, SourceRange{254, 255}, kMaxBandedCap8, win, costs.data(), rule,
                   scratch);
  EXPECT_EQ(mine, portable);
  // Columns past the grid's width (inside the stride) are never touched.
  for (int y = 0; y < h; ++y)
    for (int x = w; x < stride; ++x)
      ASSERT_EQ(mine[static_cast<std::size_t>(y) * stride + x], grid[static_cast<std::size_t>(y) * stride + x]);
}

TEST_P(CostMergeTest, CostRowsMatchBruteForceAndLeaveTheGridAlone)
{
  std::mt19937 rng(static_cast<unsigned>(std::hash<std::string>()(GetParam()) % 1000 + 17));
  DistanceTransformScratch scratch;
  for (int trial = 0; trial < 100; ++trial)
  {
    const int w = 1 + static_cast<int>(rng() % 200), h = 1 + static_cast<int>(rng() % 50);
    const int stride = w + static_cast<int>(rng() % 5);
    const auto cells = randomGrid(rng, stride, h, (trial % 5) * 0.02 + 0.002);
    const SourceRange src = trial % 3 ? SourceRange{254, 254} : SourceRange{254, 255};
    std::vector<uint8_t> tight(static_cast<std::size_t>(w) * h);  // the same cells without the stride
    for (int y = 0; y < h; ++y)
      std::copy_n(cells.begin() + static_cast<std::ptrdiff_t>(y) * stride, w,
                  tight.begin() + static_cast<std::ptrdiff_t>(y) * w);
    DistanceWindow win;
    win.x0 = static_cast<int>(rng() % static_cast<unsigned>(w));
    win.y0 = static_cast<int>(rng() % static_cast<unsigned>(h));
    win.x1 = win.x0 + 1 + static_cast<int>(rng() % static_cast<unsigned>(w - win.x0));
    win.y1 = win.y0 + 1 + static_cast<int>(rng() % static_cast<unsigned>(h - win.y0));
    if (trial % 4 == 0) win = DistanceWindow{0, 0, w, h};
    if (trial % 7 == 0) win = DistanceWindow{-5, -3, w + 4, h + 9};  // clipped to the grid
    const int x0 = std::max(0, win.x0), x1 = std::min(w, win.x1);
    const int y0 = std::max(0, win.y0), y1 = std::min(h, win.y1);
    const int cap = static_cast<int>(rng() % (kMaxBandedCap8 + 1));
    const auto costs = randomCosts(rng, cap);
    const auto d = bruteForce(tight, w, h, src);
    std::vector<int> calls(static_cast<std::size_t>(h), 0);
    cappedCostRows8(cells.data(), w, h, stride, src, cap, win, costs.data(), scratch,
                    [&](int y, const uint8_t* row)
                    {
                      ASSERT_GE(y, y0);
                      ASSERT_LT(y, y1);
                      ++calls[static_cast<std::size_t>(y)];
                      for (int x = x0; x < x1; ++x)
                      {
                        const uint32_t d2 = d[static_cast<std::size_t>(y) * w + x];
                        const uint8_t expected = d2 <= static_cast<uint32_t>(cap * cap) ? costs[d2] : uint8_t{0};
                        ASSERT_EQ(row[x - x0], expected) << "trial " << trial << " cell " << x << "," << y << " cap "
                                                         << cap << " grid " << w << "x" << h;
                      }
                    });
    for (int y = 0; y < h; ++y)
      ASSERT_EQ(calls[static_cast<std::size_t>(y)], y >= y0 && y < y1 ? 1 : 0) << y;
  }
  // Runs of identical rows (whose costs are reused) between rows that differ only in their last or
  // first column.
  {
    const int w = 300, h = 200;
    std::vector<uint8_t> grid(static_cast<std::size_t>(w) * h, 0);
    for (int y = 0; y < h; ++y)
    {
      uint8_t* row = grid.data() + static_cast<std::size_t>(y) * w;
      const int kind = y % 41;
      if (kind < 30)
      {
        row[10] = row[11] = row[150] = 254;
        if (kind >= 20) row[w - 1] = 254;
        if (kind == 25) row[0] = 254;
      }
      if (y == 133) std::fill(row, row + w, uint8_t{254});
    }
    const auto d = bruteForce(grid, w, h, SourceRange{254, 254});
    for (const int cap : {3, kMaxBandedCap8})
    {
      const auto costs = randomCosts(rng, cap);
      int rows = 0;
      cappedCostRows8(grid.data(), w, h, w, SourceRange{254, 254}, cap, DistanceWindow{0, 0, w, h}, costs.data(),
                      scratch,
                      [&](int y, const uint8_t* row)
                      {
                        ++rows;
                        for (int x = 0; x < w; ++x)
                        {
                          const uint32_t d2 = d[static_cast<std::size_t>(y) * w + x];
                          const uint8_t expected = d2 <= static_cast<uint32_t>(cap * cap) ? costs[d2] : uint8_t{0};
                          ASSERT_EQ(row[x], expected) << "repeated rows, cell " << x << "," << y << " cap " << cap;
                        }
                      });
      EXPECT_EQ(rows, h);
    }
  }
  // The same over several stripes of a wide grid, against cappedCostMerge8 (brute-force checked above):
  // merged into the grid itself, non-source cells (0) end up with the cost.
  {
    const int w = 5000, h = 150;
    std::vector<uint8_t> grid(static_cast<std::size_t>(w) * h, 0);
    for (int y = 0; y < h; ++y)
    {
      uint8_t* row = grid.data() + static_cast<std::size_t>(y) * w;
      if (y % 23 < 15)
        for (int x = 7; x < w; x += 97)
          row[x] = 254;
      if (y % 23 == 9) row[w - 1] = 254;
      if (y % 61 == 5) std::fill(row, row + w, uint8_t{254});
    }
    const auto costs = randomCosts(rng, kMaxBandedCap8);
    auto merged = grid;
    cappedCostMerge8(merged.data(), w, h, w, SourceRange{254, 254}, kMaxBandedCap8, DistanceWindow{0, 0, w, h},
                     costs.data(), CostMergeRule{255, 255}, scratch);
    int rows = 0;
    cappedCostRows8(grid.data(), w, h, w, SourceRange{254, 254}, kMaxBandedCap8, DistanceWindow{0, 0, w, h},
                    costs.data(), scratch,
                    [&](int y, const uint8_t* row)
                    {
                      ++rows;
                      for (int x = 0; x < w; ++x)
                      {
                        const std::size_t i = static_cast<std::size_t>(y) * w + x;
                        ASSERT_EQ(row[x], grid[i] == 254 ? costs[0] : merged[i]) << "wide, cell " << x << "," << y;
                      }
                    });
    EXPECT_EQ(rows, h);
  }
  // The grid is only read.
  const auto cells = randomGrid(rng, 70, 30, 0.05);
  auto copy = cells;
  cappedCostRows8(copy.data(), 70, 30, 70, SourceRange{254, 255}, 6, DistanceWindow{0, 0, 70, 30},
                  randomCosts(rng, 6).data(), scratch, [](int, const uint8_t*) {});
  EXPECT_EQ(copy, cells);
  const std::vector<uint8_t> rising = {10, 20};
  EXPECT_THROW(cappedCostRows8(copy.data(), 2, 2, 2, SourceRange{}, 1, DistanceWindow{0, 0, 2, 2}, rising.data(),
                               scratch, [](int, const uint8_t*) {}),
               std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Kernels, CostMergeTest, ::testing::ValuesIn(kernelNames()),
                         [](const ::testing::TestParamInfo<std::string>& info)
                         {
                           std::string name = info.param;
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

TEST(DistanceTransform, CostMergeRejectsBadArguments)
{
  DistanceTransformScratch scratch;
  std::vector<uint8_t> g(4, 0);
  const std::vector<uint8_t> rising = {10, 20};
  EXPECT_THROW(cappedCostMerge8(g.data(), 2, 2, 2, SourceRange{}, 1, DistanceWindow{0, 0, 2, 2}, rising.data(),
                                CostMergeRule{}, scratch),
               std::invalid_argument);
  const std::vector<uint8_t> costs(200, 5);
  EXPECT_THROW(cappedCostMerge8(g.data(), 2, 2, 2, SourceRange{}, kMaxBandedCap8 + 1, DistanceWindow{0, 0, 2, 2},
                                costs.data(), CostMergeRule{}, scratch),
               std::invalid_argument);
  EXPECT_THROW(cappedCostMerge8(g.data(), 2, 2, 2, SourceRange{}, 1, DistanceWindow{0, 0, 2, 2}, costs.data(),
                                CostMergeRule{255, 0}, scratch),
               std::invalid_argument);
}
