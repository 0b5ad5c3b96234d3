#include "costmap_layers/core/filters/costmap_filter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "costmap_layers/core/config/input_error.hpp"
#include "costmap_layers/core/config/param_reader.hpp"
#include "costmap_layers/core/rules/stamp_order.hpp"

namespace costmap_layers
{
InputError validateGrid(const OccupancyGridData& grid, uint64_t max_cells)
{
  std::ostringstream err;
  std::string field;
  const uint64_t cells = static_cast<uint64_t>(grid.width) * grid.height;
  if (grid.width == 0 || grid.height == 0)
  {
    field = "info.width";
    err << "info.width/info.height must be positive (got " << grid.width << "x" << grid.height << ")";
  }
  else if (cells > max_cells)
  {
    field = "info.cells";
    err << "info.width x info.height = " << grid.width << "x" << grid.height << " exceeds the limit of " << max_cells
        << " cells";
  }
  else if (grid.data.size() != cells)
  {
    field = "data";
    err << "data has " << grid.data.size() << " values, expected info.width x info.height = " << cells;
  }
  else if (!(grid.resolution >= limits::kMinResolution && grid.resolution <= limits::kMaxResolution))
  {
    field = "info.resolution";
    err << "info.resolution must be in [" << limits::kMinResolution << ", " << limits::kMaxResolution
        << "] m/cell (got " << grid.resolution << ")";
  }
  else if (!std::isfinite(grid.origin_x) || !std::isfinite(grid.origin_y) || !std::isfinite(grid.origin_yaw))
  {
    field = "info.origin";
    err << "info.origin must be finite (got x=" << grid.origin_x << " y=" << grid.origin_y << " yaw=" << grid.origin_yaw
        << ")";
  }
  else if (std::fabs(grid.origin_x) > limits::kMaxCoordinate || std::fabs(grid.origin_y) > limits::kMaxCoordinate)
  {
    field = "info.origin";
    err << "info.origin is absurdly far away: |x| and |y| must be at most " << limits::kMaxCoordinate
        << " m (got x=" << grid.origin_x << " y=" << grid.origin_y << ")";
  }
  else if (std::fabs(grid.origin_yaw) > limits::kMaxYaw)
  {
    field = "info.origin.orientation";
    err << "info.origin yaw must be within +-" << limits::kMaxYaw << " rad (got " << grid.origin_yaw << ")";
  }
  return InputError::of(field, err.str());
}

InputError validateGridUpdate(int64_t x, int64_t y, uint32_t width, uint32_t height, std::size_t data_size,
                              uint32_t grid_width, uint32_t grid_height)
{
  std::ostringstream err;
  std::string field;
  if (x < 0 || y < 0)
  {
    field = "x";
    err << "x/y must not be negative (got x=" << x << " y=" << y << ")";
  }
  else if (static_cast<uint64_t>(data_size) != static_cast<uint64_t>(width) * height)
  {
    field = "data";
    err << "data has " << data_size << " values, expected width x height = " << width << "x" << height;
  }
  else if (static_cast<uint64_t>(x) + width > grid_width || static_cast<uint64_t>(y) + height > grid_height)
  {
    field = "width";
    err << "rectangle x=" << x << " y=" << y << " " << width << "x" << height << " leaves the " << grid_width << "x"
        << grid_height << " grid";
  }
  return InputError::of(field, err.str());
}

void CostmapFilter::onInitialize()
{
  ParamReader params(context_->params(), name_);
  filter_info_topic_ = params.getTopic("filter_info_topic", "", true);
  if (usesFilterInfo() && params.has("mask_topic"))
    params.fail("filter_info_topic",
                "is set together with 'mask_topic' (" + params.raw("mask_topic")->toString() +
                    "): set one of them: filter_info_topic (Nav2's form) takes the mask topic from the filter info "
                    "(costmap_filter_info_server), mask_topic names the mask directly");
  if (!usesFilterInfo()) mask_topic_ = params.getTopic("mask_topic", defaultMaskTopic(), true);
  onInitializeFilter(params);
  mask_port_ = inputs().size();
  addInput(maskPort(mask_topic_, 0));
  info_port_ = inputs().size();
  if (usesFilterInfo())
    addInput(InputPort::filterInfo(filter_info_topic_,
                                   [this](const std::shared_ptr<const FilterInfoData>& info) { setFilterInfo(info); }));
  // Switched off from the start: the outputs say "no effect" once (the host never calls the filter).
  if (!enabled()) processInactive();
}

InputPort CostmapFilter::maskPort(const std::string& topic, uint64_t generation)
{
  return InputPort::grid(InputKind::Mask, topic,
                         [this, generation](const std::shared_ptr<const OccupancyGridData>& mask)
                         { setMaskOf(generation, mask); });
}

std::string CostmapFilter::maskTopic() const
{
  std::lock_guard<std::mutex> lock(mask_mutex_);
  return mask_topic_;
}

std::shared_ptr<const FilterInfoData> CostmapFilter::getFilterInfo() const
{
  std::lock_guard<std::mutex> lock(mask_mutex_);
  return info_;
}

std::string CostmapFilter::setFilterInfo(std::shared_ptr<const FilterInfoData> info)
{
  std::lock_guard<std::mutex> serial(info_mutex_);
  {
    // Nav2 has no subscription then; deactivate() and activate() change this under info_mutex_ too.
    std::lock_guard<std::mutex> lock(mask_mutex_);
    if (deactivated_) return "the filter is deactivated: filter info ignored";
  }
  const InputError error = info ? checkFilterInfoFor(filterFamily(), *info) : InputError::of("data", "no filter info");
  if (!error.ok())
  {
    const bool had = getFilterInfo() != nullptr;
    context_->report(Severity::Error, "filter_info/" + error.field,
                     name_ + ": filter info on " + filter_info_topic_ + " ignored" +
                         (had ? ", the previous one stays in force" : "") + ": " + error.message);
    return error.message;
  }
  std::string old_topic;
  bool moved = false;
  uint64_t generation = 0;
  {
    std::lock_guard<std::mutex> lock(mask_mutex_);
    old_topic = mask_topic_;
    info_ = info;
    if (!mask_changed_) pending_old_ = mask_;
    mask_changed_ = true;  // the mask's meaning may have changed: redraw its extent
    if (info->filter_mask_topic != mask_topic_)
    {
      moved = true;
      generation = ++mask_generation_;
      mask_ = nullptr;  // from the old topic: not what this info describes
      mask_topic_ = info->filter_mask_topic;
    }
  }
  std::ostringstream text;
  text << name_ << ": filter info from " << filter_info_topic_ << ": type " << static_cast<int>(info->type) << " ("
       << filterInfoTypeName(info->type) << "), mask on " << info->filter_mask_topic << ", value = " << info->base
       << " + " << info->multiplier << " * mask value";
  if (moved && !old_topic.empty()) text << "; the mask topic was " << old_topic << ": its mask is dropped";
  context_->report(Severity::Info, "filter_info", text.str());
  if (filterFamily() == FilterFamily::Keepout &&
      (info->base != filter_info::kBaseDefault || info->multiplier != filter_info::kMultiplierDefault))
  {
    std::ostringstream warn;
    warn << name_ << ": filter info on " << filter_info_topic_ << " has base " << info->base << " and multiplier "
         << info->multiplier << ": this filter reads mask values as they are and ignores both (Nav2's keepout filter "
         << "expects 0 and 1)";
    context_->report(Severity::Warn, "filter_info/base", warn.str());
  }
  onFilterInfo(*info);
  if (moved) replaceInput(mask_port_, maskPort(info->filter_mask_topic, generation));
  return {};
}

void CostmapFilter::deactivate()
{
  std::lock_guard<std::mutex> lifecycle(lifecycle_mutex_);
  uint64_t generation;
  {
    // After an info being applied (which may move the mask port), so that what follows is final.
    std::lock_guard<std::mutex> serial(info_mutex_);
    std::lock_guard<std::mutex> lock(mask_mutex_);
    if (deactivated_) return;
    deactivated_ = true;
    generation = ++mask_generation_;  // masks still on their way from the subscription are stale
    if (!mask_changed_) pending_old_ = mask_;
    mask_changed_ = true;  // the dropped mask's extent is redrawn without it
    mask_ = nullptr;
    latest_rejected_ = false;
    if (usesFilterInfo())
    {
      info_ = nullptr;
      mask_topic_.clear();  // the next info names it
    }
  }
  {
    std::lock_guard<std::mutex> lock(outputs_mutex_);
    processInactive();
  }
  // The host ends the subscriptions (a port without a topic is not subscribed). Not under info_mutex_:
  // an info callback waiting for it would keep the host's unsubscribing waiting for that callback.
  replaceInput(mask_port_, maskPort("", generation));
  if (usesFilterInfo())
    replaceInput(info_port_, InputPort::filterInfo("", [this](const std::shared_ptr<const FilterInfoData>& info)
                                                   { setFilterInfo(info); }));
}

void CostmapFilter::activate()
{
  std::lock_guard<std::mutex> lifecycle(lifecycle_mutex_);
  uint64_t generation;
  std::string topic;
  {
    std::lock_guard<std::mutex> serial(info_mutex_);
    std::lock_guard<std::mutex> lock(mask_mutex_);
    if (!deactivated_) return;
    deactivated_ = false;
    restart_grace_ = true;  // a latched mask or info comes moments after the subscription, as at start
    generation = ++mask_generation_;
    topic = mask_topic_;
  }
  // A new subscription: the host delivers what is latched on the topic again. In the filter_info_topic
  // form the info then names the mask topic (setFilterInfo() subscribes it).
  if (usesFilterInfo())
    replaceInput(info_port_,
                 InputPort::filterInfo(filter_info_topic_, [this](const std::shared_ptr<const FilterInfoData>& info)
                                       { setFilterInfo(info); }));
  else
    replaceInput(mask_port_, maskPort(topic, generation));
}

bool CostmapFilter::isActive() const
{
  std::lock_guard<std::mutex> lock(mask_mutex_);
  return mask_ && (!usesFilterInfo() || info_);
}

void CostmapFilter::onEnabledChanged(bool on)
{
  {
    std::lock_guard<std::mutex> lock(mask_mutex_);
    // The mask drawn so far must be redrawn even if another one replaces it before the next update.
    if (!mask_changed_) pending_old_ = mask_;
    mask_changed_ = true;  // the mask's extent must be redrawn
  }
  // Switched off: the outputs say "no effect" now, since the host calls a disabled filter no more.
  if (!on)
  {
    std::lock_guard<std::mutex> lock(outputs_mutex_);
    processInactive();
  }
}

std::string CostmapFilter::setMask(std::shared_ptr<const OccupancyGridData> mask)
{
  uint64_t generation;
  {
    std::lock_guard<std::mutex> lock(mask_mutex_);
    generation = mask_generation_;
  }
  return setMaskOf(generation, std::move(mask));
}

std::string CostmapFilter::setMaskOf(uint64_t generation, std::shared_ptr<const OccupancyGridData> mask)
{
  static const char* const kStale = "the mask came from a topic no longer in force";
  static const char* const kDeactivated = "the filter is deactivated: mask ignored";
  {
    // From a topic the filter info has moved away from (delivered while the host re-subscribed), or
    // from a subscription that a deactivation ended: neither used nor judged.
    std::lock_guard<std::mutex> lock(mask_mutex_);
    if (deactivated_) return kDeactivated;
    if (generation != mask_generation_) return kStale;
  }
  InputError error = mask ? validateGrid(*mask) : InputError::of("data", "no mask");
  std::string topic;
  if (error.ok())
  {
    const uint64_t now = context_ ? context_->nowNs() : UINT64_MAX;
    std::lock_guard<std::mutex> lock(mask_mutex_);
    if (deactivated_) return kDeactivated;
    if (generation != mask_generation_) return kStale;  // the info moved on while this mask was checked
    if (!mask_ || !isOutOfOrder(mask->stamp_ns, mask_->stamp_ns, now))
    {
      if (mask->origin_yaw != 0.0 && context_ && layered_costmap_ && !layered_costmap_->isRolling())
      {
        // The static layer (as costmap_2d's and Nav2's) ignores its map's origin yaw in a costmap that
        // is not rolling, and Nav2's filters ignore a mask's: a mask drawn on the map's image lands
        // rotated against the walls here.
        std::ostringstream what;
        what << name_ << ": mask on " << mask_topic_ << " is drawn rotated by its origin yaw " << mask->origin_yaw
             << " rad; the static layer ignores its map's yaw in a costmap that is not rolling (as costmap_2d and "
                "Nav2 do, whose filters ignore a mask's yaw too): a mask made on the map's image will not lie on "
                "its walls";
        context_->report(Severity::Warn, "mask/info.origin.orientation", what.str());
      }
      if (!mask_changed_) pending_old_ = mask_;
      mask_ = std::move(mask);
      mask_changed_ = true;
      ++masks_accepted_;
      mask_received_ns_ = now;
      latest_rejected_ = false;
      return {};
    }
    error = InputError::of("header.stamp", outOfOrderError(mask->stamp_ns, mask_->stamp_ns, "mask"));
    topic = mask_topic_;
  }
  else
    topic = maskTopic();
  {
    std::lock_guard<std::mutex> lock(mask_mutex_);
    ++masks_rejected_;
    last_rejection_ = error.message;
    latest_rejected_ = true;
  }
  if (context_)
    context_->report(Severity::Error, "mask/" + error.field,
                     name_ + ": mask on " + topic + " rejected, keeping the previous one: " + error.message);
  return error.message;
}

std::shared_ptr<const OccupancyGridData> CostmapFilter::getMask() const
{
  std::lock_guard<std::mutex> lock(mask_mutex_);
  return mask_;
}

bool CostmapFilter::maskBoundsInGlobal(const OccupancyGridData& mask, const std::optional<Transform2D>& to_mask,
                                       double& x0, double& y0, double& x1, double& y1)
{
  const std::string& global = context_->globalFrame();
  Transform2D from_mask;  // mask frame -> global frame
  if (to_mask)
    from_mask = to_mask->inverse();
  else if (!mask.frame_id.empty() && mask.frame_id != global)
  {
    std::string error;
    const auto t = context_->lookupTransform(global, mask.frame_id, &error);
    if (!t) return false;
    from_mask = *t;
  }
  const double w = mask.width * mask.resolution, h = mask.height * mask.resolution;
  const double cm = std::cos(mask.origin_yaw), sm = std::sin(mask.origin_yaw);
  x0 = y0 = std::numeric_limits<double>::max();
  x1 = y1 = std::numeric_limits<double>::lowest();
  for (const auto& c : {std::pair<double, double>{0, 0}, {w, 0}, {0, h}, {w, h}})
  {
    const double mx = mask.origin_x + cm * c.first - sm * c.second;
    const double my = mask.origin_y + sm * c.first + cm * c.second;
    double gx, gy;
    from_mask.apply(mx, my, gx, gy);
    x0 = std::min(x0, gx);
    y0 = std::min(y0, gy);
    x1 = std::max(x1, gx);
    y1 = std::max(y1, gy);
  }
  return true;
}

void CostmapFilter::updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y,
                                 double* max_x, double* max_y)
{
  robot_x_ = robot_x;
  robot_y_ = robot_y;
  robot_yaw_ = robot_yaw;
  std::shared_ptr<const OccupancyGridData> old;
  bool changed = false;
  std::string mask_topic;
  bool deactivated;
  {
    std::lock_guard<std::mutex> lock(mask_mutex_);
    if (restart_grace_) startup_grace_ = StartupGrace{};  // activated: waiting starts again
    restart_grace_ = false;
    deactivated = deactivated_;
    active_info_ = info_;
    // In the filter_info_topic form a mask means nothing until an info says how to read it.
    active_mask_ = usesFilterInfo() && !info_ ? nullptr : mask_;
    changed = mask_changed_;
    mask_changed_ = false;
    old = std::move(pending_old_);
    mask_topic = mask_topic_;
  }
  if (changed && active_mask_ && drawsCosts() && layered_costmap_)
  {
    // Each costmap cell takes the mask value at its centre (as in Nav2): of a finer mask, a line
    // thinner than a costmap cell may fall between the centres and vanish.
    const Costmap2D& master = layered_costmap_->getCostmap();
    const double costmap_resolution = master.getResolution();
    if (master.cellCount() > 0 && active_mask_->resolution < costmap_resolution * (1.0 - 1e-9))
    {
      std::ostringstream what;
      what << name_ << ": mask on " << mask_topic << " at " << active_mask_->resolution
           << " m/cell is finer than the costmap's " << costmap_resolution
           << " m/cell: each costmap cell takes the mask value at its centre (as in Nav2), so a line thinner than "
           << costmap_resolution << " m (a one-pixel fence, a zone_server outline) may not appear";
      context_->report(Severity::Warn, "mask/info.resolution", what.str());
    }
  }
  have_transform_ = false;
  if (active_mask_)
  {
    // One transform lookup per cycle, used by processPose() now and by process() in updateCosts().
    const std::string& global = context_->globalFrame();
    to_mask_ = Transform2D{};
    have_transform_ = true;
    if (!active_mask_->frame_id.empty() && active_mask_->frame_id != global)
    {
      std::string error;
      const auto t = context_->lookupTransform(active_mask_->frame_id, global, &error);
      have_transform_ = t.has_value();
      transform_error_ = t ? std::string() : error;
      if (t)
        to_mask_ = *t;
      else
        context_->report(Severity::Error, "transform",
                         name_ + ": no transform from " + global + " to mask frame " +
                             shownText(active_mask_->frame_id) +
                             ", filter skipped this update: " + shownText(error, 400));
    }
  }
  {
    // A switch that flips while this cycle runs (its host asked enabled() before) is settled here:
    // whichever of this and onEnabledChanged() comes last leaves its outputs in force.
    std::lock_guard<std::mutex> lock(outputs_mutex_);
    if (!active_mask_ || !enabled())
      processInactive();
    else if (have_transform_)
      processPose(*active_mask_, to_mask_, robot_x, robot_y, robot_yaw);
  }
  // Said every cycle (the host's log throttles) once the start-up grace is over: a latched mask or
  // info comes moments after start.
  if (!active_mask_ && enabled() && !deactivated && startup_grace_.over(context_->nowNs()))
  {
    if (usesFilterInfo() && !active_info_)
      context_->report(Severity::Warn, "waiting",
                       name_ + ": waiting for filter info on " + filter_info_topic_ +
                           " (from costmap_filter_info_server): the filter does nothing until one arrives");
    else
      context_->report(Severity::Warn, "waiting",
                       name_ + ": no mask yet on " + mask_topic +
                           (usesFilterInfo() ? " (named by the filter info on " + filter_info_topic_ + ")" : "") +
                           ": the filter does nothing until one arrives");
  }
  changed = changed || redraw_requested_;
  redraw_requested_ = false;
  // A filter that writes no cost (SpeedFilter) asks for no redraw.
  if (drawsCosts()) requestMaskExtent(changed, old, min_x, min_y, max_x, max_y);
}

