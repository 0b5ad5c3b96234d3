// The obstacle layer's clearing, cell for cell, against a brute-force reference written here from
// costmap_2d's rule (issue 38 made the walk cheap: the first and last cleared step found once per ray,
// the beam directions cached, the points projected in one pass): every cell of costmap_2d's Bresenham
// walk from the origin's cell to the reading's cell, step k lying k * hypot(dx, dy) / max(|dx|, |dy|) cells
// along the line, is cleared when raytrace_min_range <= that <= raytrace_max_range (both in whole
// cells, rounded up), the walk cut at the range plus two cells.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/layers/obstacle_layer.hpp"
#include "fake_context.hpp"
#include "sensor_test_helpers.hpp"

namespace costmap_layers_test
{
namespace
{
constexpr double kRes = 0.05, kOriginX = -3.0, kOriginY = -2.5;
constexpr unsigned kSizeX = 120, kSizeY = 100;

/// The reference: clears along one ray on a copy of the grid (the ray's end inside the grid).
void referenceRay(std::vector<uint8_t>& grid, double ox, double oy, double px, double py, double min_range,
                  double max_range)
{
  const int x0 = static_cast<int>(std::floor((ox - kOriginX) / kRes)),
            y0 = static_cast<int>(std::floor((oy - kOriginY) / kRes));
  const int x1 = static_cast<int>(std::floor((px - kOriginX) / kRes)),
            y1 = static_cast<int>(std::floor((py - kOriginY) / kRes));
  ASSERT_TRUE(x1 >= 0 && y1 >= 0 && x1 < static_cast<int>(kSizeX) && y1 < static_cast<int>(kSizeY));
  const double min_cells = std::ceil(min_range / kRes), max_cells = std::ceil(max_range / kRes);
  const int dx = x1 - x0, dy = y1 - y0, adx = std::abs(dx), ady = std::abs(dy);
  const int major = std::max(adx, ady), minor = std::min(adx, ady);
  const double dist = std::hypot(static_cast<double>(dx), static_cast<double>(dy));
  const double step = major == 0 ? 0.0 : dist / major;
  const double scale = dist == 0.0 ? 1.0 : std::min(1.0, (max_cells + 2) / dist);
  const int steps = static_cast<int>(scale * major);
  int x = x0, y = y0, error = major / 2;
  for (int k = 0; k <= steps; ++k)
  {
    const double along = k * step;
    if (along >= min_cells && along <= max_cells) grid[static_cast<std::size_t>(y) * kSizeX + x] = FREE_SPACE;
    // costmap_2d's bresenham2D: one step along the major axis, a minor step when the error overflows.
    if (adx >= ady)
      x += dx > 0 ? 1 : -1;
    else
      y += dy > 0 ? 1 : -1;
    error += minor;
    if (error >= major)
    {
      if (adx >= ady)
        y += dy > 0 ? 1 : -1;
      else
        x += dx > 0 ? 1 : -1;
      error -= major;
    }
  }
}

TEST(ObstacleRaytraceReference, ClearsTheCellsOfCostmap2dsRuleOnEveryCell)
{
  std::mt19937 rng(38);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::size_t cleared_total = 0;
  for (int round = 0; round < 12; ++round)
  {
    const double min_range = round % 3 == 0 ? 0.0 : 0.07 * round, max_range = 0.9 + 0.13 * round;
    LayeredCostmap lc("map", false, false);
    lc.resizeMap(kSizeX, kSizeY, kRes, kOriginX, kOriginY);
    ParamValue p = paramMap({{"observation_sources", S("scan")}, {"footprint_clearing_enabled", B(false)}});
    p.set("scan", paramMap({{"data_type", S("LaserScan")},
                            {"clearing", B(true)},
                            {"marking", B(false)},
                            {"inf_is_valid", B(true)},
                            {"raytrace_min_range", D(min_range)},
                            {"raytrace_max_range", D(max_range)}}));
    auto ctx = std::make_shared<FakeContext>(p);
    auto layer = std::make_shared<ObstacleLayer>();
    layer->initialize(&lc, "obstacles", ctx);
    ctx->bind(*layer);
    lc.addPlugin(layer);
    Costmap2D& grid = layer->costmap();
    std::memset(grid.data(), LETHAL_OBSTACLE, grid.cellCount());
    std::vector<uint8_t> expected(grid.data(), grid.data() + grid.cellCount());

    // A scan whose every reading lies inside the grid (ranges up to 2.4 m from an origin at least 2.45 m
    // from every border), with no-return beams (clear up to range_max) and dropped ones (NaN, too short).
    LaserScanData s;
    s.frame_id = "laser";
    const int n = 90 + 61 * round;
    s.angle_min = static_cast<float>(-3.1 + 0.2 * U(rng));
    s.angle_increment = static_cast<float>((round % 2 ? 6.2 : -4.0) / n);
    s.angle_max = s.angle_min + s.angle_increment * static_cast<float>(n - 1);
    s.range_min = 0.05f;
    s.range_max = 2.4f;
    for (int k = 0; k < n; ++k)
    {
      const double u = U(rng);
      s.ranges.push_back(u < 0.05   ? NAN
                         : u < 0.1  ? INFINITY
                         : u < 0.12 ? 0.01f
                                    : static_cast<float>(0.06 + 2.3 * U(rng)));
    }
    const double ox = -0.5 + 0.1 * U(rng), oy = 0.1 * U(rng) - 0.05, yaw = 6.28 * U(rng);
    const SensorPose pose = poseAt(ox, oy, 0.3, yaw);
    ASSERT_EQ(ctx->publishScan("scan", s, pose), 1);
    double a0 = 1e30, b0 = 1e30, a1 = -1e30, b1 = -1e30;
    layer->updateBounds(ox, oy, yaw, &a0, &b0, &a1, &b1);

    for (int k = 0; k < n; ++k)
    {
      float r = s.ranges[k];
      if (std::isnan(r) || r < s.range_min) continue;
      if (std::isinf(r)) r = s.range_max;
      // The beam's point in the laser's frame (float, as a LaserScan projects), then in the map.
      const double a = static_cast<double>(s.angle_min) + k * static_cast<double>(s.angle_increment);
      const float lx = static_cast<float>(r * std::cos(a)), ly = static_cast<float>(r * std::sin(a));
      double gx, gy, gz;
      pose.to_global.apply(lx, ly, 0.0f, gx, gy, gz);
      referenceRay(expected, ox, oy, static_cast<float>(gx), static_cast<float>(gy), min_range, max_range);
    }
    std::size_t mismatches = 0, cleared = 0;
    for (std::size_t i = 0; i < expected.size(); ++i)
    {
      mismatches += expected[i] != grid.data()[i];
      cleared += expected[i] == FREE_SPACE;
    }
    EXPECT_EQ(mismatches, 0u) << "round " << round;
    cleared_total += cleared;
  }
  // The rounds cleared something worth comparing.
  EXPECT_GT(cleared_total, 5000u);
}
}  // namespace
}  // namespace costmap_layers_test
