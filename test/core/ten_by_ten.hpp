// costmap_2d's test map test/TenByTen.pgm (navigation noetic, costmap_2d/test, BSD) as map_server reads
// it: 10 x 10 cells of 1 m, 20 occupied, for the tests that rebuild costmap_2d's own scenarios.
#pragma once

#include <cstddef>

#include "costmap_layers/core/data/grid_data.hpp"

namespace costmap_layers_test
{
inline costmap_layers::OccupancyGridData tenByTen()
{
  costmap_layers::OccupancyGridData m;
  m.frame_id = "map";
  m.width = 10;
  m.height = 10;
  m.resolution = 1.0;
  m.data.assign(100, 0);
  // (x, y) with y the row, read from the PGM (its first row is the top, y = 9).
  const int cells[][2] = {{7, 0}, {8, 0}, {9, 0}, {7, 1}, {8, 1}, {9, 1}, {3, 2}, {4, 2}, {5, 2}, {4, 5},
                          {7, 5}, {8, 5}, {9, 5}, {4, 6}, {7, 6}, {8, 6}, {9, 6}, {7, 7}, {8, 7}, {9, 7}};
  for (const auto& c : cells)
    m.data[static_cast<std::size_t>(c[1] * 10 + c[0])] = 100;
  return m;
}
}  // namespace costmap_layers_test
