#include "costmap_layers/core/layers/static_layer.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "costmap_layers/core/grid/cost_values.hpp"
#include "costmap_layers/core/filters/costmap_filter.hpp"
#include "costmap_layers/core/grid/footprint.hpp"
#include "costmap_layers/core/costmap/layered_costmap.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/rules/stamp_order.hpp"

// The map conversion of a trinary map, written once with Highway (foreach_target.h compiles it per
// target; HWY_DYNAMIC_DISPATCH picks one at run time).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/core/layers/static_layer.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace costmap_layers
{
namespace HWY_NAMESPACE
{
namespace hn = hwy::HWY_NAMESPACE;

/// out[k] = in[k] == unknown ? unknown_cost : (in[k] >= threshold ? 254 : 0), bytes compared unsigned:
/// interpretStaticValue() of a trinary map, one vector at a time.
void ConvertTrinary(const uint8_t* HWY_RESTRICT in, uint8_t* HWY_RESTRICT out, std::size_t n, uint8_t unknown,
                    uint8_t unknown_cost, uint8_t threshold)
{
  const hn::ScalableTag<uint8_t> d;
  const std::size_t N = hn::Lanes(d);
  const auto vu = hn::Set(d, unknown), vuc = hn::Set(d, unknown_cost), vt = hn::Set(d, threshold);
  const auto lethal = hn::Set(d, LETHAL_OBSTACLE);
  std::size_t k = 0;
  for (; k + N <= n; k += N)
  {
    const auto v = hn::LoadU(d, in + k);
    const auto cost = hn::IfThenElseZero(hn::Eq(hn::Max(v, vt), v), lethal);
    hn::StoreU(hn::IfThenElse(hn::Eq(v, vu), vuc, cost), d, out + k);
  }
  for (; k < n; ++k)
    out[k] = in[k] == unknown ? unknown_cost : (in[k] >= threshold ? LETHAL_OBSTACLE : FREE_SPACE);
}
}  // namespace HWY_NAMESPACE
}  // namespace costmap_layers
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace costmap_layers
{
HWY_EXPORT(ConvertTrinary);

StaticConfig parseStaticConfig(const ParamReader& params, bool default_track_unknown)
{
  StaticConfig cfg;
  cfg.map_topic = params.getTopic("map_topic", cfg.map_topic, true);
  if (cfg.map_topic.empty()) params.fail("map_topic", "must not be empty");
  cfg.first_map_only = params.getBool("first_map_only", cfg.first_map_only);
  cfg.subscribe_to_updates = params.getBool("subscribe_to_updates", cfg.subscribe_to_updates);
  cfg.track_unknown_space = params.getBool("track_unknown_space", default_track_unknown);
  cfg.use_maximum = params.getBool("use_maximum", cfg.use_maximum);
  // costmap_2d clamps the threshold to [0, 100] rather than rejecting it.
  cfg.lethal_cost_threshold = std::clamp(params.getInt("lethal_cost_threshold", cfg.lethal_cost_threshold), 0, 100);
  cfg.unknown_cost_value = params.getInt("unknown_cost_value", cfg.unknown_cost_value, -128, 255);
  cfg.trinary_costmap = params.getBool("trinary_costmap", cfg.trinary_costmap);
  cfg.footprint_clearing_enabled = params.getBool("footprint_clearing_enabled", cfg.footprint_clearing_enabled);
  cfg.restore_cleared_footprint = params.getBool("restore_cleared_footprint", cfg.restore_cleared_footprint);
  return cfg;
}

void StaticLayer::onInitialize()
{
  config_ = parseStaticConfig(ParamReader(context_->params(), name_), layered_costmap_->isTrackingUnknown());
  // costmap_2d clamps it without a word: say so.
  if (const ParamValue* t = context_->params().find("lethal_cost_threshold");
      t != nullptr && t->type() == ParamValue::Type::Int && t->asInt() != config_.lethal_cost_threshold)
    context_->report(Severity::Warn, "lethal_cost_threshold",
                     name_ + ": lethal_cost_threshold " + std::to_string(t->asInt()) +
                         " is outside the occupancy range [0, 100]: " + std::to_string(config_.lethal_cost_threshold) +
                         " used (as costmap_2d clamps it)");
  rebuildTable();
  current_ = false;  // until the first map
  addInput(InputPort::grid(InputKind::Map, config_.map_topic,
                           [this](const std::shared_ptr<const OccupancyGridData>& map) { setMap(map); }));
  if (config_.subscribe_to_updates)
    addInput(InputPort::mapUpdates(config_.map_topic + "_updates",
                                   [this](const std::shared_ptr<const OccupancyGridUpdateData>& u)
                                   {
                                     if (u) applyUpdate(u->x, u->y, u->width, u->height, u->data, u->stamp_ns);
                                   }));
}

void StaticLayer::rebuildTable()
{
  for (int b = 0; b < 256; ++b)
    table_[b] = interpretStaticValue(static_cast<int8_t>(static_cast<uint8_t>(b)), config_);
}

bool StaticLayer::mapAccepted() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return accepted_any_;
}

