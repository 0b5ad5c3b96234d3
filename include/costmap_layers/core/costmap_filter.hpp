// The base of costmap filters (Nav2's design): the base owns the mask, its frame transform and the
// robot pose; a subclass only says what a mask value means, in process(). A new mask replaces the old
// one atomically, and the next update covers the union of the old and new mask extents.
//
// Where the mask comes from, one of two forms (setting both is a start-up error naming both):
//  - `mask_topic`: the mask is read from that topic (default: the filter's defaultMaskTopic()).
//  - `filter_info_topic` (Nav2's form): the filter reads a filter info (CostmapFilterInfo, as
//    published by costmap_filter_info_server) there, and reads the mask from the topic the info names,
//    with the info's type, base and multiplier (filter_info.hpp says which types a filter takes).
//    Until an info arrives the filter does nothing and says so (a throttled "waiting" warning); an
//    info the filter cannot use is reported (an Error keyed "filter_info/<field>") and ignored, the
//    previous info staying in force. A later info naming another mask topic moves the subscription:
//    the mask from the old topic is dropped (it is not what the new info describes) and the filter
//    waits for a mask on the new one; masks still arriving from the old topic are ignored. An info
//    naming the same topic keeps the mask and changes only how it is read.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "costmap_layers/core/costmap_2d.hpp"
#include "costmap_layers/core/filter_info.hpp"
#include "costmap_layers/core/input_error.hpp"
#include "costmap_layers/core/layer.hpp"
#include "costmap_layers/core/layered_costmap.hpp"
#include "costmap_layers/core/limits.hpp"

namespace costmap_layers
{
class ParamReader;

/// Checks a mask or map: data size, dimensions (at most max_cells), resolution in
/// [limits::kMinResolution, limits::kMaxResolution], origin x/y within limits::kMaxCoordinate and yaw
/// within limits::kMaxYaw (see limits.hpp for why).
/// @return ok() when valid, else the field at fault and one line naming it and its value.
InputError validateGrid(const OccupancyGridData& grid, uint64_t max_cells = limits::kMaxGridCells);

/// Checks a partial update (x, y, width x height, data_size values) against a grid of
/// grid_width x grid_height cells, in arithmetic that cannot overflow or wrap for any field values.
/// @return ok() when it fits, else the field at fault and one line naming it and its value.
InputError validateGridUpdate(int64_t x, int64_t y, uint32_t width, uint32_t height, std::size_t data_size,
                              uint32_t grid_width, uint32_t grid_height);

/// How master cells of one update window map to cells of the mask: per master column a mask column
/// (or -1 outside) and per master row a mask row, when the mask is axis-aligned with the costmap;
/// otherwise a per-cell affine map. Built once per update, never per cell.
class MaskMapping
{
public:
  /// @param to_mask  transform from the costmap's global frame into the mask's frame
  void build(const Costmap2D& master, const CellWindow& window, const OccupancyGridData& mask,
             const Transform2D& to_mask);

  /// Calls fn(master_cell, mask_value) for every cell of the window that lies on the mask.
  template <class Fn>
  void forEach(Costmap2D& master, const OccupancyGridData& mask, Fn&& fn) const;

  /// Row-wise form for fast kernels. `source` holds one value per mask cell (mask-sized, row-major).
  /// For each window row that meets the mask, calls fn(master_cells, values, n): values[k] belongs to
  /// master_cells[k]. Mask cells are read in place when the mapping is an offset; otherwise they are
  /// gathered into scratch (reused when consecutive rows share a mask row), with `neutral` for cells
  /// that fall outside the mask.
  template <class T, class RowFn>
  void forEachRow(Costmap2D& master, const T* source, uint32_t source_width, uint32_t source_height, T neutral,
                  std::vector<T>& scratch, RowFn&& fn) const;

  /// True when rows and columns map independently (no rotation between costmap and mask).
  bool axisAligned() const { return axis_aligned_; }
  /// True when, in addition, one master cell is one mask cell (an offset).
  bool isOffset() const { return offset_; }
  /// Window columns per block of forEachRow's byte gather (16 or 8; one byte shuffle per block), or 0
  /// when byte masks are gathered cell by cell (offset, rotated, or no block fits the resolution ratio).
  int byteGatherBlock() const { return offset_ || !axis_aligned_ ? 0 : chunk_width_; }

private:
  /// Gathers the on-mask columns of one window row from a byte mask row through the shuffle plan (a
  /// Highway kernel in costmap_filter.cpp).
  void shuffleRow(const uint8_t* mask_row, uint8_t* out) const;