void CostmapFilter::requestMaskExtent(bool changed, const std::shared_ptr<const OccupancyGridData>& old, double* min_x,
                                      double* min_y, double* max_x, double* max_y)
{
  auto add = [&](const OccupancyGridData& mask, const std::optional<Transform2D>& to_mask)
  {
    double x0, y0, x1, y1;
    if (!maskBoundsInGlobal(mask, to_mask, x0, y0, x1, y1))
    {
      // Extent unknown without the transform: redraw everything rather than leave stale costs.
      x0 = y0 = -std::numeric_limits<float>::max();
      x1 = y1 = std::numeric_limits<float>::max();
    }
    // The new value first: NaN bounds from an earlier layer give way to the extent instead of
    // cancelling the redraw (std::min returns its first argument when a comparison with NaN fails).
    *min_x = std::min(x0, *min_x);
    *min_y = std::min(y0, *min_y);
    *max_x = std::max(x1, *max_x);
    *max_y = std::max(y1, *max_y);
  };
  // Where the mask in force was drawn (nullopt: nowhere yet). A replaced mask is cleared where it was
  // drawn, not where the transform of this cycle would put it.
  const std::optional<Transform2D> drawn_with = drawn_with_;
  if (old) add(*old, drawn_with);
  if (changed) drawn_with_.reset();
  if (!active_mask_ || !enabled())
  {
    if (changed && active_mask_) add(*active_mask_, drawn_with);  // switched off: its costs go
    drawn_with_.reset();
    draw_incomplete_ = false;
    return;
  }
  if (!have_transform_)
  {
    // Nothing can be drawn: whatever the other layers redraw this cycle lacks the mask, so the whole
    // extent is drawn again once the transform is back (without it, a mask that came before its frame's
    // transform was never drawn, and a tf gap left a lasting hole in a keepout zone).
    draw_incomplete_ = true;
    if (changed) add(*active_mask_, std::nullopt);
    return;
  }
  // A transform that changed since the drawing (a non-rolling costmap in another frame than the mask:
  // localisation moves map -> odom) moves the mask: drawn anew there, cleared at the old place.
  constexpr double kSameTransform = 1e-9;  // [m], [rad]: tf's repeated answers for an unchanged transform
  const bool moved = drawn_with && (std::abs(drawn_with->x - to_mask_.x) > kSameTransform ||
                                    std::abs(drawn_with->y - to_mask_.y) > kSameTransform ||
                                    std::abs(drawn_with->yaw - to_mask_.yaw) > kSameTransform);
  // A rolling window moves onto cells nobody else may ask for: the extent every cycle (the costmap clips
  // it to the window), as costmap_2d's static layer does when rolling.
  if (!changed && drawn_with_ && !draw_incomplete_ && !moved && !layered_costmap_->isRolling()) return;
  add(*active_mask_, to_mask_);
  if (moved) add(*active_mask_, drawn_with);
  drawn_with_ = to_mask_;
  draw_incomplete_ = false;
}

