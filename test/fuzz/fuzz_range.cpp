// Fuzzes sensor_msgs/Range readings: interpretRange directly (every input type), then the readings
// through a RangeSensorLayer (the Range subscription -> addRange -> queue -> cone update in
// updateBounds) with fuzzed layer parameters, on a fixed or rolling LayeredCostmap.
// Input: layer parameters, master geometry, then readings (field of view, min/max range, range,
// radiation type, each with 0/NaN/inf/huge values) with their sensor poses, and update cycles.
// Invariants: a reading interpretRange accepts has a finite, non-negative range within max_range;
// the master grid keeps its geometry.
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>

#include "costmap_layers/core/layers/range_sensor_layer.hpp"
#include "fuzz_common.hpp"

using namespace costmap_layers;
using namespace costmap_layers_fuzz;

namespace
{
RangeData decodeRange(FuzzDecoder& in)
{
  RangeData r;
  r.frame_id = "sonar";
  r.radiation_type = in.u8();
  r.field_of_view = in.real32();
  r.min_range = in.real32();
  r.max_range = in.real32();
  r.range = in.real32();
  return r;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  FuzzDecoder in(data, size);
  const uint8_t bits = in.u8();
  const bool rolling = bits & 1;
  ParamValue params = ParamValue::makeMap();
  params.set("topics",
             bits & 2 ? ParamValue::makeString("sonar") : ParamValue::makeList({ParamValue::makeString("sonar")}));
  params.set("phi", ParamValue::makeDouble(in.real()));
  params.set("inflate_cone", ParamValue::makeDouble(in.u8() / 255.0));
  params.set("clear_threshold", ParamValue::makeDouble(in.u8() / 255.0));
  params.set("mark_threshold", ParamValue::makeDouble(in.u8() / 255.0));
  params.set("clear_on_max_reading", ParamValue::makeBool(bits & 4));
  static const char* const kTypes[] = {"ALL", "VARIABLE", "FIXED"};
  params.set("input_sensor_type", ParamValue::makeString(kTypes[in.u8() % 3]));
  const MasterGeometry g = MasterGeometry::decode(in);

  LayeredCostmap lc("map", rolling, (bits & 8) != 0);
  lc.resizeMap(g.w, g.h, g.res, g.ox, g.oy);
  auto ctx = std::make_shared<FuzzContext>(params);
  auto layer = std::make_shared<RangeSensorLayer>();
  try
  {
    layer->initialize(&lc, "range", ctx);
    ctx->bind(*layer);
  }
  catch (const std::invalid_argument&)
  {
    return 0;
  }
  lc.addPlugin(layer);

  for (int op = 0; op < 8 && !in.empty(); ++op)
  {
    if (in.u8() % 3 != 0)
    {
      const RangeData r = decodeRange(in);
      for (RangeInputType type : {RangeInputType::All, RangeInputType::Variable, RangeInputType::Fixed})
        for (bool clear_on_max : {false, true})
        {
          const RangeInterpretation ri = interpretRange(r, type, clear_on_max);
          if (ri.ok() && ri.use)
            FUZZ_CHECK(std::isfinite(ri.range) && ri.range >= 0.0 && ri.range <= r.max_range,
                       "a used reading has a range within [0, max_range]");
        }
      ctx->publishRange("sonar", r, decodeSensorPose(in));
    }
    else
    {
      double x, y, yaw;
      decodePose(in, x, y, yaw);
      ctx->now_ns += in.u32();
      lc.updateMap(x, y, yaw);
      checkMasterUnchanged(lc, g.w, g.h, g.res);
    }
  }
  return 0;
}