  CellWindow window_;
  bool axis_aligned_ = true;
  bool offset_ = false;
  int offset_x_ = 0, offset_y_ = 0;  ///< mask cell = master cell + offset, when isOffset()
  std::vector<int32_t> cols_;        ///< mask column per window column, -1 outside
  std::vector<int32_t> rows_;        ///< mask row per window row, -1 outside
  // Axis-aligned, not an offset: the window columns on the mask are [cols_lo_, cols_hi_) (one run, as
  // the map is linear) when cols_contiguous_; the byte gather then runs through a shuffle plan built
  // once per update (chunk_width_ 16 or 8 columns per chunk, 0 when no plan fits the mapping).
  int cols_lo_ = 0, cols_hi_ = 0;
  bool cols_contiguous_ = false;
  int chunk_width_ = 0;
  /// The blocks of the byte gather, two numbers each: chunk_width_ window columns starting at window
  /// column pos take bytes src + shuffle[0..chunk_width_) of the mask row (shuffle indices 0..15, so
  /// one 16-byte load per block).
  std::vector<int32_t> chunks_;
  std::vector<uint8_t> chunk_shuffle_;  ///< 16 indices per chunk (0x80 past chunk_width_)
  // General case: mask-grid coordinates [cells] of master cell (i, j) = p0 + i * du + j * dv.
  double p0x_ = 0, p0y_ = 0, dux_ = 0, duy_ = 0, dvx_ = 0, dvy_ = 0;
};

class CostmapFilter : public Layer
{
public:
  /// Takes the newest mask, looks up the transform (global -> mask frame) once for the cycle and calls
  /// processPose(); grows the bounds by the old and new mask extents when the mask changed (and the
  /// filter drawsCosts()).
  void updateBounds(double robot_x, double robot_y, double robot_yaw, double* min_x, double* min_y, double* max_x,
                    double* max_y) override;
  /// Calls process(); skips (writing nothing) when disabled, without a mask, or without a transform.
  void updateCosts(Costmap2D& master_grid, int min_i, int min_j, int max_i, int max_j) final;
  bool isClearable() override { return false; }
  /// The filter's one switch, set by `enabled` (at start and at run time) and by the ~<name>/toggle
  /// service alike: it is setFilterEnabled(). The filter keeps taking part in updates (enabled() stays
  /// true), so that switching it off clears its cells at the next update.
  void setEnabled(bool on) final;

  /// Replaces the mask, unless it is invalid or stamped before the mask in force (isOutOfOrder()): then
  /// the previous mask stays, and the reason is reported (an Error keyed by the field) and returned.
  /// Safe to call from another thread than the update loop.
  /// @return an empty string when accepted, else the error.
  std::string setMask(std::shared_ptr<const OccupancyGridData> mask);
  /// The mask in force (nullptr before the first one).
  std::shared_ptr<const OccupancyGridData> getMask() const;
  /// The topic the mask is read from: `mask_topic`, or the one the filter info named (empty before
  /// the first info).
  std::string maskTopic() const;

