#include "costmap_layers/core/layers/asymmetric_inflation_layer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/grid/costmap_2d.hpp"
#include "costmap_layers/core/rules/cost_rules.hpp"
#include "costmap_layers/core/rules/limits.hpp"

namespace costmap_layers
{
AsymmetricInflationConfig parseAsymmetricInflationConfig(const ParamReader& params)
{
  AsymmetricInflationConfig cfg;
  InflationConfig& inf = cfg.inflation;
  inf.inflation_radius = params.getDouble("inflation_radius", 2.0, 0.0, limits::kMaxDistance);  // Nav2's default
  cfg.cost_scaling_factor_left = params.getDouble("cost_scaling_factor_left", cfg.cost_scaling_factor_left, 0.0);
  cfg.cost_scaling_factor_right = params.getDouble("cost_scaling_factor_right", cfg.cost_scaling_factor_right, 0.0);
  inf.cost_scaling_factor = std::max(cfg.cost_scaling_factor_left, cfg.cost_scaling_factor_right);
  inf.inflate_unknown = params.getBool("inflate_unknown", inf.inflate_unknown);
  inf.inflate_around_unknown = params.getBool("inflate_around_unknown", inf.inflate_around_unknown);
  inf.num_threads = parseInflationThreads(params, inf.num_threads);
  cfg.plan_topic = params.getTopic("plan_topic", cfg.plan_topic);
  cfg.goal_distance_threshold =
      params.getDouble("goal_distance_threshold", cfg.goal_distance_threshold, 0.0, limits::kMaxDistance);
  return cfg;
}

PathSide sideOfSegments(const PathSegment* segments, const uint32_t* indices, std::size_t count, double radius,
                        double x, double y)
{
  double best = std::numeric_limits<double>::infinity();
  double best_cross = 0.0;
  for (std::size_t k = 0; k < count; ++k)
  {
    const PathSegment& s = segments[indices[k]];
    const double abx = s.bx - s.ax, aby = s.by - s.ay;
    const double acx = x - s.ax, acy = y - s.ay;
    const double len_sq = abx * abx + aby * aby;
    double d2, cross;
    if (len_sq < 1e-6)  // Nav2's: a segment under 1 mm has no direction
    {
      d2 = acx * acx + acy * acy;
      cross = 0.0;
    }
    else
    {
      const double t = std::clamp((acx * abx + acy * aby) / len_sq, 0.0, 1.0);
      const double dx = acx - t * abx, dy = acy - t * aby;
      d2 = dx * dx + dy * dy;
      cross = abx * acy - aby * acx;
    }
    if (d2 < best)  // the first of equally near segments stays
    {
      best = d2;
      best_cross = cross;
    }
  }
  if (!(best <= radius * radius)) return PathSide::None;
  return best_cross > 0.0 ? PathSide::Left : best_cross < 0.0 ? PathSide::Right : PathSide::None;
}

namespace
{
/// Clips the segment to the rectangle (Liang-Barsky); false when it misses it.
bool clipSegment(PathSegment& s, double x0, double y0, double x1, double y1)
{
  double t0 = 0.0, t1 = 1.0;
  const double dx = s.bx - s.ax, dy = s.by - s.ay;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {s.ax - x0, x1 - s.ax, s.ay - y0, y1 - s.ay};
  for (int k = 0; k < 4; ++k)
  {
    if (p[k] == 0.0)
    {
      if (q[k] < 0.0) return false;
      continue;
    }
    const double r = q[k] / p[k];
    if (p[k] < 0.0)
      t0 = std::max(t0, r);
    else
      t1 = std::min(t1, r);
    if (t0 > t1) return false;
  }
  const PathSegment in = s;
  s.ax = in.ax + t0 * dx;
  s.ay = in.ay + t0 * dy;
  s.bx = in.ax + t1 * dx;
  s.by = in.ay + t1 * dy;
  return true;
}
}  // namespace

bool PathSideIndex::build(const std::vector<PathSegment>& segments, double radius, double x0, double y0, double x1,
                          double y1, std::size_t max_entries)
{
  segments_.assign(segments.begin(), segments.end());
  radius_ = radius;
  x0_ = x0;
  y0_ = y0;
  // A bucket lists every segment whose pieces' boxes, grown by the radius, meet it: a point then finds
  // in its own bucket every segment within reach. Buckets at least `radius` wide (so that a piece
  // touches a few of them) and at most 512 a side whatever the area (bounded memory).
  size_ = std::max({radius, (x1 - x0) / 512.0, (y1 - y0) / 512.0, 1e-9});
  nx_ = static_cast<int>(std::floor((x1 - x0) / size_)) + 1;
  ny_ = static_cast<int>(std::floor((y1 - y0) / size_)) + 1;
  const std::size_t buckets = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  first_.assign(buckets + 1, 0);
  count_.assign(buckets, UINT32_MAX);  // during a walk: the last segment listed in each bucket
  indices_.clear();

  // Each segment is walked in pieces no longer than a bucket; the buckets each piece's box (grown by
  // the radius) touches list the segment once. Walked twice: to count, then to fill.
  auto walk = [&](auto&& visit)
  {
    for (std::size_t n = 0; n < segments.size(); ++n)
    {
      PathSegment s = segments[n];
      if (!clipSegment(s, x0 - radius, y0 - radius, x1 + radius, y1 + radius)) continue;
      const double len = std::hypot(s.bx - s.ax, s.by - s.ay);
      const int pieces = std::max(1, static_cast<int>(std::ceil(len / size_)));
      for (int k = 0; k < pieces; ++k)
      {
        const double ta = static_cast<double>(k) / pieces, tb = static_cast<double>(k + 1) / pieces;
        const double pax = s.ax + ta * (s.bx - s.ax), pay = s.ay + ta * (s.by - s.ay);
        const double pbx = s.ax + tb * (s.bx - s.ax), pby = s.ay + tb * (s.by - s.ay);
        auto bucket = [&](double v, double origin, int n_max)
        { return std::clamp(static_cast<int>(std::floor((v - origin) / size_)), 0, n_max - 1); };
        const int bx0 = bucket(std::min(pax, pbx) - radius, x0, nx_),
                  bx1 = bucket(std::max(pax, pbx) + radius, x0, nx_);
        const int by0 = bucket(std::min(pay, pby) - radius, y0, ny_),
                  by1 = bucket(std::max(pay, pby) + radius, y0, ny_);
        for (int by = by0; by <= by1; ++by)
          for (int bx = bx0; bx <= bx1; ++bx)
          {
            const std::size_t b = static_cast<std::size_t>(by) * static_cast<std::size_t>(nx_) + bx;
            if (count_[b] == n) continue;
            count_[b] = static_cast<uint32_t>(n);
            if (!visit(b, static_cast<uint32_t>(n))) return false;
          }
      }
    }
    return true;
  };
  std::size_t total = 0;
  const bool fits = walk(
      [&](std::size_t b, uint32_t)
      {
        ++first_[b + 1];
        return ++total <= max_entries;
      });
  if (!fits)
  {
    std::fill(first_.begin(), first_.end(), 0u);
    return false;
  }
  for (std::size_t b = 0; b < buckets; ++b)
    first_[b + 1] += first_[b];
  indices_.resize(total);
  std::fill(count_.begin(), count_.end(), UINT32_MAX);
  std::vector<uint32_t> fill(first_.begin(), first_.end() - 1);
  walk(
      [&](std::size_t b, uint32_t n)
      {
        indices_[fill[b]++] = n;
        return true;
      });
  return true;
}

PathSide PathSideIndex::side(double x, double y) const
{
  if (segments_.empty() || nx_ <= 0 || ny_ <= 0) return PathSide::None;
  const int bx = std::clamp(static_cast<int>(std::floor((x - x0_) / size_)), 0, nx_ - 1);
  const int by = std::clamp(static_cast<int>(std::floor((y - y0_) / size_)), 0, ny_ - 1);
  const std::size_t b = static_cast<std::size_t>(by) * static_cast<std::size_t>(nx_) + bx;
  return sideOfSegments(segments_.data(), indices_.data() + first_[b], first_[b + 1] - first_[b], radius_, x, y);
}

void AsymmetricInflationLayer::onInitialize()
{
  config_ = parseAsymmetricInflationConfig(ParamReader(context_->params(), name_));
  initializeWith(config_.inflation);
  plan_topic_ = config_.plan_topic;
  addInput(InputPort::path(config_.plan_topic, [this](const std::shared_ptr<const PathData>& plan) { setPlan(plan); }));
}

void AsymmetricInflationLayer::onReconfigure(const ParamValue& params)
{
  const AsymmetricInflationConfig next = parseAsymmetricInflationConfig(ParamReader(params, name_));
  if (next.plan_topic != config_.plan_topic)
    throw std::invalid_argument(name_ + ": plan_topic cannot change at run time");
  setConfig(next.inflation);  // redraws the whole map
  config_ = next;
}

std::vector<ParamSpec> AsymmetricInflationLayer::tunableLayerParameters(const ParamValue& params) const
{
  std::vector<ParamSpec> specs =
      recordParameters(params, name_, [](const ParamReader& r) { parseAsymmetricInflationConfig(r); });
  specs.erase(std::remove_if(specs.begin(), specs.end(), [](const ParamSpec& s) { return s.name == "plan_topic"; }),
              specs.end());
  return specs;
}

std::string AsymmetricInflationLayer::setPlan(const std::shared_ptr<const PathData>& plan)
{
  InputError error = plan ? validatePath(*plan) : InputError::of("poses", "no plan");
  if (error.ok() && plan->poses.size() < 2)
    error = InputError::of("poses", "poses has " + std::to_string(plan->poses.size()) +
                                        " entries: a plan needs two poses or more to have sides");
  if (error.ok())
  {
    std::lock_guard<std::mutex> lock(plan_mutex_);
    plan_ = plan;
    ++plan_generation_;
    return {};
  }
  if (context_)
    context_->report(Severity::Error, "plan/" + error.field,
                     name_ + ": plan on " + plan_topic_ + " refused, keeping the previous one: " + error.message);
  return error.message;
}

AsymmetricInflationLayer::Off AsymmetricInflationLayer::preparePlan(double robot_x, double robot_y)
{
  std::shared_ptr<const PathData> plan;
  uint64_t generation = 0;
  {
    std::lock_guard<std::mutex> lock(plan_mutex_);
    plan = plan_;
    generation = plan_generation_;
  }
  if (!plan)
  {
    if (!said_no_plan_ && context_)
    {
      std::ostringstream s;
      s << name_ << ": no plan on " << config_.plan_topic << " yet: symmetric inflation with the larger factor ("
        << config_.inflation.cost_scaling_factor << ") until one arrives";
      context_->report(Severity::Info, "plan/none", s.str());
    }
    said_no_plan_ = true;
    return Off::NoPlan;
  }
  if (config_.cost_scaling_factor_left == config_.cost_scaling_factor_right) return Off::EqualFactors;
  if (cellInflationRadius() <= 0) return Off::EqualFactors;  // nothing is inflated at all

  Transform2D to_global;
  const std::string& global = context_->globalFrame();
  if (plan->frame_id != global)
  {
    std::string error;
    const auto t = context_->lookupTransform(global, plan->frame_id, &error);
    if (!t)
    {
      // Nav2's: symmetric for this cycle; the plan stays and is tried again at the next.
      context_->report(Severity::Error, "plan/header.frame_id",
                       name_ + ": cannot transform the plan on " + config_.plan_topic + " from header.frame_id " +
                           shownText(plan->frame_id) + " into " + global +
                           ": symmetric inflation this cycle: " + shownText(error, 400));
      return Off::NoTransform;
    }
    to_global = *t;
  }
  const double c = std::cos(to_global.yaw), s = std::sin(to_global.yaw);
  auto place = [&](const PathData::Point& p, double& x, double& y)
  {
    x = to_global.x + c * p.x - s * p.y;
    y = to_global.y + s * p.x + c * p.y;
  };
  double gx, gy;
  place(plan->poses.back(), gx, gy);
  if (std::hypot(gx - robot_x, gy - robot_y) <= config_.goal_distance_threshold) return Off::NearGoal;

  const Costmap2D& grid = layered_costmap_->getCostmap();
  const double mx0 = grid.getOriginX(), my0 = grid.getOriginY();
  const double mx1 = mx0 + grid.getSizeInMetersX(), my1 = my0 + grid.getSizeInMetersY();
  const bool same = generation == used_generation_ && to_global.x == used_transform_.x &&
                    to_global.y == used_transform_.y && to_global.yaw == used_transform_.yaw && mx0 == used_rect_[0] &&
                    my0 == used_rect_[1] && mx1 == used_rect_[2] && my1 == used_rect_[3];
  if (!same)
  {
    // Nav2's culling: only segments whose box grown by the radius meets the costmap can be near a cell.
    const double r = config_.inflation.inflation_radius;
    segments_.clear();
    double px, py;
    place(plan->poses.front(), px, py);
    for (std::size_t i = 1; i < plan->poses.size(); ++i)
    {
      double qx, qy;
      place(plan->poses[i], qx, qy);
      if (std::max(px, qx) + r >= mx0 && std::min(px, qx) - r <= mx1 && std::max(py, qy) + r >= my0 &&
          std::min(py, qy) - r <= my1)
        segments_.push_back({px, py, qx, qy});
      px = qx;
      py = qy;
    }
    index_ok_ = segments_.empty() || index_.build(segments_, r, mx0, my0, mx1, my1, kMaxIndexEntries);
    used_generation_ = generation;
    used_transform_ = to_global;
    used_rect_ = {mx0, my0, mx1, my1};
  }
  if (segments_.empty()) return Off::NoPlan;
  if (!index_ok_)
  {
    context_->report(Severity::Error, "plan/poses",
                     name_ + ": the plan on " + config_.plan_topic + " (" + std::to_string(plan->poses.size()) +
                         " poses) crosses the costmap so often that its index would exceed " +
                         std::to_string(kMaxIndexEntries) + " entries: symmetric inflation");
    return Off::TooManyEntries;
  }
  return Off::None;
}

void AsymmetricInflationLayer::rebuildSideTable(double resolution)
{
  const int cells = cellInflationRadius();
  const double factor = std::min(config_.cost_scaling_factor_left, config_.cost_scaling_factor_right);
  const TableKey key{cells, factor, resolution, inscribedRadius()};
  if (key == side_key_) return;
  const uint64_t cap_sq = static_cast<uint64_t>(cells) * static_cast<uint64_t>(cells);
  const double inscribed = key.inscribed;
  // The InflationLayer's cost rule with the smaller factor, 0 past the radius.
  side_costs_ = cells <= 0 || !(resolution > 0.0)
                    ? DistanceCosts()
                    : DistanceCosts(cells,
                                    [&](uint64_t d2) -> uint8_t {
                                      return d2 > cap_sq ? 0
                                                         : inflationCost(std::sqrt(static_cast<double>(d2)), resolution,
                                                                         inscribed, factor);
                                    });
  side_key_ = key;
}

void AsymmetricInflationLayer::updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x,
                                            double* min_y, double* max_x, double* max_y)
{
  const bool was_active = active_;
  const uint64_t was_generation = used_generation_;
  const Transform2D was_transform = used_transform_;
  off_ = preparePlan(robot_x, robot_y);
  active_ = off_ == Off::None;
  const bool moved = used_generation_ != was_generation || used_transform_.x != was_transform.x ||
                     used_transform_.y != was_transform.y || used_transform_.yaw != was_transform.yaw;
  // Sides that appear, go or move change costs anywhere: the whole map once (as Nav2 does).
  if (active_ != was_active || (active_ && moved)) InflationLayer::reset();
  InflationLayer::updateBounds(robot_x, robot_y, robot_yaw, min_x, min_y, max_x, max_y);
  if (!active_) return;
  const double res = layered_costmap_->getCostmap().getResolution();
  rebuildSideTable(res);
  const double limit = std::numeric_limits<float>::max();
  if (!(*min_x <= *max_x) || !(*min_y <= *max_y) || *min_x <= -limit || *max_x >= limit) return;
  // A change below reaches as far as the smaller factor's costs do.
  const double extra = static_cast<double>(side_costs_.reach() - costReach()) * res;
  if (extra <= 0.0) return;
  *min_x -= extra;
  *min_y -= extra;
  *max_x += extra;
  *max_y += extra;
}