std::string StaticLayer::setMap(std::shared_ptr<const OccupancyGridData> map)
{
  InputError error = map ? validateGrid(*map) : InputError::of("data", "no map");
  const uint64_t now = context_ ? context_->nowNs() : UINT64_MAX;
  if (error.ok())
  {
    // The stamp check and the hand-over under one lock: two maps arriving together cannot both pass
    // the check and then install the older one last.
    std::lock_guard<std::mutex> lock(mutex_);
    if (isOutOfOrder(map->stamp_ns, map_stamp_ns_, now))
      error = InputError::of("header.stamp", outOfOrderError(map->stamp_ns, map_stamp_ns_, "map"));
    else
    {
      if (config_.first_map_only && accepted_any_) return {};
      pending_map_ = std::move(map);
      pending_updates_.clear();  // they referred to the previous map
      pending_update_cells_ = 0;
      accepted_any_ = true;
      ++maps_accepted_;
      map_received_ns_ = now;
      latest_rejected_ = false;
      map_stamp_ns_ = pending_map_->stamp_ns;
      latest_width_ = pending_map_->width;
      latest_height_ = pending_map_->height;
      return {};
    }
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++maps_rejected_;
    last_rejection_ = error.message;
    latest_rejected_ = true;
  }
  // Throttled per field, so that each distinct problem is still reported once.
  const std::string text =
      name_ + ": map on " + config_.map_topic + " rejected, keeping the previous one: " + error.message;
  if (context_) context_->report(Severity::Error, "map/" + error.field, text);
  return text;
}

std::string StaticLayer::applyUpdate(int64_t x, int64_t y, uint32_t width, uint32_t height,
                                     const std::vector<int8_t>& data, uint64_t stamp_ns)
{
  std::string why, key;
  uint64_t dropped = 0;
  const uint64_t now = context_ ? context_->nowNs() : UINT64_MAX;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!config_.subscribe_to_updates)
      why = "subscribe_to_updates is false", key = "subscribe_to_updates";
    else if (!accepted_any_)
      why = "no map yet", key = "no_map";
    else if (isOutOfOrder(stamp_ns, map_stamp_ns_, now))
      why = outOfOrderError(stamp_ns, map_stamp_ns_, "map"), key = "header.stamp";
    else if (const InputError e = validateGridUpdate(x, y, width, height, data.size(), latest_width_, latest_height_);
             !e.ok())
      why = e.message, key = e.field;
    else
    {
      const uint64_t cells = static_cast<uint64_t>(width) * height;
      while (!pending_updates_.empty() &&
             (pending_updates_.size() >= kMaxPendingUpdates || pending_update_cells_ + cells > kMaxPendingUpdateCells))
      {
        pending_update_cells_ -=
            static_cast<uint64_t>(pending_updates_.front().width) * pending_updates_.front().height;
        pending_updates_.erase(pending_updates_.begin());
        dropped = ++dropped_updates_;
      }
      pending_updates_.push_back(
          PendingUpdate{static_cast<uint32_t>(x), static_cast<uint32_t>(y), width, height, data});
      pending_update_cells_ += cells;
    }
    ++(why.empty() ? updates_accepted_ : updates_rejected_);
  }
  if (why.empty())
  {
    if (dropped != 0 && context_)
      context_->report(Severity::Warn, "map_update/flood",
                       name_ + ": map updates arrive faster than the update loop applies them: dropped the oldest (" +
                           std::to_string(dropped) + " dropped so far)");
    return {};
  }
  const std::string error = name_ + ": map update rejected: " + why;
  // Throttled per field, so that each distinct problem is still reported once.
  if (context_) context_->report(Severity::Error, "map_update/" + key, error);
  return error;
}

