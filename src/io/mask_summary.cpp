#include "costmap_layers/io/mask_summary.hpp"

#include <sstream>
#include <vector>

namespace costmap_layers
{
namespace io
{
namespace
{
uint64_t at(const std::array<uint64_t, 256>& counts, int value)
{
  return counts[static_cast<std::size_t>(value + 128)];
}
}  // namespace

std::array<uint64_t, 256> countValues(const OccupancyGridData& grid)
{
  std::array<uint64_t, 256> counts{};
  for (const int8_t v : grid.data)
    ++counts[static_cast<std::size_t>(static_cast<int>(v) + 128)];
  return counts;
}

std::string describeValues(const std::array<uint64_t, 256>& counts, std::size_t max_listed)
{
  std::size_t distinct = 0;
  for (const uint64_t c : counts)
    distinct += c != 0;
  std::ostringstream out;
  if (distinct == 0) return "no cells";
  if (distinct <= max_listed)
  {
    bool first = true;
    for (int v = -128; v <= 127; ++v)
    {
      if (at(counts, v) == 0) continue;
      out << (first ? "" : ", ") << v << " x " << at(counts, v);
      first = false;
    }
    return out.str();
  }
  // Bins: -1, 0, 1-10, ..., 81-90, 91-99, 100, other.
  struct Bin
  {
    std::string name;
    uint64_t cells = 0;
    int values = 0;
  };
  std::vector<Bin> bins;
  bins.push_back({"-1"});
  bins.push_back({"0"});
  for (int lo = 1; lo <= 91; lo += 10)
    bins.push_back({std::to_string(lo) + "-" + std::to_string(lo == 91 ? 99 : lo + 9)});
  bins.push_back({"100"});
  bins.push_back({"other (outside -1..100)"});
  for (int v = -128; v <= 127; ++v)
  {
    const uint64_t c = at(counts, v);
    if (c == 0) continue;
    std::size_t b;
    if (v == -1)
      b = 0;
    else if (v == 0)
      b = 1;
    else if (v >= 1 && v <= 99)
      b = 2 + static_cast<std::size_t>((v - 1) / 10);
    else if (v == 100)
      b = 12;
    else
      b = 13;
    bins[b].cells += c;
    ++bins[b].values;
  }
  out << distinct << " distinct values, histogram: ";
  bool first = true;
  for (const Bin& b : bins)
  {
    if (b.cells == 0) continue;
    out << (first ? "" : ", ") << b.name << " x " << b.cells;
    if (b.values > 1) out << " (" << b.values << " values)";
    first = false;
  }
  return out.str();
}

std::string pixelRuleDescription(MapMode mode)
{
  switch (mode)
  {
    case MapMode::Scale:
      return "ros1 (map_server scale: 1 + 98 * ratio truncated, strict thresholds)";
    case MapMode::Nav2Scale:
      return "nav2 (map_io scale: round(100 * ratio), inclusive thresholds)";
    case MapMode::Trinary:
      return "ros1 trinary (0 / 100 / -1, strict thresholds)";
    case MapMode::Raw:
      return "ros1 raw (the grey value itself)";
  }
  return "unknown";
}

std::string pixelRuleWarning(const std::array<uint64_t, 256>& counts, MapMode mode)
{
  if (mode != MapMode::Scale) return {};
  const uint64_t ones = at(counts, 1), ninety_nines = at(counts, 99);
  if (at(counts, 0) != 0 || at(counts, 100) != 0 || (ones == 0 && ninety_nines == 0)) return {};
  std::ostringstream out;
  out << "the values look like a mask drawn for Nav2's pixel rule: read with ROS 1 map_server's scale rule it has "
      << ones << " cells of 1 and " << ninety_nines
      << " of 99 but none of 0 or 100, which is what white and black give under that rule when the YAML's "
         "thresholds are 1.0 / 0.0 (Nav2 reads them as 0 and 100). If 0 and 100 were meant, read it with Nav2's rule "
         "(mask_server ~pixel_rule: nav2)";
  return out.str();
}
}  // namespace io
}  // namespace costmap_layers
