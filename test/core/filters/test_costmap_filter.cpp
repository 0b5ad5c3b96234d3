// Unit tests of the CostmapFilter base (through a tiny test subclass) and of GridSampler, checked
// against a naive per-cell computation.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "costmap_layers/core/filters/costmap_filter.hpp"
#include "fake_context.hpp"

using namespace costmap_layers;
using costmap_layers_test::FakeContext;
using costmap_layers_test::GridKind;

namespace
{
constexpr uint8_t kSentinel = 200;  // never a value the test filter writes

/// Writes every mask value it is given into the master cell (as uint8: -1 becomes 255).
class CopyFilter : public CostmapFilter
{
public:
  int process_calls = 0;
  int pose_calls = 0;
  CellWindow last_window;
  bool last_axis_aligned = false;
  bool last_offset = false;
  Transform2D last_to_mask;
  std::string init_topic;

protected:
  void onInitializeFilter(const ParamReader&) override { init_topic = maskTopic(); }
  void process(Costmap2D& master, const CellWindow& window, const OccupancyGridData& mask, const GridSampler& mapping,
               double, double, double) override
  {
    ++process_calls;
    last_window = window;
    last_axis_aligned = mapping.axisAligned();
    last_offset = mapping.isOffset();
    mapping.forEach(master, mask, [](uint8_t& cell, int8_t v) { cell = static_cast<uint8_t>(v); });
  }
  void processPose(const OccupancyGridData&, const Transform2D& to_mask, double, double, double) override
  {
    ++pose_calls;
    last_to_mask = to_mask;
  }
};

OccupancyGridData makeMask(uint32_t w, uint32_t h, double res, double ox, double oy, double yaw = 0.0,
                           const std::string& frame = "map")
{
  OccupancyGridData m;
  m.frame_id = frame;
  m.width = w;
  m.height = h;
  m.resolution = res;
  m.origin_x = ox;
  m.origin_y = oy;
  m.origin_yaw = yaw;
  m.data.resize(static_cast<std::size_t>(w) * h);
  for (std::size_t k = 0; k < m.data.size(); ++k)
    m.data[k] = static_cast<int8_t>(k % 7 == 3 ? -1 : k % 100 + 1);
  return m;
}

std::shared_ptr<const OccupancyGridData> share(const OccupancyGridData& m)
{
  return std::make_shared<const OccupancyGridData>(m);
}

/// The mask value under the centre of master cell (i, j), computed from scratch: cell centre in the
/// global frame -> mask frame (to_mask) -> relative to the mask origin, rotated by -origin_yaw ->
/// divided by the mask resolution -> truncated. *ambiguous is set when the point lies within 1e-6
/// cells of a mask cell edge (then either neighbour would be right).
std::optional<int8_t> naiveValue(const Costmap2D& master, unsigned int i, unsigned int j, const OccupancyGridData& mask,
                                 const Transform2D& to_mask, bool* ambiguous)
{
  const double wx = master.getOriginX() + (i + 0.5) * master.getResolution();
  const double wy = master.getOriginY() + (j + 0.5) * master.getResolution();
  const double tx = to_mask.x + std::cos(to_mask.yaw) * wx - std::sin(to_mask.yaw) * wy;
  const double ty = to_mask.y + std::sin(to_mask.yaw) * wx + std::cos(to_mask.yaw) * wy;
  const double dx = tx - mask.origin_x, dy = ty - mask.origin_y;
  const double gx = (std::cos(mask.origin_yaw) * dx + std::sin(mask.origin_yaw) * dy) / mask.resolution;
  const double gy = (-std::sin(mask.origin_yaw) * dx + std::cos(mask.origin_yaw) * dy) / mask.resolution;
  const double fx = gx - std::round(gx), fy = gy - std::round(gy);
  if (std::fabs(fx) < 1e-6 || std::fabs(fy) < 1e-6) *ambiguous = true;
  if (gx < 0.0 || gy < 0.0 || gx >= mask.width || gy >= mask.height) return std::nullopt;
  const auto cx = static_cast<std::size_t>(gx), cy = static_cast<std::size_t>(gy);
  return mask.data[cy * mask.width + cx];
}

/// Checks master against the naive computation: inside the window, cells on the mask hold the mask
/// value and cells off the mask hold the sentinel; outside the window everything holds the sentinel.
/// @return the number of cells that took a mask value.
int expectMatchesNaive(const Costmap2D& master, const CellWindow& w, const OccupancyGridData& mask,
                       const Transform2D& to_mask)
{
  int on_mask = 0;
  for (unsigned int j = 0; j < master.getSizeInCellsY(); ++j)
    for (unsigned int i = 0; i < master.getSizeInCellsX(); ++i)
    {
      bool ambiguous = false;
      const bool inside = static_cast<int>(i) >= w.x0 && static_cast<int>(i) < w.xn && static_cast<int>(j) >= w.y0 &&
                          static_cast<int>(j) < w.yn;
      const auto v = naiveValue(master, i, j, mask, to_mask, &ambiguous);
      EXPECT_FALSE(ambiguous && inside) << "degenerate test set-up at cell " << i << "," << j;
      const uint8_t expected = (inside && v) ? static_cast<uint8_t>(*v) : kSentinel;
      if (inside && v) ++on_mask;
      EXPECT_EQ(static_cast<int>(master.getCost(i, j)), static_cast<int>(expected)) << "cell " << i << "," << j;
    }
  return on_mask;
}

/// Runs the row-wise form of the mapping on a copy of master, with the mask values widened to int16 and
/// the sentinel as the neutral value, and checks it against the naive computation too.
void expectRowsMatchNaive(const GridSampler& m, const Costmap2D& master, const CellWindow& w,
                          const OccupancyGridData& mask, const Transform2D& to_mask)
{
  Costmap2D copy = master;
  copy.fillWindow(0, 0, copy.getSizeInCellsX(), copy.getSizeInCellsY(), kSentinel);
  std::vector<int16_t> source(mask.data.begin(), mask.data.end());
  std::vector<int16_t> scratch;
  m.forEachRow(copy, source.data(), mask.width, mask.height, static_cast<int16_t>(kSentinel), scratch,
               [](uint8_t* cells, const int16_t* values, std::size_t n)
               {
                 for (std::size_t k = 0; k < n; ++k)
                   cells[k] = static_cast<uint8_t>(values[k]);
               });
  SCOPED_TRACE("forEachRow");
  expectMatchesNaive(copy, w, mask, to_mask);
}

/// As expectRowsMatchNaive, with the mask values as bytes (the block-shuffle gather), twice over the
/// same scratch (which starts with stale values).
void expectByteRowsMatchNaive(const GridSampler& m, const Costmap2D& master, const CellWindow& w,
                              const OccupancyGridData& mask, const Transform2D& to_mask)
{
  const std::vector<uint8_t> source(mask.data.begin(), mask.data.end());
  std::vector<uint8_t> scratch(3, 77);
  for (int pass = 0; pass < 2; ++pass)
  {
    Costmap2D copy = master;
    copy.fillWindow(0, 0, copy.getSizeInCellsX(), copy.getSizeInCellsY(), kSentinel);
    m.forEachRow(copy, source.data(), mask.width, mask.height, kSentinel, scratch,
                 [](uint8_t* cells, const uint8_t* values, std::size_t n)
                 {
                   for (std::size_t k = 0; k < n; ++k)
                     cells[k] = values[k];
                 });
    SCOPED_TRACE("forEachRow, bytes, pass " + std::to_string(pass));
    expectMatchesNaive(copy, w, mask, to_mask);
  }
}

struct Rig
{
  LayeredCostmap lc{"map", false, false};
  std::shared_ptr<FakeContext> ctx;
  std::shared_ptr<CopyFilter> filter = std::make_shared<CopyFilter>();