  /// Whether the filter is configured in Nav2's form (`filter_info_topic`).
  bool usesFilterInfo() const { return !filter_info_topic_.empty(); }
  const std::string& filterInfoTopic() const { return filter_info_topic_; }
  /// Installs a filter info (what the filter_info_topic subscription calls), as the file comment says.
  /// Thread-safe; infos are applied one at a time.
  /// @return an empty string when accepted, else the error (also reported).
  std::string setFilterInfo(std::shared_ptr<const FilterInfoData> info);
  /// The filter info in force (nullptr before the first accepted one, and always in the mask_topic form).
  std::shared_ptr<const FilterInfoData> getFilterInfo() const;
  /// Turns the filter on or off at run time (the ~<name>/toggle service); the next update covers the
  /// mask's extent so that the filter's effect appears or disappears at once. Thread-safe.
  void setFilterEnabled(bool on);
  bool filterEnabled() const { return filter_enabled_; }
  /// OK when switched off or when a mask is in force; WARN while no mask has arrived (naming the topic
  /// and the last rejection), when the latest mask was rejected, or when the mask cannot be placed (no
  /// transform into its frame).
  LayerStatus status() const override;

protected:
  /// Reads the base's parameters (mask_topic or filter_info_topic), calls onInitializeFilter(), then
  /// declares the inputs: the mask (with an empty topic in the filter_info_topic form, until an info
  /// names it) and, in that form, the filter info.
  void onInitialize() final;
  /// Which infos this filter takes (checkFilterInfoFor()).
  virtual FilterFamily filterFamily() const { return FilterFamily::Keepout; }
  /// Called once an info was accepted (any thread), for the subclass's own warnings.
  virtual void onFilterInfo(const FilterInfoData& info) { (void)info; }
  virtual void onInitializeFilter(const ParamReader& params) { (void)params; }
  /// The subclass's meaning of the mask. `mapping` maps the window onto `mask`.
  /// robot pose in the global frame [m, rad].
  virtual void process(Costmap2D& master_grid, const CellWindow& window, const OccupancyGridData& mask,
                       const MaskMapping& mapping, double robot_x, double robot_y, double robot_yaw) = 0;
  /// Called every cycle with the mask in force and the transform, even when no cell is updated (what
  /// SpeedFilter needs). robot pose in the global frame [m, rad].
  virtual void processPose(const OccupancyGridData& mask, const Transform2D& to_mask, double robot_x, double robot_y,
                           double robot_yaw)
  {
    (void)mask, (void)to_mask, (void)robot_x, (void)robot_y, (void)robot_yaw;
  }
  /// Called every cycle instead of processPose() while the filter is switched off or has no mask yet
  /// (not when only the transform is missing): SpeedFilter restores its default there.
  virtual void processInactive() {}
  /// Whether the filter writes costs into the master grid. A filter that does not (SpeedFilter) asks for
  /// no redraw when its mask changes or it is switched: the next update's bounds stay what the other
  /// layers ask for.
  virtual bool drawsCosts() const { return true; }
  /// Default topic of the mask, overridable per filter type.
  virtual std::string defaultMaskTopic() const { return "/map_filter"; }
  /// The mask value at a world point (global frame), or nullopt when outside the mask.
  static std::optional<int8_t> maskValueAt(const OccupancyGridData& mask, const Transform2D& to_mask, double wx,
                                           double wy);
  /// The mask of the current cycle (the one process() receives); the pointer changes only when a new
  /// mask was accepted, so subclasses can key derived data on it.
  const std::shared_ptr<const OccupancyGridData>& activeMask() const { return active_mask_; }
  /// The filter info of the current cycle (update thread only; nullptr in the mask_topic form). While
  /// the filter waits for its first info, no mask is active either.
  const std::shared_ptr<const FilterInfoData>& activeInfo() const { return active_info_; }
  /// The transform used by the last update (global frame -> mask frame).
  const Transform2D& lastTransform() const { return to_mask_; }
  /// Asks that this update cover the mask's whole extent, as when a new mask arrived (a subclass whose
  /// costs changed for another reason). Update thread only; call it from processPose().
  void requestRedraw() { redraw_requested_ = true; }

private:
  /// The mask's extent as a box in the global frame [m], when the transform is known.
  bool maskBoundsInGlobal(const OccupancyGridData& mask, double& x0, double& y0, double& x1, double& y1);

  /// setMask() for a mask delivered by the subscription of mask generation `generation`: masks of an
  /// older generation (a topic no longer in force) are ignored.
  std::string setMaskOf(uint64_t generation, std::shared_ptr<const OccupancyGridData> mask);