void StaticLayer::markDirty(unsigned x0, unsigned y0, unsigned x1, unsigned y1)
{
  if (x0 >= x1 || y0 >= y1) return;
  if (!dirty_)
  {
    dirty_x0_ = x0, dirty_y0_ = y0, dirty_x1_ = x1, dirty_y1_ = y1;
    dirty_ = true;
    return;
  }
  dirty_x0_ = std::min(dirty_x0_, x0);
  dirty_y0_ = std::min(dirty_y0_, y0);
  dirty_x1_ = std::max(dirty_x1_, x1);
  dirty_y1_ = std::max(dirty_y1_, y1);
}

void StaticLayer::processMap(const OccupancyGridData& map)
{
  const bool rolling = layered_costmap_->isRolling();
  auto differs = [&map](const Costmap2D& c)
  {
    return c.getSizeInCellsX() != map.width || c.getSizeInCellsY() != map.height ||
           c.getResolution() != map.resolution || c.getOriginX() != map.origin_x || c.getOriginY() != map.origin_y;
  };
  // Fill the own grid at the map's geometry first; a resize of the master then finds it matching
  // (see matchSize) and keeps it.
  if (differs(costmap_)) costmap_.resizeMap(map.width, map.height, map.resolution, map.origin_x, map.origin_y);
  const std::size_t n = map.data.size();
  uint8_t* out = costmap_.data();
  const int8_t* in = map.data.data();
  if (config_.trinary_costmap)
    // The table is three-valued then (rebuildTable() says the same): compare instead of looking up.
    HWY_DYNAMIC_DISPATCH(ConvertTrinary)
  (reinterpret_cast<const uint8_t*>(in), out, n, static_cast<uint8_t>(config_.unknown_cost_value),
   table_[static_cast<uint8_t>(config_.unknown_cost_value)], static_cast<uint8_t>(config_.lethal_cost_threshold));
  else for (std::size_t k = 0; k < n; ++k) out[k] = table_[static_cast<uint8_t>(in[k])];
  if (!rolling && differs(layered_costmap_->getCostmap()))
    layered_costmap_->resizeMap(map.width, map.height, map.resolution, map.origin_x, map.origin_y, true);
  if (!rolling && map.origin_yaw != 0.0)
    context_->report(Severity::Warn, "map_yaw",
                     name_ + ": the map's origin yaw is ignored when the costmap is not rolling (as costmap_2d)");
  map_frame_ = map.frame_id;
  map_yaw_ = map.origin_yaw;
  map_received_ = true;
  current_ = true;
  dirty_ = false;
  markDirty(0, 0, map.width, map.height);
}

void StaticLayer::processUpdate(const PendingUpdate& u)
{
  const unsigned sx = costmap_.getSizeInCellsX(), sy = costmap_.getSizeInCellsY();
  if (!map_received_ || static_cast<uint64_t>(u.x) + u.width > sx || static_cast<uint64_t>(u.y) + u.height > sy)
  {
    context_->report(Severity::Error, "map_update", name_ + ": map update does not fit the map, skipped");
    return;
  }
  const int8_t* in = u.data.data();
  for (uint32_t row = 0; row < u.height; ++row)
  {
    uint8_t* out = costmap_.data() + costmap_.getIndex(u.x, u.y + row);
    for (uint32_t k = 0; k < u.width; ++k)
      out[k] = table_[static_cast<uint8_t>(*in++)];
  }
  markDirty(u.x, u.y, u.x + u.width, u.y + u.height);
}

void StaticLayer::matchSize()
{
  if (layered_costmap_->isRolling()) return;  // the own grid is the map's
  const Costmap2D& master = layered_costmap_->getCostmap();
  if (master.getSizeInCellsX() == costmap_.getSizeInCellsX() &&
      master.getSizeInCellsY() == costmap_.getSizeInCellsY() && master.getResolution() == costmap_.getResolution() &&
      master.getOriginX() == costmap_.getOriginX() && master.getOriginY() == costmap_.getOriginY())
    return;  // e.g. the resize this layer asked for: the map just drawn stays
  CostmapLayer::matchSize();
}

void StaticLayer::reset()
{
  if (map_received_) markDirty(0, 0, costmap_.getSizeInCellsX(), costmap_.getSizeInCellsY());
}