  explicit Rig(ParamValue params = ParamValue::makeMap()) : ctx(std::make_shared<FakeContext>(std::move(params)))
  {
    filter->initialize(&lc, "test_filter", ctx);
    ctx->bind(*filter);
  }
  /// Calls updateBounds with "nothing yet" bounds and returns what came back.
  std::array<double, 4> bounds(double x0 = std::numeric_limits<double>::max(),
                               double y0 = std::numeric_limits<double>::max(),
                               double x1 = std::numeric_limits<double>::lowest(),
                               double y1 = std::numeric_limits<double>::lowest())
  {
    filter->updateBounds(0.0, 0.0, 0.0, &x0, &y0, &x1, &y1);
    return {x0, y0, x1, y1};
  }
};

using B = std::array<double, 4>;
constexpr double kDMax = std::numeric_limits<double>::max();
constexpr double kDLow = std::numeric_limits<double>::lowest();
}  // namespace

// ---------------------------------------------------------------- set-up

TEST(CostmapFilterBase, InitializeSubscribesAndAdvertisesToggle)
{
  Rig r;
  ASSERT_EQ(r.ctx->grid_subs.size(), 1u);
  EXPECT_EQ(r.ctx->grid_subs[0].topic, "/map_filter");
  EXPECT_EQ(r.ctx->grid_subs[0].kind, GridKind::Mask);
  EXPECT_EQ(r.filter->maskTopic(), "/map_filter");
  EXPECT_EQ(r.filter->init_topic, "/map_filter");  // read before onInitializeFilter
  EXPECT_TRUE(static_cast<bool>(r.ctx->toggle));
  EXPECT_TRUE(r.filter->enabled());
  EXPECT_EQ(r.filter->getMask(), nullptr);
  EXPECT_FALSE(r.filter->isClearable());

  ParamValue p = ParamValue::makeMap();
  p.set("mask_topic", ParamValue::makeString("/keepout_mask"));
  p.set("enabled", ParamValue::makeBool(false));
  Rig r2(p);
  EXPECT_EQ(r2.ctx->grid_subs[0].topic, "/keepout_mask");
  EXPECT_FALSE(r2.filter->enabled());  // starts switched off: the host leaves it out of updates
}