  std::string filter_info_topic_;  ///< set once in onInitialize()
  std::size_t mask_port_ = 0;      ///< index of the mask input
  std::atomic<bool> filter_enabled_{true};
  std::mutex info_mutex_;  ///< one setFilterInfo() at a time, so that port replacements stay in order
  mutable std::mutex mask_mutex_;
  std::string mask_topic_;                                ///< guarded by mask_mutex_
  uint64_t mask_generation_ = 0;                          ///< guarded by mask_mutex_; +1 per topic change
  std::shared_ptr<const FilterInfoData> info_;            ///< guarded by mask_mutex_
  std::shared_ptr<const OccupancyGridData> mask_;         ///< guarded by mask_mutex_
  std::shared_ptr<const OccupancyGridData> pending_old_;  ///< the mask replaced since the last bounds
  bool mask_changed_ = false;                             ///< guarded by mask_mutex_
  // For status(), guarded by mask_mutex_: what arrived and when (context clock).
  uint64_t masks_accepted_ = 0, masks_rejected_ = 0, mask_received_ns_ = 0;
  std::string last_rejection_;
  bool latest_rejected_ = false;
  std::string transform_error_;  ///< why the last cycle could not place the mask (update thread)
  std::shared_ptr<const OccupancyGridData> active_mask_;  ///< the mask of this cycle (update thread only)
  std::shared_ptr<const FilterInfoData> active_info_;     ///< the info of this cycle (update thread only)
  bool have_transform_ = false;
  bool redraw_requested_ = false;  ///< update thread only (requestRedraw())
  double robot_x_ = 0, robot_y_ = 0, robot_yaw_ = 0;
  Transform2D to_mask_;
  MaskMapping mapping_;
};

template <class T, class RowFn>
void MaskMapping::forEachRow(Costmap2D& master, const T* source, uint32_t source_width, uint32_t source_height,
                             T neutral, std::vector<T>& scratch, RowFn&& fn) const
{
  if (window_.empty()) return;
  const int mask_w = static_cast<int>(source_width);
  const int mask_h = static_cast<int>(source_height);
  const std::size_t n = static_cast<std::size_t>(window_.xn - window_.x0);
  if (!offset_) scratch.resize(n);
  // Axis-aligned gather: the columns off the mask hold `neutral` in every row, written once here.
  bool use_shuffle = false;
  if (!offset_ && axis_aligned_ && cols_contiguous_)
  {
    std::fill(scratch.begin(), scratch.begin() + cols_lo_, neutral);
    std::fill(scratch.begin() + cols_hi_, scratch.end(), neutral);
    if constexpr (std::is_integral_v<T> && sizeof(T) == 1) use_shuffle = chunk_width_ > 0;
  }
  int cached_row = -1;
  for (int j = window_.y0; j < window_.yn; ++j)
  {
    uint8_t* row = master.data() + static_cast<std::size_t>(j) * master.getSizeInCellsX();
    if (offset_)
    {
      const int my = j + offset_y_;
      if (my < 0 || my >= mask_h) continue;
      const int i0 = std::max(window_.x0, -offset_x_);
      const int i1 = std::min(window_.xn, mask_w - offset_x_);
      if (i0 >= i1) continue;
      fn(row + i0, source + static_cast<std::size_t>(my) * mask_w + offset_x_ + i0, static_cast<std::size_t>(i1 - i0));
    }
    else if (axis_aligned_)
    {
      const int my = rows_[static_cast<std::size_t>(j - window_.y0)];
      if (my < 0) continue;
      if (my != cached_row)
      {
        const T* mrow = source + static_cast<std::size_t>(my) * mask_w;
        if (use_shuffle)
        {
          if constexpr (std::is_integral_v<T> && sizeof(T) == 1)
            shuffleRow(reinterpret_cast<const uint8_t*>(mrow), reinterpret_cast<uint8_t*>(scratch.data()));
        }
        else if (cols_contiguous_)
        {
          const int32_t* cols = cols_.data();
          T* out = scratch.data();
          for (int k = cols_lo_; k < cols_hi_; ++k)
            out[k] = mrow[cols[k]];
        }
        else
          for (std::size_t k = 0; k < n; ++k)
            scratch[k] = cols_[k] >= 0 ? mrow[cols_[k]] : neutral;
        cached_row = my;
      }
      fn(row + window_.x0, scratch.data(), n);
    }
    else
    {
      double px = p0x_ + window_.x0 * dux_ + j * dvx_;
      double py = p0y_ + window_.x0 * duy_ + j * dvy_;
      for (std::size_t k = 0; k < n; ++k, px += dux_, py += duy_)
      {
        const bool inside = px >= 0.0 && py >= 0.0 && px < mask_w && py < mask_h;
        scratch[k] = inside ? source[static_cast<std::size_t>(py) * mask_w + static_cast<std::size_t>(px)] : neutral;
      }
      fn(row + window_.x0, scratch.data(), n);
    }
  }
}

template <class Fn>
void MaskMapping::forEach(Costmap2D& master, const OccupancyGridData& mask, Fn&& fn) const
{
  if (window_.empty()) return;
  const int mask_w = static_cast<int>(mask.width);
  const int mask_h = static_cast<int>(mask.height);
  const int8_t* mdata = mask.data.data();
  for (int j = window_.y0; j < window_.yn; ++j)
  {
    uint8_t* row = master.data() + static_cast<std::size_t>(j) * master.getSizeInCellsX();
    if (offset_)
    {
      const int my = j + offset_y_;
      if (my < 0 || my >= mask_h) continue;
      const int i0 = std::max(window_.x0, -offset_x_);
      const int i1 = std::min(window_.xn, mask_w - offset_x_);
      const int8_t* mrow = mdata + static_cast<std::size_t>(my) * mask_w + offset_x_;
      for (int i = i0; i < i1; ++i)
        fn(row[i], mrow[i]);
    }
    else if (axis_aligned_)
    {
      const int my = rows_[static_cast<std::size_t>(j - window_.y0)];
      if (my < 0) continue;
      const int8_t* mrow = mdata + static_cast<std::size_t>(my) * mask_w;
      const int32_t* cols = cols_.data() - window_.x0;
      for (int i = window_.x0; i < window_.xn; ++i)
      {
        const int mx = cols[i];
        if (mx >= 0) fn(row[i], mrow[mx]);
      }
    }
    else
    {
      double px = p0x_ + window_.x0 * dux_ + j * dvx_;
      double py = p0y_ + window_.x0 * duy_ + j * dvy_;
      for (int i = window_.x0; i < window_.xn; ++i, px += dux_, py += duy_)
      {
        if (!(px >= 0.0 && py >= 0.0 && px < mask_w && py < mask_h)) continue;  // NaN too
        fn(row[i], mdata[static_cast<std::size_t>(py) * mask_w + static_cast<std::size_t>(px)]);
      }
    }
  }
}
}  // namespace costmap_layers