void CostmapFilter::updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j)
{
  if (!active_mask_ || !have_transform_) return;
  CellWindow window{std::max(min_i, 0), std::max(min_j, 0),
                    std::min(max_i, static_cast<int>(master_grid.getSizeInCellsX())),
                    std::min(max_j, static_cast<int>(master_grid.getSizeInCellsY()))};
  if (window.empty()) return;
  mapping_.build(master_grid, window, *active_mask_, to_mask_);
  process(master_grid, window, *active_mask_, mapping_, robot_x_, robot_y_, robot_yaw_);
}

std::optional<int8_t> CostmapFilter::maskValueAt(const OccupancyGridData& mask, const Transform2D& to_mask, double wx,
                                                 double wy)
{
  std::size_t k;
  if (!gridCellAt(GridPlacement::of(mask), to_mask, wx, wy, k)) return std::nullopt;
  return mask.data[k];
}
}  // namespace costmap_layers

namespace costmap_layers
{
LayerStatus CostmapFilter::status() const
{
  LayerStatus s;
  const uint64_t now = context_ ? context_->nowNs() : 0;
  std::lock_guard<std::mutex> lock(mask_mutex_);
  s.add("enabled", enabled() ? "true" : "false");
  s.add("mask topic", mask_topic_);
  s.add("masks accepted", std::to_string(masks_accepted_));
  s.add("masks rejected", std::to_string(masks_rejected_));
  s.add("last mask accepted", mask_ ? describeAge(secondsBetween(mask_received_ns_, now)) : "never");
  if (masks_rejected_ > 0) s.add("last rejection", last_rejection_);
  if (mask_)
  {
    s.add("mask size [cells]", std::to_string(mask_->width) + " x " + std::to_string(mask_->height));
    s.add("mask frame", mask_->frame_id);
  }
  if (deactivated_)
  {
    s.message = "deactivated: no mask or filter info until activated";
    return s;
  }
  if (!enabled())
  {
    s.message = "switched off";
    return s;
  }
  if (!mask_)
  {
    s.raise(StatusLevel::Warn, "no mask yet on " + mask_topic_ +
                                   (masks_rejected_ > 0 ? " (every mask so far rejected: " + last_rejection_ + ")"
                                                        : ": the filter does nothing until one arrives"));
    return s;
  }
  if (latest_rejected_)
    s.raise(StatusLevel::Warn, "the latest mask on " + mask_topic_ + " was rejected (" + last_rejection_ +
                                   "); the previous one stays in force");
  if (active_mask_ && !have_transform_)
    s.raise(StatusLevel::Warn, "cannot place the mask: no transform into " + shownText(active_mask_->frame_id) + " (" +
                                   shownText(transform_error_, 400) + ")");
  if (s.level == StatusLevel::Ok)
    s.message = active_mask_ ? "mask from " + mask_topic_ + " in force" : "mask received, applied at the next update";
  return s;
}
}  // namespace costmap_layers