// ---------------------------------------------------------------- mask validation

TEST(CostmapFilterBase, InvalidMasksAreRejectedAndThePreviousOneKept)
{
  Rig r;
  const auto good = share(makeMask(4, 3, 0.5, 1.0, 2.0));
  EXPECT_EQ(r.filter->setMask(good), "");
  EXPECT_EQ(r.filter->getMask(), good);

  struct Bad
  {
    const char* what;
    OccupancyGridData mask;
    const char* needle;
  };
  std::vector<Bad> bad;
  {
    auto m = makeMask(4, 3, 0.5, 0, 0);
    m.data.pop_back();
    bad.push_back({"data one short", m, "data"});
  }
  {
    auto m = makeMask(4, 3, 0.5, 0, 0);
    m.data.push_back(0);
    bad.push_back({"data one long", m, "data"});
  }
  bad.push_back({"zero resolution", makeMask(4, 3, 0.0, 0, 0), "resolution"});
  bad.push_back({"negative resolution", makeMask(4, 3, -0.1, 0, 0), "resolution"});
  bad.push_back({"NaN resolution", makeMask(4, 3, std::nan(""), 0, 0), "resolution"});
  bad.push_back({"inf origin", makeMask(4, 3, 0.5, std::numeric_limits<double>::infinity(), 0), "origin"});
  bad.push_back({"NaN origin y", makeMask(4, 3, 0.5, 0, std::nan("")), "origin"});
  bad.push_back({"NaN yaw", makeMask(4, 3, 0.5, 0, 0, std::nan("")), "origin"});
  bad.push_back({"absurd origin", makeMask(4, 3, 0.5, 5e7, 0), "origin"});
  bad.push_back({"zero width", makeMask(0, 3, 0.5, 0, 0), "width"});
  {
    OccupancyGridData m;  // huge dimensions, no data allocated: must be refused before any copy
    m.width = 100000;
    m.height = 100000;
    m.resolution = 0.05;
    bad.push_back({"huge dimensions", m, "exceeds"});
  }
  for (const auto& b : bad)
  {
    const InputError direct = validateGrid(b.mask);
    EXPECT_NE(direct.message.find(b.needle), std::string::npos) << b.what << ": " << direct.message;
    EXPECT_FALSE(direct.field.empty()) << b.what;
    const std::string err = r.filter->setMask(share(b.mask));
    EXPECT_FALSE(err.empty()) << b.what;
    EXPECT_EQ(r.filter->getMask(), good) << b.what;
  }
  EXPECT_FALSE(r.filter->setMask(nullptr).empty());
  EXPECT_EQ(r.filter->getMask(), good);
  EXPECT_TRUE(validateGrid(makeMask(4, 3, 0.5, 1.0, 2.0)).ok());
  EXPECT_FALSE(validateGrid(makeMask(10, 10, 1.0, 0, 0), 99).ok());  // custom cell limit
}

TEST(CostmapFilterBase, RejectedMaskOnTopicIsReportedAndIgnored)
{
  Rig r;
  r.ctx->publishGrid(GridKind::Mask, makeMask(3, 3, 1.0, 0, 0));
  const auto first = r.filter->getMask();
  ASSERT_NE(first, nullptr);
  EXPECT_TRUE(r.ctx->reports.empty());
  r.ctx->publishGrid(GridKind::Mask, makeMask(3, 3, 0.0, 0, 0));
  EXPECT_EQ(r.filter->getMask(), first);
  ASSERT_EQ(r.ctx->reports.size(), 1u);
  EXPECT_EQ(r.ctx->reports[0].severity, Severity::Error);
  EXPECT_EQ(r.ctx->reports[0].key, "mask/info.resolution");  // throttled per field
  EXPECT_NE(r.ctx->reports[0].message.find("test_filter"), std::string::npos);
  EXPECT_NE(r.ctx->reports[0].message.find("/map_filter"), std::string::npos);
  EXPECT_NE(r.ctx->reports[0].message.find("resolution"), std::string::npos);
  // A rejected mask does not count as a change: the next bounds are only the first mask's.
  EXPECT_EQ(r.bounds(), (B{0.0, 0.0, 3.0, 3.0}));
  EXPECT_EQ(r.bounds(1, 1, 2, 2), (B{1, 1, 2, 2}));
}

// ---------------------------------------------------------------- bounds