void StaticLayer::updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y,
                               double* max_x, double* max_y)
{
  std::shared_ptr<const OccupancyGridData> map;
  std::vector<PendingUpdate> updates;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    map = std::move(pending_map_);
    pending_map_.reset();
    updates.swap(pending_updates_);
    pending_update_cells_ = 0;
  }
  if (map) processMap(*map);
  for (const auto& u : updates)
    processUpdate(u);
  useExtraBounds(min_x, min_y, max_x, max_y);
  if (!map_received_)
  {
    // costmap_2d waits for the map, saying so; here the costmap runs without it, so say it every
    // throttle period once the start-up grace is over (a latched map comes moments after start): a
    // costmap with no static map is all free (or all unknown) where walls are.
    if (startup_grace_.over(context_->nowNs()))
      context_->report(Severity::Warn, "waiting",
                       name_ + ": waiting for the map on " + config_.map_topic +
                           " (nothing received yet): the costmap has no walls from the map");
    return;
  }
  if (config_.footprint_clearing_enabled)
  {
    // Where the footprint was (drawn as the map again) and where it is (drawn free).
    for (const auto& p : footprint_)
      touch(p.x(), p.y(), min_x, min_y, max_x, max_y);
    footprint_ = transformFootprint(robot_x, robot_y, robot_yaw, getFootprint());
    for (const auto& p : footprint_)
      touch(p.x(), p.y(), min_x, min_y, max_x, max_y);
  }

  if (!layered_costmap_->isRolling())
  {
    if (!dirty_) return;
    // Centres of the first and last dirty cells.
    double wx, wy;
    costmap_.mapToWorld(dirty_x0_, dirty_y0_, wx, wy);
    touch(wx, wy, min_x, min_y, max_x, max_y);
    costmap_.mapToWorld(dirty_x1_ - 1, dirty_y1_ - 1, wx, wy);
    touch(wx, wy, min_x, min_y, max_x, max_y);
    dirty_ = false;
    return;
  }
  // Rolling: the window moves, so the map's whole extent (in the costmap's frame) is asked for every
  // cycle, as costmap_2d does.
  dirty_ = false;
  const std::string& global = context_->globalFrame();
  Transform2D from_map;
  if (!map_frame_.empty() && map_frame_ != global)
  {
    std::string error;
    const auto t = context_->lookupTransform(global, map_frame_, &error);
    if (!t)
    {
      context_->report(Severity::Error, "transform",
                       name_ + ": no transform from " + map_frame_ + " to " + global + ": " + error);
      return;
    }
    from_map = *t;
  }
  const double w = costmap_.getSizeInMetersX(), h = costmap_.getSizeInMetersY();
  const double c = std::cos(map_yaw_), s = std::sin(map_yaw_);
  for (const auto& corner : {std::pair<double, double>{0, 0}, {w, 0}, {0, h}, {w, h}})
  {
    const double mx = costmap_.getOriginX() + c * corner.first - s * corner.second;
    const double my = costmap_.getOriginY() + s * corner.first + c * corner.second;
    double gx, gy;
    from_map.apply(mx, my, gx, gy);
    touch(gx, gy, min_x, min_y, max_x, max_y);
  }
}

bool StaticLayer::overwritesWindow(const Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j) const
{
  (void)min_i, (void)min_j, (void)max_i, (void)max_j;  // the copy covers the whole master
  return map_received_ && enabled() && !layered_costmap_->isRolling() && !config_.use_maximum &&
         costmap_.getSizeInCellsX() == master_grid.getSizeInCellsX() &&
         costmap_.getSizeInCellsY() == master_grid.getSizeInCellsY();
}

void StaticLayer::updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j)
{
  if (!map_received_) return;
  if (!layered_costmap_->isRolling())
  {
    // The own grid lies on the master (the map's yaw is ignored here, as costmap_2d does).
    clearFootprintCells(ownPlacement(0.0), Transform2D{});
    if (config_.use_maximum)
      updateWithMax(master_grid, min_i, min_j, max_i, max_j);
    else
      updateWithTrueOverwrite(master_grid, min_i, min_j, max_i, max_j);
    restoreFootprintCells();
    return;
  }
  min_i = std::max(min_i, 0);
  min_j = std::max(min_j, 0);
  max_i = std::min(max_i, static_cast<int>(master_grid.getSizeInCellsX()));
  max_j = std::min(max_j, static_cast<int>(master_grid.getSizeInCellsY()));
  if (min_i >= max_i || min_j >= max_j) return;

  // Master cell centre -> costmap frame -> map frame -> map cell: the filters' sampler.
  const std::string& global = context_->globalFrame();
  Transform2D to_map;
  if (!map_frame_.empty() && map_frame_ != global)
  {
    std::string error;
    const auto t = context_->lookupTransform(map_frame_, global, &error);
    if (!t)
    {
      context_->report(Severity::Error, "transform",
                       name_ + ": no transform from " + global + " to " + map_frame_ + ": " + error);
      return;
    }
    to_map = *t;
  }
  const GridPlacement map = ownPlacement(map_yaw_);
  sampler_.build(master_grid, CellWindow{min_i, min_j, max_i, max_j}, map, to_map);
  clearFootprintCells(map, to_map);
  if (config_.use_maximum)
    sampler_.forEach(master_grid, costmap_.data(), map.width, map.height,
                     [](uint8_t& cell, uint8_t v) { cell = std::max(cell, v); });
  else
    sampler_.forEach(master_grid, costmap_.data(), map.width, map.height, [](uint8_t& cell, uint8_t v) { cell = v; });
  restoreFootprintCells();
}

