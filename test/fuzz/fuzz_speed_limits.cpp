// Fuzzes SpeedLimits (features) through SpeedFilter on a LayeredCostmap: limits as the message
// carries them (SpeedFilter::setSpeedLimits via the features subscription) or as a features YAML
// (io::parseParamsYaml -> io::speedLimitsFromParams, what features_server and costmap_tool read),
// a mask of area ids or Nav2 speed values, and update cycles at fuzzed poses.
// Input: the filter's parameters, master geometry, a mask (width, height, resolution, values), then
// operations (limits message / features YAML / update / toggle).
// Invariants: every published MaxSpeed is finite and >= 0 (0 = no limit), and in percent mode never
// above default_max_speed; buildSpeedLimitTable keeps only ids 1..100 with finite limits >= 0; the
// master grid keeps its size.
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>

#include "costmap_layers/core/filters/speed_filter.hpp"
#include "costmap_layers/io/features_file.hpp"
#include "costmap_layers/io/param_yaml.hpp"
#include "fuzz_common.hpp"

using namespace costmap_layers;
using namespace costmap_layers_fuzz;

namespace
{
SpeedLimitsData decodeLimits(FuzzDecoder& in)
{
  SpeedLimitsData d;
  d.frame_id = "map";
  const uint32_t n = in.small(0, 12);
  for (uint32_t k = 0; k < n; ++k)
  {
    SpeedLimitEntry e;
    e.area_id = in.size();
    e.max_speed = in.real();
    d.limits.push_back(e);
  }
  return d;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  FuzzDecoder in(data, size);
  ParamValue params = ParamValue::makeMap();
  params.set("default_max_speed", ParamValue::makeDouble(in.real()));
  params.set("speed_limit_in_percent", ParamValue::makeBool(in.flag()));
  params.set("mask_mode", ParamValue::makeString(in.flag() ? "nav2" : "area_id"));
  params.set("base", ParamValue::makeDouble(in.real()));
  params.set("multiplier", ParamValue::makeDouble(in.real()));
  const MasterGeometry g = MasterGeometry::decode(in);

  LayeredCostmap lc("map", false, false);
  lc.resizeMap(g.w, g.h, g.res, g.ox, g.oy);
  auto ctx = std::make_shared<FuzzContext>(params);
  auto filter = std::make_shared<SpeedFilter>();
  try
  {
    filter->initialize(&lc, "speed_filter", ctx);
    ctx->bind(*filter);
  }
  catch (const std::invalid_argument&)
  {
    return 0;  // bad parameters are fuzz_params' business
  }
  lc.addFilter(filter);
  const SpeedFilterConfig& cfg = filter->config();

  // One mask, small and valid in geometry (masks themselves are fuzz_mask's business).
  auto mask = std::make_shared<OccupancyGridData>();
  mask->frame_id = "map";
  mask->width = in.small(1, 16);
  mask->height = in.small(1, 16);
  mask->resolution = (1 + in.u8()) / 32.0;
  mask->origin_x = in.i16() / 256.0;
  mask->origin_y = in.i16() / 256.0;
  mask->data = gridValues(in, static_cast<uint64_t>(mask->width) * mask->height, 1u << 16);
  mask->data.resize(static_cast<std::size_t>(mask->width) * mask->height, 0);
  FUZZ_CHECK(filter->setMask(mask).empty(), "a well-formed mask is accepted");

  for (int op = 0; op < 10 && !in.empty(); ++op)
  {
    switch (in.u8() % 5)
    {
      case 0:
      {
        const SpeedLimitsData limits = decodeLimits(in);
        std::vector<SpeedLimitIssue> issues;
        const SpeedLimitTable table = buildSpeedLimitTable(limits, cfg, &issues);
        FUZZ_CHECK(!table.limit_mps[0], "area id 0 never has a limit");
        for (const auto& l : table.limit_mps)
          FUZZ_CHECK(!l || (std::isfinite(*l) && *l >= 0.0), "table limits are finite and >= 0");
        ctx->publishSpeedLimits(limits);
        break;
      }
      case 1:
      {
        const std::string text = in.str(200);
        try
        {
          filter->setSpeedLimits(io::speedLimitsFromParams(io::parseParamsYaml(text, "features"), "features"));
        }
        catch (const std::runtime_error&)
        {
        }
        catch (const std::invalid_argument&)
        {
        }
        break;
      }
      case 2:
        filter->setEnabled(in.flag());
        break;
      default:
      {
        double x, y, yaw;
        decodePose(in, x, y, yaw);
        lc.updateMap(x, y, yaw);
        checkMasterUnchanged(lc, g.w, g.h, g.res);
        FUZZ_CHECK(filter->lastPublished().has_value(), "every cycle has published once");
        const double v = *filter->lastPublished();
        FUZZ_CHECK(std::isfinite(v) && v >= 0.0, "MaxSpeed is finite and >= 0");
        if (cfg.speed_limit_in_percent && cfg.mask_mode == SpeedMaskMode::AreaId)
          FUZZ_CHECK(v <= cfg.default_max_speed * (1 + 1e-12), "percent limits stay within default_max_speed");
        break;
      }
    }
  }
  return 0;
}