TEST(CostmapFilterBase, BoundsCoverUnionOfOldAndNewMaskExtents)
{
  Rig r;
  EXPECT_EQ(r.bounds(1, 1, 2, 2), (B{1, 1, 2, 2}));  // no mask: nothing asked
  EXPECT_EQ(r.filter->setMask(share(makeMask(5, 5, 1.0, 0.0, 0.0))), "");
  EXPECT_EQ(r.bounds(), (B{0.0, 0.0, 5.0, 5.0}));
  EXPECT_EQ(r.bounds(1, 1, 2, 2), (B{1, 1, 2, 2}));  // unchanged mask: nothing more
  EXPECT_EQ(r.filter->setMask(share(makeMask(3, 2, 0.5, 10.0, 12.0))), "");
  EXPECT_EQ(r.bounds(1, 1, 2, 2), (B{0.0, 0.0, 11.5, 13.0}));  // old [0,5]^2 with new [10,11.5]x[12,13]
  EXPECT_EQ(r.bounds(), (B{kDMax, kDMax, kDLow, kDLow}));
  // Two masks between updates: the one in force before (B) and the newest (D); C was never drawn.
  EXPECT_EQ(r.filter->setMask(share(makeMask(2, 2, 1.0, 20.0, 20.0))), "");
  EXPECT_EQ(r.filter->setMask(share(makeMask(1, 1, 1.0, -5.0, -5.0))), "");
  EXPECT_EQ(r.bounds(), (B{-5.0, -5.0, 11.5, 13.0}));
  EXPECT_EQ(r.bounds(), (B{kDMax, kDMax, kDLow, kDLow}));
}

// An earlier layer that hands on NaN bounds (another plugin's bug) must not cancel the redraw of a new
// mask: the extent comes out whole.
TEST(CostmapFilterBase, NaNBoundsFromAnEarlierLayerDoNotCancelTheRedraw)
{
  Rig r;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(r.filter->setMask(share(makeMask(5, 5, 1.0, 0.0, 0.0))), "");
  EXPECT_EQ(r.bounds(nan, nan, nan, nan), (B{0.0, 0.0, 5.0, 5.0}));
}

TEST(CostmapFilterBase, BoundsOfRotatedAndTransformedMasks)
{
  Rig r;
  EXPECT_EQ(r.filter->setMask(share(makeMask(4, 2, 1.0, 1.0, 1.0, M_PI / 2))), "");
  // Rotated masks are drawn rotated; in a costmap that is not rolling the static layer ignores its
  // map's yaw (as costmap_2d and Nav2): said, since a mask made on the map's image would be off.
  EXPECT_EQ(r.ctx->countReports("ignores its map's yaw"), 1);
  EXPECT_EQ(r.ctx->countReports("origin yaw 1.5708 rad"), 1);
  const B b = r.bounds();
  EXPECT_NEAR(b[0], -1.0, 1e-9);
  EXPECT_NEAR(b[1], 1.0, 1e-9);
  EXPECT_NEAR(b[2], 1.0, 1e-9);
  EXPECT_NEAR(b[3], 5.0, 1e-9);

  // A mask in "odom", where odom -> map moves points by (+10, -2).
  Rig t;
  const Transform2D to_mask{-10.0, 2.0, 0.0};
  t.ctx->transforms[{"odom", "map"}] = to_mask;
  t.ctx->transforms[{"map", "odom"}] = to_mask.inverse();
  EXPECT_EQ(t.filter->setMask(share(makeMask(2, 3, 1.0, 0.0, 0.0, 0.0, "odom"))), "");
  const B c = t.bounds();
  EXPECT_NEAR(c[0], 10.0, 1e-9);
  EXPECT_NEAR(c[1], -2.0, 1e-9);
  EXPECT_NEAR(c[2], 12.0, 1e-9);
  EXPECT_NEAR(c[3], 1.0, 1e-9);
}

TEST(CostmapFilterBase, UpdatedWindowAfterMaskChangeThroughLayeredCostmap)
{
  Rig r;
  r.lc.resizeMap(20, 20, 1.0, 0.0, 0.0);
  r.lc.addFilter(r.filter);
  r.filter->setMask(share(makeMask(4, 5, 1.0, 2.0, 3.0)));
  r.lc.updateMap(0, 0, 0);
  CellWindow w = r.lc.getUpdatedBounds();
  EXPECT_EQ(w.x0, 2);
  EXPECT_EQ(w.y0, 3);
  EXPECT_GE(w.xn, 6);
  EXPECT_GE(w.yn, 8);
  r.lc.updateMap(0, 0, 0);
  EXPECT_TRUE(r.lc.getUpdatedBounds().empty());
  r.filter->setMask(share(makeMask(2, 2, 1.0, 10.25, 10.25)));
  r.lc.updateMap(0, 0, 0);
  w = r.lc.getUpdatedBounds();
  EXPECT_EQ(w.x0, 2);  // the old mask's extent ...
  EXPECT_EQ(w.y0, 3);
  EXPECT_EQ(w.xn, 13);  // ... united with the new one, [10.25, 12.25]: cells up to 12
  EXPECT_EQ(w.yn, 13);
  // The old mask's cells were cleared, the new mask's cells written.
  const Costmap2D& g = r.lc.getCostmap();
  EXPECT_EQ(g.getCost(3, 4), 0);
  EXPECT_EQ(g.getCost(10, 10), static_cast<uint8_t>(makeMask(2, 2, 1.0, 0, 0).data[0]));
  EXPECT_EQ(g.getCost(11, 11), static_cast<uint8_t>(makeMask(2, 2, 1.0, 0, 0).data[3]));
}

