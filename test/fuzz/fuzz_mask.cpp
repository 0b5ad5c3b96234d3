// Fuzzes OccupancyGrid masks through the real filters: KeepoutFilter, LanesFilter or SpeedFilter on a
// LayeredCostmap, masks delivered on the mask topic (CostmapFilter::setMask -> validateGrid), then
// update cycles at fuzzed robot poses, toggles, and a transform from the mask's frame.
// Input: filter kind, its parameters, master geometry, rolling flag, the transform, then a list of
// operations (new mask / update / toggle). Invariants: a rejected mask leaves the previous one in
// force, an accepted mask is valid by validateGrid, the master grid never changes size.
#include <cstdint>
#include <memory>

#include "costmap_layers/core/filters/keepout_filter.hpp"
#include "costmap_layers/core/filters/lanes_filter.hpp"
#include "costmap_layers/core/filters/speed_filter.hpp"
#include "fuzz_common.hpp"

using namespace costmap_layers;
using namespace costmap_layers_fuzz;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  FuzzDecoder in(data, size);
  const int kind = in.u8() % 3;
  ParamValue params = ParamValue::makeMap();
  if (kind == 1)
  {
    params.set("lane_border_width", ParamValue::makeDouble(in.real()));
    params.set("border_cost", ParamValue::makeInt(in.small(0, 255)));
    params.set("cost_profile", ParamValue::makeString(in.flag() ? "exponential" : "linear"));
    params.set("decay", ParamValue::makeDouble(in.real()));
  }
  else if (kind == 2)
  {
    params.set("default_max_speed", ParamValue::makeDouble(in.real()));
    params.set("speed_limit_in_percent", ParamValue::makeBool(in.flag()));
    params.set("mask_mode", ParamValue::makeString(in.flag() ? "nav2" : "area_id"));
    params.set("base", ParamValue::makeDouble(in.real()));
    params.set("multiplier", ParamValue::makeDouble(in.real()));
  }
  const MasterGeometry g = MasterGeometry::decode(in);
  const bool rolling = in.flag();
  const bool track_unknown = in.flag();

  LayeredCostmap lc("map", rolling, track_unknown);
  lc.resizeMap(g.w, g.h, g.res, g.ox, g.oy);
  auto ctx = std::make_shared<FuzzContext>(params);
  ctx->transforms[{"odom", "map"}] = Transform2D{finiteReal(in), finiteReal(in), finiteReal(in)};
  std::shared_ptr<CostmapFilter> filter;
  if (kind == 0) filter = std::make_shared<KeepoutFilter>();
  if (kind == 1) filter = std::make_shared<LanesFilter>();
  if (kind == 2) filter = std::make_shared<SpeedFilter>();
  try
  {
    filter->initialize(&lc, "filter", ctx);
    ctx->bind(*filter);
  }
  catch (const std::invalid_argument&)
  {
    return 0;  // bad parameters are fuzz_params' business
  }
  lc.addFilter(filter);
  FUZZ_CHECK(ctx->grid_subs.size() == 1, "the filter subscribes to one mask topic");

  for (int op = 0; op < 8 && !in.empty(); ++op)
  {
    switch (in.u8() % 4)
    {
      case 0:
      case 1:
      {
        auto before = filter->getMask();
        auto mask = std::make_shared<const OccupancyGridData>(decodeGrid(in));
        const std::string valid = validateGrid(*mask).message;
        const std::string err = filter->setMask(mask);
        FUZZ_CHECK(err.empty() == valid.empty(), "setMask and validateGrid disagree");
        if (err.empty())
          FUZZ_CHECK(filter->getMask() == mask, "an accepted mask is in force");
        else
          FUZZ_CHECK(filter->getMask() == before, "a rejected mask leaves the previous one in force");
        break;
      }
      case 2:
      {
        double x, y, yaw;
        decodePose(in, x, y, yaw);
        lc.updateMap(x, y, yaw);
        // A rolling window moves with the robot (size kept); a fixed one keeps everything.
        checkMasterUnchanged(lc, g.w, g.h, g.res);
        const CellWindow b = lc.getUpdatedBounds();
        FUZZ_CHECK(b.empty() || (b.x0 >= 0 && b.y0 >= 0 && b.xn <= int(g.w) && b.yn <= int(g.h)),
                   "updated bounds inside the grid");
        break;
      }
      default:
        filter->setEnabled(in.flag());
        break;
    }
  }
  return 0;
}
