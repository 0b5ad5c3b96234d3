#include "costmap_layers/core/filters/keepout_filter.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/grid/polygon.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/config/param_reader.hpp"

namespace costmap_layers
{
KeepoutFilterConfig parseKeepoutFilterConfig(const ParamReader& params)
{
  KeepoutFilterConfig c;
  c.override_lethal_cost = params.getBool("override_lethal_cost", c.override_lethal_cost);
  c.lethal_override_cost = params.getInt("lethal_override_cost", c.lethal_override_cost, 1, MAX_NON_OBSTACLE);
  return c;
}

double escapeClearance(double inscribed_radius, double costmap_resolution)
{
  return inscribed_radius + std::sqrt(2.0) * costmap_resolution;
}

namespace
{
bool lethalKeepout(int8_t v)
{
  return maskValueCost(v) >= INSCRIBED_INFLATED_OBSTACLE;
}
}  // namespace

bool robotInLethalKeepout(const OccupancyGridData& mask, const Transform2D& to_mask, double x, double y, double yaw,
                          const Footprint& footprint, double clearance)
{
  // Everything in mask-grid coordinates [cells]: cell (i, j) spans [i, i + 1) x [j, j + 1).
  const GridPlacement grid = GridPlacement::of(mask);
  auto toGrid = [&](double wx, double wy)
  {
    Eigen::Vector2d g;
    toGridCells(grid, to_mask, wx, wy, g.x(), g.y());
    return g;
  };
  const Eigen::Vector2d c = toGrid(x, y);
  if (!std::isfinite(c.x()) || !std::isfinite(c.y())) return false;
  std::vector<Eigen::Vector2d> polygon;
  polygon.reserve(footprint.size());
  for (const Eigen::Vector2d& p : transformFootprint(x, y, yaw, footprint))
    polygon.push_back(toGrid(p.x(), p.y()));
  const double rc = std::max(0.0, clearance) / mask.resolution;
  double u0 = c.x() - rc, u1 = c.x() + rc, v0 = c.y() - rc, v1 = c.y() + rc;
  for (const Eigen::Vector2d& p : polygon)
  {
    u0 = std::min(u0, p.x());
    u1 = std::max(u1, p.x());
    v0 = std::min(v0, p.y());
    v1 = std::max(v1, p.y());
  }
  const double w = mask.width, h = mask.height;
  const double fi0 = std::max(0.0, std::floor(u0)), fi1 = std::min(w - 1.0, std::floor(u1));
  const double fj0 = std::max(0.0, std::floor(v0)), fj1 = std::min(h - 1.0, std::floor(v1));
  if (!(fi0 <= fi1) || !(fj0 <= fj1)) return false;  // off the mask (or not finite)
  const auto i0 = static_cast<int64_t>(fi0), i1 = static_cast<int64_t>(fi1);
  const auto j0 = static_cast<int64_t>(fj0), j1 = static_cast<int64_t>(fj1);
  auto holds = [](int64_t i, int64_t j, const Eigen::Vector2d& p)
  { return std::floor(p.x()) == static_cast<double>(i) && std::floor(p.y()) == static_cast<double>(j); };
  const bool polygonal = polygon.size() >= 3;
  for (int64_t j = j0; j <= j1; ++j)
  {
    const int8_t* row = mask.data.data() + static_cast<std::size_t>(j) * mask.width;
    for (int64_t i = i0; i <= i1; ++i)
    {
      if (!lethalKeepout(row[i])) continue;
      const double px = i + 0.5, py = j + 0.5;
      if ((px - c.x()) * (px - c.x()) + (py - c.y()) * (py - c.y()) <= rc * rc) return true;
      if (holds(i, j, c)) return true;
      if (polygonal && pointInPolygon(polygon, px, py, CrossingOrigin::EdgeEnd)) return true;
      for (const Eigen::Vector2d& p : polygon)
        if (holds(i, j, p)) return true;
    }
  }
  return false;
}

void writeEscapeRamp(std::vector<uint8_t>& costs, uint32_t width, uint32_t height, double resolution,
                     double ramp_length, uint8_t top, std::vector<uint8_t>& ramp, DistanceTransformScratch& scratch)
{
  if (width == 0 || height == 0) return;
  // The distance engine takes costs that do not rise with the distance: it computes
  // g = top + 1 - escapeRampCost(depth) (top + 1 at the edge, 1 from ramp_length on, 0 beyond its
  // reach), and the ramp is top + 1 - g, the top where g is 1 or 0 (deep inside, or no way out at all).
  // The ways out are the cells that are not lethal.
  const double cells = std::ceil(ramp_length / resolution);
  const int64_t max_cells = cells > 0.0 && cells < 1e6 ? static_cast<int64_t>(cells) : (cells >= 1e6 ? 1000000 : 0);
  const DistanceCosts complement(max_cells,
                                 [&](uint64_t d2)
                                 {
                                   const double depth = std::sqrt(static_cast<double>(d2)) * resolution;
                                   return static_cast<uint8_t>(top + 1 - escapeRampCost(depth, ramp_length, top));
                                 });
  ramp.assign(costs.size(), top);
  distanceCostRows(costs.data(), static_cast<int>(width), static_cast<int>(height), width,
                   SourceRange{0, MAX_NON_OBSTACLE}, complement,
                   DistanceWindow{0, 0, static_cast<int>(width), static_cast<int>(height)}, scratch,
                   [&](int y, const uint8_t* g)
                   {
                     uint8_t* out = ramp.data() + static_cast<std::size_t>(y) * width;
                     for (uint32_t x = 0; x < width; ++x)
                       out[x] = g[x] <= 1 ? top : static_cast<uint8_t>(top + 1 - g[x]);
                   });
  for (std::size_t k = 0; k < costs.size(); ++k)
    if (costs[k] >= INSCRIBED_INFLATED_OBSTACLE) costs[k] = ramp[k];
}

void KeepoutFilter::onInitializeFilter(const ParamReader& params)
{
  config_ = parseKeepoutFilterConfig(params);
}

void KeepoutFilter::processPose(const OccupancyGridData& mask, const Transform2D& to_mask, double robot_x,
                                double robot_y, double robot_yaw)
{
  if (!config_.override_lethal_cost) return;
  const double resolution = layered_costmap_ ? layered_costmap_->getCostmap().getResolution() : mask.resolution;
  const double inscribed = layered_costmap_ ? layered_costmap_->getInscribedRadius() : 0.0;
  const double clearance = escapeClearance(inscribed, resolution);
  const bool in = robotInLethalKeepout(mask, to_mask, robot_x, robot_y, robot_yaw, getFootprint(), clearance);
  if (in == escaping_) return;
  escaping_ = in;
  invalidateCosts();
  requestRedraw();
  std::ostringstream text;
  text << name_ << ": ";
  if (in)
    text << "the robot at (" << robot_x << ", " << robot_y << ") overlaps a lethal keepout zone (under its footprint "
         << "or within " << clearance << " m of its centre): escape mode on, the zone's lethal cells cost a ramp "
         << "of 1.." << config_.lethal_override_cost << " rising away from the nearest way out";
  else
    text << "the robot at (" << robot_x << ", " << robot_y << ") is clear of every lethal keepout zone: escape mode "
         << "off, the zones are lethal again";
  context_->report(in ? Severity::Warn : Severity::Info, "escape", text.str());
}

void KeepoutFilter::onFootprintChanged()
{
  if (!escaping_) return;
  invalidateCosts();  // the ramp's length is the footprint's circumscribed radius
  requestRedraw();
}

std::size_t KeepoutFilter::computeCosts(const OccupancyGridData& mask, std::vector<uint8_t>& costs)
{
  std::array<uint8_t, 256> table{};
  for (int b = 0; b < 256; ++b)
    table[static_cast<std::size_t>(b)] = maskValueCost(static_cast<int8_t>(b));
  costs.resize(mask.data.size());
  std::size_t invalid = 0;
  for (std::size_t k = 0; k < mask.data.size(); ++k)
  {
    const int8_t v = mask.data[k];
    invalid += (v < -1 || v > 100) ? 1 : 0;
    costs[k] = table[static_cast<uint8_t>(v)];
  }
  if (escaping_)
  {
    const double circumscribed = layered_costmap_ ? layered_costmap_->getCircumscribedRadius() : 0.0;
    writeEscapeRamp(costs, mask.width, mask.height, mask.resolution, std::max(circumscribed, mask.resolution),
                    static_cast<uint8_t>(config_.lethal_override_cost), ramp_, scratch_);
  }
  return invalid;
}
}  // namespace costmap_layers