// ---------------------------------------------------------------- toggling

namespace
{
/// 12x12 at 1 m with a 4x4 mask at (2, 2); returns the rig after the first update.
void expectMaskDrawn(const Costmap2D& g, const OccupancyGridData& mask, bool drawn)
{
  for (unsigned int y = 0; y < 12; ++y)
    for (unsigned int x = 0; x < 12; ++x)
    {
      const bool on = x >= 2 && x < 6 && y >= 2 && y < 6;
      const uint8_t v = on && drawn ? static_cast<uint8_t>(mask.data[(y - 2) * 4 + (x - 2)]) : 0;
      EXPECT_EQ(g.getCost(x, y), v) << x << "," << y << (drawn ? " drawn" : " cleared");
    }
}
}  // namespace

TEST(CostmapFilterBase, ToggleClearsAndRestoresTheEffect)
{
  Rig r;
  r.lc.resizeMap(12, 12, 1.0, 0.0, 0.0);
  r.lc.addFilter(r.filter);
  const auto mask = makeMask(4, 4, 1.0, 2.0, 2.0);
  r.filter->setMask(share(mask));
  r.lc.updateMap(0, 0, 0);
  expectMaskDrawn(r.lc.getCostmap(), mask, true);
  EXPECT_EQ(r.filter->process_calls, 1);

  r.ctx->toggle(false);  // the ~toggle service
  EXPECT_FALSE(r.filter->enabled());
  r.lc.updateMap(0, 0, 0);
  // The host redraws the whole grid once when a switch flips.
  const CellWindow all = r.lc.getUpdatedBounds();
  EXPECT_EQ(all.x0, 0);
  EXPECT_EQ(all.y0, 0);
  EXPECT_EQ(all.xn, 12);
  EXPECT_EQ(all.yn, 12);
  expectMaskDrawn(r.lc.getCostmap(), mask, false);
  EXPECT_EQ(r.filter->process_calls, 1);
  r.lc.updateMap(0, 0, 0);
  EXPECT_TRUE(r.lc.getUpdatedBounds().empty());

  r.filter->setEnabled(false);  // no change: no redraw
  r.lc.updateMap(0, 0, 0);
  EXPECT_TRUE(r.lc.getUpdatedBounds().empty());

  r.filter->setEnabled(true);
  r.lc.updateMap(0, 0, 0);
  expectMaskDrawn(r.lc.getCostmap(), mask, true);
  EXPECT_EQ(r.filter->process_calls, 2);
}

TEST(CostmapFilterBase, ToggleOffThenNewMaskClearsTheOldMasksArea)
{
  Rig r;
  r.lc.resizeMap(12, 12, 1.0, 0.0, 0.0);
  r.lc.addFilter(r.filter);
  const auto mask = makeMask(4, 4, 1.0, 2.0, 2.0);
  r.filter->setMask(share(mask));
  r.lc.updateMap(0, 0, 0);
  expectMaskDrawn(r.lc.getCostmap(), mask, true);
  // Switched off, and before the next update a new mask elsewhere arrives: the old mask's effect
  // must still disappear.
  r.filter->setEnabled(false);
  r.filter->setMask(share(makeMask(2, 2, 1.0, 8.0, 8.0)));
  r.lc.updateMap(0, 0, 0);
  const Costmap2D& g = r.lc.getCostmap();
  for (unsigned int i = 0; i < g.cellCount(); ++i)
    EXPECT_EQ(g.getCost(i), 0) << i;
}

// ---------------------------------------------------------------- transforms

