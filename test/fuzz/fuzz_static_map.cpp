// Fuzzes OccupancyGrid maps and OccupancyGridUpdate messages through StaticLayer (optionally followed
// by an InflationLayer) on a LayeredCostmap, fixed or rolling: maps on the map topic (setMap ->
// validateGrid), partial updates on the updates topic (applyUpdate, x/y as the int32 the message
// carries), update cycles at fuzzed poses.
// Invariants: setMap accepts exactly what validateGrid accepts; on a fixed costmap the master takes
// the size and resolution of the map in force (the first one with first_map_only); on a rolling
// costmap the master keeps its geometry.
#include <cstdint>
#include <memory>

#include "costmap_layers/core/filters/costmap_filter.hpp"
#include "costmap_layers/core/layers/inflation_layer.hpp"
#include "costmap_layers/core/layers/static_layer.hpp"
#include "fuzz_common.hpp"

using namespace costmap_layers;
using namespace costmap_layers_fuzz;

namespace
{
OccupancyGridUpdateData decodeUpdate(FuzzDecoder& in)
{
  OccupancyGridUpdateData u;
  u.frame_id = "map";
  // Mostly small windows near the map; tag 255 of size() gives any 32-bit value, and the sign bit
  // below any negative x / y.
  u.x = static_cast<int32_t>(in.size()) * (in.flag() ? -1 : 1);
  u.y = static_cast<int32_t>(in.size()) * (in.flag() ? -1 : 1);
  u.width = in.size();
  u.height = in.size();
  u.data = gridValues(in, static_cast<uint64_t>(u.width) * u.height, 1u << 16);
  return u;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  FuzzDecoder in(data, size);
  ParamValue params = ParamValue::makeMap();
  const uint8_t bits = in.u8();
  params.set("first_map_only", ParamValue::makeBool(bits & 1));
  params.set("subscribe_to_updates", ParamValue::makeBool((bits & 2) == 0));
  params.set("use_maximum", ParamValue::makeBool(bits & 4));
  params.set("trinary_costmap", ParamValue::makeBool(bits & 8));
  params.set("track_unknown_space", ParamValue::makeBool(bits & 16));
  const bool rolling = bits & 32;
  const bool with_inflation = bits & 64;
  params.set("lethal_cost_threshold", ParamValue::makeInt(static_cast<int8_t>(in.u8())));
  params.set("unknown_cost_value", ParamValue::makeInt(static_cast<int8_t>(in.u8())));
  const MasterGeometry g = MasterGeometry::decode(in);

  LayeredCostmap lc("map", rolling, (bits & 128) != 0);
  lc.resizeMap(g.w, g.h, g.res, g.ox, g.oy);
  auto ctx = std::make_shared<FuzzContext>(params);
  ctx->transforms[{"odom", "map"}] = Transform2D{finiteReal(in), finiteReal(in), finiteReal(in)};
  auto layer = std::make_shared<StaticLayer>();
  layer->initialize(&lc, "static_layer", ctx);
  ctx->bind(*layer);
  lc.addPlugin(layer);
  if (with_inflation)
  {
    ParamValue ip = ParamValue::makeMap();
    ip.set("inflation_radius", ParamValue::makeDouble(in.small(0, 40) / 16.0));
    ip.set("cost_scaling_factor", ParamValue::makeDouble(in.small(0, 100) / 4.0));
    auto inflation = std::make_shared<InflationLayer>();
    inflation->initialize(&lc, "inflation", std::make_shared<FuzzContext>(ip));
    lc.addPlugin(inflation);
    inflation->matchSize();
  }
  lc.setFootprint(makeFootprintFromRadius(0.3));

  std::shared_ptr<const OccupancyGridData> in_force;  // the map the master must match (fixed costmap)
  for (int op = 0; op < 8 && !in.empty(); ++op)
  {
    switch (in.u8() % 4)
    {
      case 0:
      {
        auto map = std::make_shared<const OccupancyGridData>(decodeGrid(in));
        const std::string err = layer->setMap(map);
        FUZZ_CHECK(err.empty() == validateGrid(*map).ok(), "setMap and validateGrid disagree");
        if (err.empty() && !(layer->config().first_map_only && in_force)) in_force = map;
        break;
      }
      case 1:
        ctx->publishGridUpdate(decodeUpdate(in));
        break;
      default:
      {
        double x, y, yaw;
        decodePose(in, x, y, yaw);
        lc.updateMap(x, y, yaw);
        const Costmap2D& m = lc.getCostmap();
        if (rolling || !in_force)
          checkMasterUnchanged(lc, g.w, g.h, g.res);
        else
        {
          FUZZ_CHECK(m.getSizeInCellsX() == in_force->width && m.getSizeInCellsY() == in_force->height,
                     "a fixed costmap takes the size of the map in force");
          FUZZ_CHECK(m.getResolution() == in_force->resolution, "a fixed costmap takes the map's resolution");
        }
        break;
      }
    }
  }
  return 0;
}