GridPlacement StaticLayer::ownPlacement(double yaw) const
{
  return {costmap_.getSizeInCellsX(), costmap_.getSizeInCellsY(), costmap_.getResolution(),
          costmap_.getOriginX(),      costmap_.getOriginY(),      yaw};
}

void StaticLayer::clearFootprintCells(const GridPlacement& own, const Transform2D& to_map)
{
  cleared_.clear();
  if (!config_.footprint_clearing_enabled || footprint_.size() < 3) return;
  std::vector<MapLocation> polygon;
  polygon.reserve(footprint_.size());
  for (const auto& p : footprint_)
  {
    std::size_t index;
    if (!gridCellAt(own, to_map, p.x(), p.y(), index)) return;
    MapLocation cell;
    costmap_.indexToCells(static_cast<unsigned int>(index), cell.x, cell.y);
    polygon.push_back(cell);
  }
  footprint_cells_.clear();
  costmap_.convexFillCells(polygon, footprint_cells_);
  uint8_t* grid = costmap_.data();
  for (const auto& c : footprint_cells_)
  {
    const std::size_t k = costmap_.getIndex(c.x, c.y);
    cleared_.emplace_back(k, grid[k]);
    grid[k] = FREE_SPACE;
  }
}

void StaticLayer::restoreFootprintCells()
{
  if (config_.restore_cleared_footprint)
  {
    uint8_t* grid = costmap_.data();
    for (const auto& [k, cost] : cleared_)
      grid[k] = cost;
  }
  cleared_.clear();
}
}  // namespace costmap_layers

namespace costmap_layers
{
LayerStatus StaticLayer::status() const
{
  LayerStatus s = Layer::status();
  s.message.clear();
  s.level = StatusLevel::Ok;
  const uint64_t now = context_ ? context_->nowNs() : 0;
  std::lock_guard<std::mutex> lock(mutex_);
  s.add("map topic", config_.map_topic);
  s.add("maps accepted", std::to_string(maps_accepted_));
  s.add("maps rejected", std::to_string(maps_rejected_));
  s.add("last map accepted", accepted_any_ ? describeAge(secondsBetween(map_received_ns_, now)) : "never");
  if (config_.subscribe_to_updates)
  {
    s.add("updates accepted", std::to_string(updates_accepted_));
    s.add("updates rejected", std::to_string(updates_rejected_));
  }
  if (maps_rejected_ > 0) s.add("last rejection", last_rejection_);
  if (map_received_)
  {
    s.add("map size [cells]", std::to_string(latest_width_) + " x " + std::to_string(latest_height_));
    s.add("map frame", map_frame_);
  }
  if (!accepted_any_)
  {
    s.raise(StatusLevel::Error, "no map yet on " + config_.map_topic +
                                    (maps_rejected_ > 0 ? " (every map so far rejected: " + last_rejection_ + ")"
                                                        : ": the static layer draws nothing until one arrives"));
    return s;
  }
  if (latest_rejected_)
    s.raise(StatusLevel::Warn, "the latest map on " + config_.map_topic + " was rejected (" + last_rejection_ +
                                   "); the previous one stays in force");
  else if (!map_received_)
    s.message = "map received on " + config_.map_topic + ", drawn at the next update";
  else
    s.message = "map " + std::to_string(latest_width_) + " x " + std::to_string(latest_height_) + " cells from " +
                config_.map_topic + " in force";
  if (!enabled()) s.message = "disabled; " + s.message;
  return s;
}
}  // namespace costmap_layers
#endif  // HWY_ONCE
