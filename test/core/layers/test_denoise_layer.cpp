// Unit tests of DenoiseLayer (Nav2's): Nav2's denoise_layer_test and the connected-components cases of
// its image_processing_test with their inputs and expected values, exactness against a plain BFS flood
// fill on random grids, the layer in a LayeredCostmap, and refused parameters.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/grid/costmap_2d.hpp"
#include "costmap_layers/core/kernels/simd_targets.hpp"
#include "costmap_layers/core/layers/denoise_layer.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;

namespace
{
/// A grid written as rows of characters, row 0 first (Nav2's imageFromString: '.' free, 'x' 255).
struct Grid
{
  int w = 0, h = 0;
  std::vector<uint8_t> cells;
  uint8_t at(int i, int j) const { return cells[static_cast<std::size_t>(j * w + i)]; }
};

Grid gridOf(const std::vector<std::string>& rows, const std::map<char, uint8_t>& legend = {{'.', 0}, {'x', 255}})
{
  Grid g;
  g.h = static_cast<int>(rows.size());
  g.w = static_cast<int>(rows.front().size());
  for (const auto& row : rows)
    for (char c : row)
      g.cells.push_back(legend.at(c));
  return g;
}

ObstacleGroupRemover::Rule rule(int minimal, int connectivity, bool unknown_is_obstacle = true)
{
  ObstacleGroupRemover::Rule r;
  r.minimal_group_size = minimal;
  r.eight_connected = connectivity == 8;
  r.unknown_is_obstacle = unknown_is_obstacle;
  return r;
}

/// The remover over the whole grid (Nav2's tests hand the layer the whole image).
Grid denoised(Grid g, const ObstacleGroupRemover::Rule& r)
{
  ObstacleGroupRemover remover;
  remover.remove(g.cells.data(), static_cast<std::size_t>(g.w), 0, 0, g.w, g.h, r);
  return g;
}

std::string show(const Grid& g)
{
  std::string s;
  for (int j = 0; j < g.h; ++j)
  {
    for (int i = 0; i < g.w; ++i)
      s += std::to_string(g.at(i, j)) + " ";
    s += "\n";
  }
  return s;
}

#define EXPECT_GRID(actual, expected) EXPECT_EQ((actual).cells, (expected).cells) << show(actual)

// --- Nav2's denoise_layer_test, case by case (its legend: 'x' is 255 and counts as an obstacle, as
// Nav2's tester sets no_information_is_obstacle unless the case says otherwise).

TEST(DenoiseNav2, RemoveSinglePixels4way)
{
  const Grid in = gridOf({"x.x.", "x..x", ".x..", "xx.x"});
  EXPECT_GRID(denoised(in, rule(2, 4)), gridOf({"x...", "x...", ".x..", "xx.."}));
}

TEST(DenoiseNav2, RemoveSinglePixels4wayNoInformationIsEmpty)
{
  const std::map<char, uint8_t> legend = {{'.', 0}, {'n', NO_INFORMATION}, {'x', LETHAL_OBSTACLE}};
  const Grid in = gridOf({"x.x.", "xnnx", "nxnn", "xx.x"}, legend);
  EXPECT_GRID(denoised(in, rule(2, 4, false)), gridOf({"x...", "xnn.", "nxnn", "xx.."}, legend));
}

TEST(DenoiseNav2, RemoveSinglePixels8way)
{
  const Grid in = gridOf({"x.x.", "x..x", ".x..", "xx.x"});
  EXPECT_GRID(denoised(in, rule(2, 8)), gridOf({"x.x.", "x..x", ".x..", "xx.."}));
}

TEST(DenoiseNav2, RemoveSinglePixelsFromExtremelySmallImage)
{
  EXPECT_GRID(denoised(gridOf({"x"}), rule(2, 8)), gridOf({"."}));
  EXPECT_GRID(denoised(gridOf({"x.", ".x"}), rule(2, 8)), gridOf({"x.", ".x"}));
  EXPECT_GRID(denoised(gridOf({"x.", ".x"}), rule(2, 4)), gridOf({"..", ".."}));
}

TEST(DenoiseNav2, RemoveSinglePixelsFromNonBinary)
{
  // 250 lies between FREE_SPACE and INSCRIBED_INFLATED_OBSTACLE: not an obstacle, never changed.
  Grid in{3, 3, std::vector<uint8_t>(9, 250)};
  in.cells[4] = NO_INFORMATION;
  Grid expected = in;
  expected.cells[4] = FREE_SPACE;
  EXPECT_GRID(denoised(in, rule(2, 4)), expected);
}

const std::vector<std::string> kGroupsIn = {".xx..xx", "..x.x..", "x..x..x", "x......",
                                            "...x.xx", "xxx..xx", "....xx."};

TEST(DenoiseNav2, RemovePixelsGroup4way)
{
  EXPECT_GRID(denoised(gridOf(kGroupsIn), rule(3, 4)),
              gridOf({".xx....", "..x....", ".......", ".......", ".....xx", "xxx..xx", "....xx."}));
}

TEST(DenoiseNav2, RemovePixelsGroup4wayNoInformationIsEmpty)
{
  const std::map<char, uint8_t> legend = {{'.', 0}, {'n', NO_INFORMATION}, {'x', LETHAL_OBSTACLE}};
  const Grid in = gridOf({".xxnnxx", "..xnx..", "x..x..x", "x......", "nnnxnxx", "xxx..xx", "....xx."}, legend);
  EXPECT_GRID(denoised(in, rule(3, 4, false)),
              gridOf({".xxnn..", "..xn...", ".......", ".......", "nnn.nxx", "xxx..xx", "....xx."}, legend));
}

TEST(DenoiseNav2, RemovePixelsGroup8way)
{
  EXPECT_GRID(denoised(gridOf(kGroupsIn), rule(3, 8)),
              gridOf({".xx..xx", "..x.x..", "...x...", ".......", "...x.xx", "xxx..xx", "....xx."}));
}

TEST(DenoiseNav2, RemovePixelsGroupFromExtremelySmallImage)
{
  EXPECT_GRID(denoised(gridOf({"x"}), rule(3, 8)), gridOf({"."}));
  EXPECT_GRID(denoised(gridOf({"x.", ".x"}), rule(3, 8)), gridOf({"..", ".."}));
}

TEST(DenoiseNav2, RemovePixelsGroupFromNonBinary)
{
  Grid in{3, 3, std::vector<uint8_t>(9, 250)};
  in.cells[4] = 255;
  Grid expected = in;
  expected.cells[4] = 0;
  EXPECT_GRID(denoised(in, rule(2, 4)), expected);
}

TEST(DenoiseNav2, DenoiseSinglesAndGroups)
{
  EXPECT_GRID(denoised(gridOf({"xx.", "...", "..x"}), rule(2, 4)), gridOf({"xx.", "...", "..."}));
  EXPECT_GRID(denoised(gridOf({"xx.", "x.x", "..x"}), rule(3, 4)), gridOf({"xx.", "x..", "..."}));
}

TEST(DenoiseNav2, DenoiseEmptyAndNothing)
{
  ObstacleGroupRemover remover;
  uint8_t cell = 255;
  EXPECT_EQ(remover.remove(&cell, 1, 0, 0, 0, 0, rule(2, 4)), 0u);  // an empty window
  EXPECT_EQ(cell, 255);
  EXPECT_EQ(remover.remove(&cell, 1, 0, 0, 1, 1, rule(1, 4)), 0u);  // size 1: no group is smaller
  EXPECT_EQ(cell, 255);
  EXPECT_EQ(remover.remove(&cell, 1, 0, 0, 1, 1, rule(0, 4)), 0u);
  EXPECT_EQ(cell, 255);
}

// --- The connected-components cases of Nav2's image_processing_test: its images, with the groups it
// expects (sizes counted by hand) turned into which groups a minimal size keeps.

TEST(DenoiseNav2Components, Way4Steps)
{
  const Grid in = gridOf({"..xx", ".xx.", "xx..", "...."});  // one group of 6 cells
  EXPECT_GRID(denoised(in, rule(6, 4)), in);
  EXPECT_GRID(denoised(in, rule(7, 4)), gridOf({"....", "....", "....", "...."}));
}

TEST(DenoiseNav2Components, Way8Steps)
{
  // a: 6 cells, b: 4 cells (8-connected, not 4-connected).
  const Grid in = gridOf({"....xx", "..xx..", "xx....", "...xx.", ".....x", "....x."});
  EXPECT_GRID(denoised(in, rule(4, 8)), in);
  EXPECT_GRID(denoised(in, rule(5, 8)), gridOf({"....xx", "..xx..", "xx....", "......", "......", "......"}));
  EXPECT_GRID(denoised(in, rule(7, 8)), gridOf({"......", "......", "......", "......", "......", "......"}));
  // 4-connected the same image is seven groups: a pair in each row, three single cells.
  EXPECT_GRID(denoised(in, rule(2, 4)), gridOf({"....xx", "..xx..", "xx....", "...xx.", "......", "......"}));
}

TEST(DenoiseNav2Components, Way4Sieve)
{
  const Grid in = gridOf({"x.x.x", ".x.x.", "x.x.x", ".x.x.", "x.x.x"});  // 13 single cells
  EXPECT_GRID(denoised(in, rule(2, 4)), gridOf({".....", ".....", ".....", ".....", "....."}));
  EXPECT_GRID(denoised(in, rule(13, 8)), in);  // 8-connected: one group of 13
  EXPECT_GRID(denoised(in, rule(14, 8)), gridOf({".....", ".....", ".....", ".....", "....."}));
}

TEST(DenoiseNav2Components, FingerBothConnectivities)
{
  // a: 2 cells, b: 3, c: 4, a free column between each.
  const Grid in = gridOf({".....", "....x", "..x.x", "x.x.x", "x.x.x"});
  for (int connectivity : {4, 8})
  {
    EXPECT_GRID(denoised(in, rule(2, connectivity)), in);
    EXPECT_GRID(denoised(in, rule(3, connectivity)), gridOf({".....", "....x", "..x.x", "..x.x", "..x.x"}));
    EXPECT_GRID(denoised(in, rule(4, connectivity)), gridOf({".....", "....x", "....x", "....x", "....x"}));
    EXPECT_GRID(denoised(in, rule(5, connectivity)), gridOf({".....", ".....", ".....", ".....", "....."}));
  }
}

TEST(DenoiseNav2Components, SpiralBothConnectivities)
{
  // One group of 27 cells winding inwards: runs of a row join only through rows far below.
  const Grid in = gridOf({".xxxxxx", "......x", ".xxxx.x", ".x..x.x", ".x.xx.x", ".x....x", ".xxxxxx"});
  for (int connectivity : {4, 8})
  {
    EXPECT_GRID(denoised(in, rule(27, connectivity)), in);
    Grid empty = in;
    std::fill(empty.cells.begin(), empty.cells.end(), 0);
    EXPECT_GRID(denoised(in, rule(28, connectivity)), empty);
  }
}

TEST(DenoiseNav2Components, LargeChessboard)
{
  // Nav2's label-overflow case: 512 x 512 single cells 4-connected, one group 8-connected.
  Grid in{512, 512, std::vector<uint8_t>(512 * 512, 0)};
  for (int j = 0; j < 512; ++j)
    for (int i = (j % 2); i < 512; i += 2)
      in.cells[static_cast<std::size_t>(j * 512 + i)] = 255;
  EXPECT_EQ(denoised(in, rule(2, 4)).cells, std::vector<uint8_t>(512 * 512, 0));
  EXPECT_GRID(denoised(in, rule(512 * 256, 8)), in);
}

// --- Exactness against a plain flood fill.

bool referenceObstacle(uint8_t v, bool unknown_is_obstacle)
{
  return v == LETHAL_OBSTACLE || v == INSCRIBED_INFLATED_OBSTACLE || (unknown_is_obstacle && v == NO_INFORMATION);
}

/// Breadth-first flood fill of each group inside the window, then every group under the size cleared.
void referenceDenoise(Grid& g, int x0, int y0, int xn, int yn, int minimal, bool eight, bool unknown_is_obstacle)
{
  if (minimal <= 1) return;
  std::vector<int> group(g.cells.size(), -1);
  std::vector<std::vector<int>> members;
  for (int y = y0; y < yn; ++y)
    for (int x = x0; x < xn; ++x)
    {
      const int start = y * g.w + x;
      if (group[start] >= 0 || !referenceObstacle(g.cells[start], unknown_is_obstacle)) continue;
      const int id = static_cast<int>(members.size());
      members.emplace_back();
      std::deque<int> queue{start};
      group[start] = id;
      while (!queue.empty())
      {
        const int c = queue.front();
        queue.pop_front();
        members[id].push_back(c);
        const int cx = c % g.w, cy = c / g.w;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
          {
            if (dx == 0 && dy == 0) continue;
            if (!eight && dx != 0 && dy != 0) continue;
            const int nx = cx + dx, ny = cy + dy;
            if (nx < x0 || nx >= xn || ny < y0 || ny >= yn) continue;
            const int n = ny * g.w + nx;
            if (group[n] >= 0 || !referenceObstacle(g.cells[n], unknown_is_obstacle)) continue;
            group[n] = id;
            queue.push_back(n);
          }
      }
    }
  for (const auto& m : members)
    if (static_cast<int>(m.size()) < minimal)
      for (int c : m)
        g.cells[c] = FREE_SPACE;
}

/// Random costs: obstacles (lethal, inscribed, unknown) with the given density, the rest free or in between.
Grid randomGrid(std::mt19937& rng, int w, int h, double density)
{
  std::bernoulli_distribution obstacle(density);
  std::uniform_int_distribution<int> which(0, 5);
  const uint8_t obstacles[] = {LETHAL_OBSTACLE, LETHAL_OBSTACLE, LETHAL_OBSTACLE, INSCRIBED_INFLATED_OBSTACLE,
                               NO_INFORMATION,  NO_INFORMATION};
  const uint8_t others[] = {FREE_SPACE, FREE_SPACE, FREE_SPACE, 1, 128, MAX_NON_OBSTACLE};
  Grid g{w, h, std::vector<uint8_t>(static_cast<std::size_t>(w * h))};
  for (auto& c : g.cells)
    c = obstacle(rng) ? obstacles[which(rng)] : others[which(rng)];
  return g;
}

TEST(DenoiseExact, RandomGridsMatchFloodFill)
{
  std::mt19937 rng(20261205);
  ObstacleGroupRemover remover;  // one remover throughout: its buffers are reused between calls
  int cases = 0;
  for (double density : {0.05, 0.3, 0.5, 0.8})
    for (int round = 0; round < 40; ++round)
    {
      std::uniform_int_distribution<int> size(1, round % 4 == 0 ? 130 : 40);
      const int w = size(rng), h = size(rng);
      const Grid g = randomGrid(rng, w, h, density);
      // Windows: the whole grid, windows touching each edge, and one strictly inside.
      std::uniform_int_distribution<int> xs(0, w), ys(0, h);
      std::vector<std::array<int, 4>> windows = {{0, 0, w, h}, {0, 0, xs(rng), ys(rng)}, {xs(rng), ys(rng), w, h}};
      int a = xs(rng), b = xs(rng), c = ys(rng), d = ys(rng);
      windows.push_back({std::min(a, b), std::min(c, d), std::max(a, b), std::max(c, d)});
      for (const auto& win : windows)
        for (int connectivity : {4, 8})
          for (int minimal = 0; minimal <= 5; ++minimal)
            for (bool unknown : {false, true})
            {
              Grid expected = g;
              referenceDenoise(expected, win[0], win[1], win[2], win[3], minimal, connectivity == 8, unknown);
              Grid actual = g;
              const std::size_t cleared = remover.remove(actual.cells.data(), static_cast<std::size_t>(w), win[0],
                                                         win[1], win[2], win[3], rule(minimal, connectivity, unknown));
              std::size_t changed = 0;
              for (std::size_t k = 0; k < g.cells.size(); ++k)
                changed += expected.cells[k] != g.cells[k];
              ASSERT_EQ(actual.cells, expected.cells)
                  << w << "x" << h << " window " << win[0] << "," << win[1] << " - " << win[2] << "," << win[3]
                  << " density " << density << " connectivity " << connectivity << " size " << minimal
                  << " unknown obstacle " << unknown;
              ASSERT_EQ(cleared, changed);
              ++cases;
            }
    }
  EXPECT_EQ(cases, 4 * 40 * 4 * 2 * 6 * 2);
}

// The row scan's obstacle bits come from one Highway kernel compiled per target: each target this CPU
// runs (down to the scalar one, whose vectors are one lane) against the flood fill, on rows longer
// than several vectors of the widest and of lengths that are no multiple of any.
TEST(DenoiseExact, EveryKernelTargetMatchesFloodFill)
{
  const std::vector<std::string> targets = simdTargets();
  ASSERT_FALSE(targets.empty());
  int cases = 0;
  for (const std::string& target : targets)
  {
    ASSERT_TRUE(setSimdTarget(target)) << target;
    std::mt19937 rng(4242);
    ObstacleGroupRemover remover;
    for (double density : {0.1, 0.5, 0.9})
      for (int round = 0; round < 6; ++round)
      {
        std::uniform_int_distribution<int> width(1, 300), height(1, 12);
        const int w = width(rng), h = height(rng);
        const Grid g = randomGrid(rng, w, h, density);
        std::uniform_int_distribution<int> xs(0, w);
        int a = xs(rng), b = xs(rng);
        for (const std::array<int, 4>& win : {std::array<int, 4>{0, 0, w, h}, {std::min(a, b), 0, std::max(a, b), h}})
          for (int minimal : {2, 3})
            for (bool unknown : {false, true})
            {
              Grid expected = g;
              referenceDenoise(expected, win[0], win[1], win[2], win[3], minimal, true, unknown);
              Grid actual = g;
              remover.remove(actual.cells.data(), static_cast<std::size_t>(w), win[0], win[1], win[2], win[3],
                             rule(minimal, 8, unknown));
              ASSERT_EQ(actual.cells, expected.cells) << target << " " << w << "x" << h << " window " << win[0]
                                                      << " - " << win[2] << " size " << minimal;
              ++cases;
            }
      }
  }
  setSimdTarget("");
  EXPECT_EQ(cases, static_cast<int>(targets.size()) * 3 * 6 * 2 * 2 * 2);
}

TEST(DenoiseExact, LongRunsAcrossTheWordBoundaries)
{
  // Rows longer than the 64 cells read at once, with single cells just before, at and after each word
  // boundary of the window and a run across one.
  ObstacleGroupRemover remover;
  for (int offset = 0; offset < 40; ++offset)
  {
    Grid g{200, 3, std::vector<uint8_t>(600, FREE_SPACE)};
    for (int i :
         {offset, offset + 31, offset + 33, offset + 62, offset + 64, offset + 66, offset + 127, offset + 129, 199})
      g.cells[static_cast<std::size_t>(200 + i)] = LETHAL_OBSTACLE;
    for (int i = offset + 120; i < std::min(200, offset + 136); ++i)
      g.cells[static_cast<std::size_t>(400 + i)] = INSCRIBED_INFLATED_OBSTACLE;
    g.cells[static_cast<std::size_t>(offset + 1)] = LETHAL_OBSTACLE;  // a corner neighbour above
    for (int connectivity : {4, 8})
    {
      Grid expected = g;
      referenceDenoise(expected, offset, 0, 200, 3, 2, connectivity == 8, false);
      Grid actual = g;
      remover.remove(actual.cells.data(), 200, offset, 0, 200, 3, rule(2, connectivity, false));
      ASSERT_EQ(actual.cells, expected.cells) << "offset " << offset << " connectivity " << connectivity;
    }
  }
}

// --- The layer.

ParamValue params(std::initializer_list<std::pair<const char*, ParamValue>> kv)
{
  ParamValue p = ParamValue::makeMap();
  for (const auto& [k, v] : kv)
    p.set(k, v);
  return p;
}

std::shared_ptr<DenoiseLayer> makeDenoise(LayeredCostmap& lc, ParamValue p = ParamValue::makeMap())
{
  auto layer = std::make_shared<DenoiseLayer>();
  layer->initialize(&lc, "denoise", std::make_shared<FakeContext>(std::move(p)));
  return layer;
}

/// Writes a fixed pattern over the whole map, as the layers below a denoise layer would.
class PatternLayer : public Layer
{
public:
  explicit PatternLayer(Grid g) : g_(std::move(g)) {}
  void updateBounds(double, double, double, double* min_x, double* min_y, double* max_x, double* max_y) override
  {
    *min_x = std::min(*min_x, -1e6);
    *min_y = std::min(*min_y, -1e6);
    *max_x = std::max(*max_x, 1e6);
    *max_y = std::max(*max_y, 1e6);
  }
  void updateCosts(Costmap2D& master, int min_i, int min_j, int max_i, int max_j) override
  {
    for (int j = min_j; j < max_j; ++j)
      for (int i = min_i; i < max_i; ++i)
        master.setCost(static_cast<unsigned>(i), static_cast<unsigned>(j), g_.at(i, j));
  }

private:
  Grid g_;
};

TEST(DenoiseLayer, Nav2DefaultsAndCustomParameters)
{
  LayeredCostmap lc("map", false, false);
  const auto d = makeDenoise(lc);
  EXPECT_TRUE(d->enabled());
  EXPECT_EQ(d->config().group_connectivity_type, 8);
  EXPECT_EQ(d->config().minimal_group_size, 2);
  const auto c = makeDenoise(lc, params({{"minimal_group_size", ParamValue::makeInt(5)},
                                         {"group_connectivity_type", ParamValue::makeInt(4)}}));
  EXPECT_EQ(c->config().group_connectivity_type, 4);
  EXPECT_EQ(c->config().minimal_group_size, 5);
  const auto off = makeDenoise(lc, params({{"enabled", ParamValue::makeBool(false)}}));
  EXPECT_FALSE(off->enabled());
}

TEST(DenoiseLayer, BadParametersAreRefusedNamingFieldAndValue)
{
  // Nav2 turns minimal_group_size -1 into 1 and group_connectivity_type 3 into 8 with a warning; here
  // both are errors, as every out-of-range parameter of this package is.
  const std::vector<std::pair<const char*, ParamValue>> bad = {
      {"group_connectivity_type", ParamValue::makeInt(3)},
      {"group_connectivity_type", ParamValue::makeInt(5)},
      {"group_connectivity_type", ParamValue::makeInt(0)},
      {"group_connectivity_type", ParamValue::makeInt(-8)},
      {"group_connectivity_type", ParamValue::makeInt(16)},
      {"group_connectivity_type", ParamValue::makeDouble(4.5)},
      {"group_connectivity_type", ParamValue::makeString("8")},
      {"minimal_group_size", ParamValue::makeInt(-1)},
      {"minimal_group_size", ParamValue::makeInt(std::numeric_limits<int>::min())},
      {"minimal_group_size", ParamValue::makeDouble(2.5)},
      {"minimal_group_size", ParamValue::makeBool(true)},
  };
  LayeredCostmap lc("map", false, false);
  for (const auto& [name, value] : bad)
  {
    const std::string shown = value.toString();
    try
    {
      makeDenoise(lc, params({{name, value}}));
      ADD_FAILURE() << name << " " << shown << " accepted";
    }
    catch (const std::invalid_argument& e)
    {
      const std::string what = e.what();
      EXPECT_NE(what.find(name), std::string::npos) << what;
      EXPECT_NE(what.find(shown), std::string::npos) << what;
      EXPECT_NE(what.find("denoise"), std::string::npos) << what;
    }
    // At run time the same value is refused and the configuration in force stays.
    const auto layer = makeDenoise(lc, params({{"minimal_group_size", ParamValue::makeInt(4)}}));
    EXPECT_THROW(layer->reconfigure(params({{"minimal_group_size", ParamValue::makeInt(3)}, {name, value}})),
                 std::invalid_argument);
    EXPECT_EQ(layer->config().minimal_group_size, 4);
    EXPECT_EQ(layer->config().group_connectivity_type, 8);
  }
  // The edges of the accepted ranges.
  for (int v : {0, 1, std::numeric_limits<int>::max()})
    EXPECT_EQ(makeDenoise(lc, params({{"minimal_group_size", ParamValue::makeInt(v)}}))->config().minimal_group_size,
              v);
}

TEST(DenoiseLayer, ReconfigureAppliesAndIsTunable)
{
  LayeredCostmap lc("map", false, false);
  const auto layer = makeDenoise(lc);
  layer->reconfigure(
      params({{"minimal_group_size", ParamValue::makeInt(7)}, {"group_connectivity_type", ParamValue::makeInt(4)}}));
  EXPECT_EQ(layer->config().minimal_group_size, 7);
  EXPECT_EQ(layer->config().group_connectivity_type, 4);
  std::vector<std::string> names;
  for (const auto& s : layer->tunableParameters(ParamValue::makeMap()))
    names.push_back(s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"enabled", "minimal_group_size", "group_connectivity_type"}));
}