TEST(CostmapFilterBase, MissingTransformWritesNothingAndReportsBothFrames)
{
  Rig r;
  r.filter->setMask(share(makeMask(4, 4, 1.0, 0.0, 0.0, 0.0, "odom")));
  const B b = r.bounds();
  // The extent is unknown without a transform: everything is asked for.
  EXPECT_LE(b[0], -1e30);
  EXPECT_LE(b[1], -1e30);
  EXPECT_GE(b[2], 1e30);
  EXPECT_GE(b[3], 1e30);
  ASSERT_GE(r.ctx->reports.size(), 1u);
  const auto& rep = r.ctx->reports.back();
  EXPECT_EQ(rep.severity, Severity::Error);
  EXPECT_NE(rep.message.find("map"), std::string::npos) << rep.message;
  EXPECT_NE(rep.message.find("odom"), std::string::npos) << rep.message;
  EXPECT_EQ(r.filter->pose_calls, 0);

  Costmap2D master(10, 10, 1.0, 0.0, 0.0, kSentinel);
  r.filter->updateCosts(master, 0, 0, 10, 10);
  EXPECT_EQ(r.filter->process_calls, 0);
  for (unsigned int i = 0; i < master.cellCount(); ++i)
    EXPECT_EQ(master.getCost(i), kSentinel);

  // Once the transform exists, the filter works again.
  r.ctx->transforms[{"odom", "map"}] = Transform2D{};
  r.bounds();
  EXPECT_EQ(r.filter->pose_calls, 1);
  r.filter->updateCosts(master, 0, 0, 10, 10);
  EXPECT_EQ(r.filter->process_calls, 1);
  EXPECT_EQ(master.getCost(0, 0), static_cast<uint8_t>(r.filter->getMask()->data[0]));
}

TEST(CostmapFilterBase, NoMaskOrDisabledWritesNothing)
{
  Rig r;
  Costmap2D master(6, 6, 1.0, 0.0, 0.0, kSentinel);
  r.bounds();
  r.filter->updateCosts(master, 0, 0, 6, 6);
  EXPECT_EQ(r.filter->process_calls, 0);
  for (unsigned int i = 0; i < master.cellCount(); ++i)
    EXPECT_EQ(master.getCost(i), kSentinel);
  // Switched off, the host (LayeredCostmap) calls it no more: no pose, no costs.
  r.lc.resizeMap(6, 6, 1.0, 0.0, 0.0);
  r.lc.addFilter(r.filter);
  r.filter->setMask(share(makeMask(6, 6, 1.0, 0.0, 0.0)));
  r.filter->setEnabled(false);
  r.lc.updateMap(0, 0, 0);
  EXPECT_EQ(r.filter->pose_calls, 0);
  EXPECT_EQ(r.filter->process_calls, 0);
}

TEST(CostmapFilterBase, TransformedMaskMatchesNaiveAndWindowIsClamped)
{
  Rig r;
  const Transform2D to_mask{1.37, -0.71, 0.3};  // global -> odom
  r.ctx->transforms[{"odom", "map"}] = to_mask;
  r.ctx->transforms[{"map", "odom"}] = to_mask.inverse();
  const auto mask = makeMask(9, 7, 0.4, -0.93, 0.21, 0.0, "odom");
  r.filter->setMask(share(mask));
  r.bounds();
  EXPECT_EQ(r.filter->pose_calls, 1);
  EXPECT_DOUBLE_EQ(r.filter->last_to_mask.x, 1.37);
  EXPECT_DOUBLE_EQ(r.filter->last_to_mask.yaw, 0.3);
  Costmap2D master(16, 14, 0.25, -2.0, -1.5, kSentinel);
  r.filter->updateCosts(master, -3, 2, 40, 12);  // clamped to [0, 16) x [2, 12)
  EXPECT_EQ(r.filter->last_window.x0, 0);
  EXPECT_EQ(r.filter->last_window.xn, 16);
  EXPECT_EQ(r.filter->last_window.y0, 2);
  EXPECT_EQ(r.filter->last_window.yn, 12);
  EXPECT_FALSE(r.filter->last_axis_aligned);
  const int on = expectMatchesNaive(master, CellWindow{0, 2, 16, 12}, mask, to_mask);
  EXPECT_GT(on, 10);
  EXPECT_LT(on, 16 * 10);  // part of the window lies off the mask
}

// ---------------------------------------------------------------- GridSampler

TEST(GridSamplerTest, OffsetPath)
{
  Costmap2D master(12, 10, 0.5, -1.0, 0.5, kSentinel);
  const auto mask = makeMask(7, 5, 0.5, 0.0, 1.0);  // same resolution, shifted by (2, 1) cells
  const CellWindow w{1, 2, 11, 9};
  GridSampler m;
  m.build(master, w, mask, Transform2D{});
  EXPECT_TRUE(m.axisAligned());
  EXPECT_TRUE(m.isOffset());
  expectRowsMatchNaive(m, master, w, mask, Transform2D{});
  expectByteRowsMatchNaive(m, master, w, mask, Transform2D{});
  m.forEach(master, mask, [](uint8_t& cell, int8_t v) { cell = static_cast<uint8_t>(v); });
  const int on = expectMatchesNaive(master, w, mask, Transform2D{});
  EXPECT_GT(on, 0);
  // Written out: master cell (2, 1) is mask cell (0, 0) (outside the window), (2, 2) is mask (0, 1).
  EXPECT_EQ(master.getCost(2, 2), static_cast<uint8_t>(mask.data[7]));
  EXPECT_EQ(master.getCost(2, 1), kSentinel);
  EXPECT_EQ(master.getCost(1, 2), kSentinel);
}