void AsymmetricInflationLayer::updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j)
{
  if (!active_)
  {
    InflationLayer::updateCosts(master_grid, min_i, min_j, max_i, max_j);
    return;
  }
  const double res = master_grid.getResolution();
  rebuildSideTable(res);
  const int width = static_cast<int>(master_grid.getSizeInCellsX());
  const int height = static_cast<int>(master_grid.getSizeInCellsY());
  const int x0 = std::max(min_i, 0), y0 = std::max(min_j, 0);
  const int x1 = std::min(max_i, width), y1 = std::min(max_j, height);
  if (x0 >= x1 || y0 >= y1 || !side_costs_.any())
  {
    InflationLayer::updateCosts(master_grid, min_i, min_j, max_i, max_j);
    return;
  }
  // The seeds come from the grid as the layers below left it (the first pass does not change which
  // cells are sources, but may write onto unknown ones).
  const int reach = static_cast<int>(std::min<int64_t>(side_costs_.reach(), std::max(width, height)));
  const int rx0 = std::max(0, x0 - reach), ry0 = std::max(0, y0 - reach);
  const int rx1 = std::min(width, x1 + reach), ry1 = std::min(height, y1 + reach);
  const int rw = rx1 - rx0, rh = ry1 - ry0;
  seeds_.assign(static_cast<std::size_t>(rw) * static_cast<std::size_t>(rh), 0);
  const PathSide disfavoured =
      config_.cost_scaling_factor_left < config_.cost_scaling_factor_right ? PathSide::Left : PathSide::Right;
  const SourceRange source = sourceRange();
  const uint8_t* data = master_grid.data();
  const double ox = master_grid.getOriginX(), oy = master_grid.getOriginY();
  bool any = false;
  for (int j = ry0; j < ry1; ++j)
  {
    const uint8_t* row = data + static_cast<std::size_t>(j) * width;
    for (int i = rx0; i < rx1; ++i)
    {
      // Sources are 254 (and 255): eight cells all below 128 hold none.
      if (i + 8 <= rx1)
      {
        uint64_t word;
        std::memcpy(&word, row + i, sizeof word);
        if ((word & 0x8080808080808080ull) == 0)
        {
          i += 7;
          continue;
        }
      }
      if (!source.contains(row[i])) continue;
      // Nav2's boundary: on the map's edge, or a 4-neighbour that is not a source.
      const bool boundary = i == 0 || j == 0 || i == width - 1 || j == height - 1 || !source.contains(row[i - 1]) ||
                            !source.contains(row[i + 1]) || !source.contains(row[i - width]) ||
                            !source.contains(row[i + width]);
      if (!boundary) continue;
      if (index_.side(ox + (i + 0.5) * res, oy + (j + 0.5) * res) != disfavoured) continue;
      seeds_[static_cast<std::size_t>(j - ry0) * rw + (i - rx0)] = 1;
      any = true;
    }
  }
  InflationLayer::updateCosts(master_grid, min_i, min_j, max_i, max_j);
  if (!any) return;
  DistanceWindow win;
  win.x0 = x0 - rx0;
  win.y0 = y0 - ry0;
  win.x1 = x1 - rx0;
  win.y1 = y1 - ry0;
  const CostMergeRule rule = mergeRule();
  uint8_t* out = master_grid.data();
  distanceCostRows(seeds_.data(), rw, rh, rw, SourceRange{1, 1}, side_costs_, win, side_scratch_,
                   [&](int y, const uint8_t* costs)
                   {
                     uint8_t* row = out + static_cast<std::size_t>(y + ry0) * width + x0;
                     const int n = x1 - x0;
                     int k = 0;
                     // Most of a row is beyond the disfavoured sources' reach (cost 0, which changes
                     // nothing): skipped eight cells at a time.
                     for (; k + 8 <= n; k += 8)
                     {
                       uint64_t word;
                       std::memcpy(&word, costs + k, sizeof word);
                       if (word == 0) continue;
                       for (int m = k; m < k + 8; ++m)
                         row[m] = rule.apply(row[m], costs[m]);
                     }
                     for (; k < n; ++k)
                       row[k] = rule.apply(row[k], costs[k]);
                   });
}

LayerStatus AsymmetricInflationLayer::status() const
{
  LayerStatus s = InflationLayer::status();
  std::size_t poses = 0;
  {
    std::lock_guard<std::mutex> lock(plan_mutex_);
    if (plan_) poses = plan_->poses.size();
  }
  s.add("plan poses", std::to_string(poses));
  static const char* const kWhy[] = {"asymmetric",
                                     "symmetric: no plan near the costmap",
                                     "symmetric: equal factors",
                                     "symmetric: within goal_distance_threshold of the goal",
                                     "symmetric: the plan's frame cannot be transformed",
                                     "symmetric: the plan crosses the costmap too often"};
  s.add("inflation", kWhy[static_cast<int>(off_)]);
  if (off_ == Off::NoTransform || off_ == Off::TooManyEntries) s.raise(StatusLevel::Warn, kWhy[static_cast<int>(off_)]);
  return s;
}
}  // namespace costmap_layers