TEST(DenoiseLayer, Nav2ResetClearableAndBounds)
{
  LayeredCostmap lc("map", false, false);
  const auto layer = makeDenoise(lc);
  layer->reset();
  EXPECT_FALSE(layer->isCurrent());  // Nav2's reset test
  EXPECT_FALSE(layer->isClearable());
  double b[4] = {1., 2., 3., 4.};
  layer->updateBounds(0., 0., 0., &b[0], &b[1], &b[2], &b[3]);
  EXPECT_EQ(b[0], 1.);
  EXPECT_EQ(b[1], 2.);
  EXPECT_EQ(b[2], 3.);
  EXPECT_EQ(b[3], 4.);
  Costmap2D grid(1, 1, 1.0, 0.0, 0.0, FREE_SPACE);
  layer->updateCosts(grid, 0, 0, 1, 1);
  EXPECT_TRUE(layer->isCurrent());
}

TEST(DenoiseLayer, Nav2UpdateCosts)
{
  // Nav2's updateCosts: a 1x1 map whose default is free, its one cell unknown: an obstacle, alone, cleared.
  LayeredCostmap lc("map", false, false);
  const auto layer = makeDenoise(lc, params({{"minimal_group_size", ParamValue::makeInt(2)},
                                             {"group_connectivity_type", ParamValue::makeInt(4)}}));
  Costmap2D grid(1, 1, 1.0, 0.0, 0.0, FREE_SPACE);
  grid.setCost(0, 0, NO_INFORMATION);
  layer->updateCosts(grid, 0, 0, 1, 1);
  EXPECT_EQ(grid.getCost(0, 0), FREE_SPACE);
  // With unknown as the default (track_unknown_space), an unknown cell is not an obstacle: it stays.
  Costmap2D unknown(1, 1, 1.0, 0.0, 0.0, NO_INFORMATION);
  layer->updateCosts(unknown, 0, 0, 1, 1);
  EXPECT_EQ(unknown.getCost(0, 0), NO_INFORMATION);
  // Windows reaching beyond the grid are clipped to it.
  Costmap2D lethal(2, 1, 1.0, 0.0, 0.0, FREE_SPACE);
  lethal.setCost(1, 0, LETHAL_OBSTACLE);
  layer->updateCosts(lethal, -5, -5, 50, 50);
  EXPECT_EQ(lethal.getCost(1, 0), FREE_SPACE);
}