TEST(GridSamplerTest, OffsetPathWithTranslationAndNegativeOffset)
{
  Costmap2D master(10, 10, 1.0, 0.0, 0.0, kSentinel);
  const auto mask = makeMask(20, 20, 1.0, -4.0, -3.0);
  const Transform2D t{2.0, -5.0, 0.0};
  const CellWindow w{0, 0, 10, 10};
  GridSampler m;
  m.build(master, w, mask, t);
  EXPECT_TRUE(m.isOffset());
  expectRowsMatchNaive(m, master, w, mask, t);
  expectByteRowsMatchNaive(m, master, w, mask, t);
  m.forEach(master, mask, [](uint8_t& cell, int8_t v) { cell = static_cast<uint8_t>(v); });
  EXPECT_GT(expectMatchesNaive(master, w, mask, t), 0);
}

TEST(GridSamplerTest, AxisAlignedDifferentResolution)
{
  Costmap2D master(14, 12, 0.2, -0.5, 0.3, kSentinel);
  const auto mask = makeMask(10, 8, 0.3, 0.13, 0.71);
  const CellWindow w{0, 1, 13, 12};
  GridSampler m;
  m.build(master, w, mask, Transform2D{});
  EXPECT_TRUE(m.axisAligned());
  EXPECT_FALSE(m.isOffset());
  expectRowsMatchNaive(m, master, w, mask, Transform2D{});
  expectByteRowsMatchNaive(m, master, w, mask, Transform2D{});
  m.forEach(master, mask, [](uint8_t& cell, int8_t v) { cell = static_cast<uint8_t>(v); });
  const int on = expectMatchesNaive(master, w, mask, Transform2D{});
  EXPECT_GT(on, 0);
  EXPECT_LT(on, 13 * 11);

  // Coarser master than mask, with a translated transform.
  Costmap2D coarse(8, 8, 1.0, 0.0, 0.0, kSentinel);
  const auto fine = makeMask(30, 25, 0.27, 0.12, 0.37);
  const Transform2D t{0.9, 0.4, 0.0};
  GridSampler m2;
  m2.build(coarse, CellWindow{0, 0, 8, 8}, fine, t);
  EXPECT_TRUE(m2.axisAligned());
  EXPECT_FALSE(m2.isOffset());
  expectRowsMatchNaive(m2, coarse, CellWindow{0, 0, 8, 8}, fine, t);
  expectByteRowsMatchNaive(m2, coarse, CellWindow{0, 0, 8, 8}, fine, t);
  m2.forEach(coarse, fine, [](uint8_t& cell, int8_t v) { cell = static_cast<uint8_t>(v); });
  EXPECT_GT(expectMatchesNaive(coarse, CellWindow{0, 0, 8, 8}, fine, t), 0);
}

TEST(GridSamplerTest, AxisAlignedByteGatherBlocks)
{
  struct Case
  {
    const char* what;
    double mask_res;
    uint32_t mask_w, mask_h;
    double ox, oy;
    Transform2D t;
    CellWindow w;
    int block;  ///< expected byteGatherBlock()
  };
  // Master: 120 x 40 cells of 0.05 m at (-1, -0.5). Offsets keep cell centres clear of mask cell edges.
  const std::vector<Case> cases = {
      // Coarser mask, off the master on both sides (neutral margins, last block overlapping, and blocks
      // near the mask's right end loading from mask_w - 16).
      {"coarser, both margins", 0.07, 60, 20, -0.613, -0.287, Transform2D{}, CellWindow{0, 0, 120, 40}, 16},
      {"coarser, inside", 0.07, 200, 40, -2.013, -1.027, Transform2D{}, CellWindow{3, 2, 117, 39}, 16},
      {"much coarser", 0.33, 30, 10, -1.213, -0.587, Transform2D{}, CellWindow{0, 0, 120, 40}, 16},
      // Finer mask: 16 columns span more than 16 mask bytes, 8 do not.
      {"finer", 0.03, 150, 50, -0.507, -0.413, Transform2D{}, CellWindow{0, 0, 120, 40}, 8},
      // Far finer: no block fits, cell by cell.
      {"far finer", 0.0113, 300, 200, -0.90371, -0.44137, Transform2D{}, CellWindow{0, 0, 120, 40}, 0},
      // Mask narrower than one load: cell by cell.
      {"narrow mask", 0.07, 12, 30, -0.213, -0.387, Transform2D{}, CellWindow{0, 0, 120, 40}, 0},
      // Flipped (yaw pi): mask columns fall as master columns rise.
      {"flipped", 0.07, 100, 40, -4.513, -1.627, Transform2D{0.0, 0.0, M_PI}, CellWindow{0, 0, 120, 40}, 16},
      // A run of on-mask columns shorter than 16: one block of 8.
      {"short run", 0.07, 20, 20, 0.0031, -0.287, Transform2D{}, CellWindow{0, 0, 31, 40}, 8},
  };
  for (const auto& c : cases)
  {
    SCOPED_TRACE(c.what);
    Costmap2D master(120, 40, 0.05, -1.0, -0.5, kSentinel);
    const auto mask = makeMask(c.mask_w, c.mask_h, c.mask_res, c.ox, c.oy);
    GridSampler m;
    m.build(master, c.w, mask, c.t);
    ASSERT_TRUE(m.axisAligned());
    ASSERT_FALSE(m.isOffset());
    EXPECT_EQ(m.byteGatherBlock(), c.block);
    expectByteRowsMatchNaive(m, master, c.w, mask, c.t);
    expectRowsMatchNaive(m, master, c.w, mask, c.t);
    m.forEach(master, mask, [](uint8_t& cell, int8_t v) { cell = static_cast<uint8_t>(v); });
    EXPECT_GT(expectMatchesNaive(master, c.w, mask, c.t), 0);
  }
}

