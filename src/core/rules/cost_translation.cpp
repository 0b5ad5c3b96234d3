#include "costmap_layers/core/rules/cost_translation.hpp"

namespace costmap_layers
{
const std::array<int8_t, 256>& costTranslationTable()
{
  static const std::array<int8_t, 256> table = []
  {
    std::array<int8_t, 256> t{};
    t[0] = 0;
    for (int c = 1; c < 253; ++c)
      t[static_cast<std::size_t>(c)] = static_cast<int8_t>(1 + (97 * (c - 1)) / 251);
    t[253] = 99;
    t[254] = 100;
    t[255] = -1;
    return t;
  }();
  return table;
}
}  // namespace costmap_layers