TEST(DenoiseLayer, InALayeredCostmapMatchesFloodFill)
{
  std::mt19937 rng(77);
  for (bool track_unknown : {false, true})
    for (int connectivity : {4, 8})
      for (int minimal : {1, 2, 3, 5})
      {
        const Grid g = randomGrid(rng, 37, 23, 0.3);
        LayeredCostmap lc("map", false, track_unknown);
        lc.resizeMap(37, 23, 0.1, 0.0, 0.0);
        lc.addPlugin(std::make_shared<PatternLayer>(g));
        auto layer = makeDenoise(lc, params({{"minimal_group_size", ParamValue::makeInt(minimal)},
                                             {"group_connectivity_type", ParamValue::makeInt(connectivity)}}));
        lc.addPlugin(layer);
        lc.updateMap(1.0, 1.0, 0.0);
        Grid expected = g;
        referenceDenoise(expected, 0, 0, 37, 23, minimal, connectivity == 8, !track_unknown);
        const Costmap2D& out = lc.getCostmap();
        const std::vector<uint8_t> actual(out.data(), out.data() + out.cellCount());
        EXPECT_EQ(actual, expected.cells)
            << "track_unknown " << track_unknown << " connectivity " << connectivity << " size " << minimal;
        // Nav2's updateCostsIfDisabled: switched off, the layers below come through unchanged.
        layer->setEnabled(false);
        lc.updateMap(1.0, 1.0, 0.0);
        EXPECT_EQ(std::vector<uint8_t>(out.data(), out.data() + out.cellCount()), g.cells);
      }
}
}  // namespace