TEST(GridSamplerTest, RotatedMaskOrigin)
{
  Costmap2D master(20, 18, 0.25, -1.0, -1.0, kSentinel);
  const auto mask = makeMask(12, 9, 0.33, 0.4, -0.6, 0.47);
  const CellWindow w{2, 1, 19, 17};
  GridSampler m;
  m.build(master, w, mask, Transform2D{});
  EXPECT_FALSE(m.axisAligned());
  EXPECT_FALSE(m.isOffset());
  expectRowsMatchNaive(m, master, w, mask, Transform2D{});
  expectByteRowsMatchNaive(m, master, w, mask, Transform2D{});
  m.forEach(master, mask, [](uint8_t& cell, int8_t v) { cell = static_cast<uint8_t>(v); });
  const int on = expectMatchesNaive(master, w, mask, Transform2D{});
  EXPECT_GT(on, 20);
  EXPECT_LT(on, 17 * 16);
}

TEST(GridSamplerTest, RotatedTransformAndMask)
{
  Costmap2D master(16, 16, 0.5, -3.0, -2.0, kSentinel);
  const auto mask = makeMask(15, 11, 0.45, -1.3, -0.2, -0.8);
  const Transform2D t{0.77, -1.21, 2.1};
  const CellWindow w{0, 0, 16, 16};
  GridSampler m;
  m.build(master, w, mask, t);
  EXPECT_FALSE(m.axisAligned());
  expectRowsMatchNaive(m, master, w, mask, t);
  expectByteRowsMatchNaive(m, master, w, mask, t);
  m.forEach(master, mask, [](uint8_t& cell, int8_t v) { cell = static_cast<uint8_t>(v); });
  const int on = expectMatchesNaive(master, w, mask, t);
  EXPECT_GT(on, 20);
  EXPECT_LT(on, 256);
}

TEST(GridSamplerTest, MaskEntirelyOutsideTheWindowTouchesNothing)
{
  Costmap2D master(8, 8, 1.0, 0.0, 0.0, kSentinel);
  for (const auto& mask :
       {makeMask(3, 3, 1.0, 50.0, 0.0), makeMask(3, 3, 0.3, -20.0, 2.0), makeMask(3, 3, 0.3, 2.0, 40.0, 0.7)})
  {
    GridSampler m;
    m.build(master, CellWindow{0, 0, 8, 8}, mask, Transform2D{});
    int calls = 0;
    m.forEach(master, mask, [&](uint8_t&, int8_t) { ++calls; });
    EXPECT_EQ(calls, 0);
  }
  for (unsigned int i = 0; i < master.cellCount(); ++i)
    EXPECT_EQ(master.getCost(i), kSentinel);
}

TEST(GridSamplerTest, MaskValueAtMatchesNaive)
{
  // maskValueAt is protected: reach it through a subclass.
  struct Probe : CopyFilter
  {
    static std::optional<int8_t> at(const OccupancyGridData& m, const Transform2D& t, double x, double y)
    {
      return maskValueAt(m, t, x, y);
    }
  };
  const auto mask = makeMask(6, 5, 0.5, 1.0, -1.0, 0.4);
  const Transform2D t{0.3, 0.2, -0.5};
  Costmap2D probe_grid(30, 30, 0.2, -1.0, -3.0);
  int hits = 0;
  for (unsigned int j = 0; j < 30; ++j)
    for (unsigned int i = 0; i < 30; ++i)
    {
      bool ambiguous = false;
      const auto expected = naiveValue(probe_grid, i, j, mask, t, &ambiguous);
      if (ambiguous) continue;
      double wx, wy;
      probe_grid.mapToWorld(i, j, wx, wy);
      const auto got = Probe::at(mask, t, wx, wy);
      ASSERT_EQ(got.has_value(), expected.has_value()) << i << "," << j;
      if (got)
      {
        EXPECT_EQ(*got, *expected);
        ++hits;
      }
    }
  EXPECT_GT(hits, 20);
}
