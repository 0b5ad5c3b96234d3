// Fuzzes map_server map files: the YAML (io::parseMapFileInfo, what loadMapFileInfo reads) and the
// image bytes (io::decodeMapImage: binary and ASCII PGM/PPM, PNG through libpng), in memory. A
// decoded map then goes to a StaticLayer on a fixed costmap and one update cycle runs.
// Input: one byte (bit 0: use the YAML's info, else a fixed valid info; bits 1-2: map mode), a 2-byte
// YAML length, the YAML text, then the image bytes (everything left).
// Invariants: a decoded map passes validateGrid; its values follow the mode (trinary: -1/0/100;
// scale and nav2_scale: -1..100; raw: anything); the master takes its size.
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include "costmap_layers/core/filters/costmap_filter.hpp"
#include "costmap_layers/core/layers/static_layer.hpp"
#include "costmap_layers/io/map_file.hpp"
#include "fuzz_common.hpp"

using namespace costmap_layers;
using namespace costmap_layers_fuzz;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  FuzzDecoder in(data, size);
  const uint8_t bits = in.u8();
  const std::size_t yaml_len = in.u16();
  const std::vector<uint8_t> yaml_bytes = in.bytes(yaml_len);
  const std::vector<uint8_t> image = in.rest();

  io::MapFileInfo info;
  info.resolution = 0.05;
  if (bits & 1)
  {
    try
    {
      info = io::parseMapFileInfo(std::string(yaml_bytes.begin(), yaml_bytes.end()), "/maps/fuzz.yaml");
    }
    catch (const std::runtime_error&)
    {
      return 0;
    }
    FUZZ_CHECK(!info.image_path.empty(), "an accepted YAML names an image");
  }
  static const io::MapMode kModes[] = {io::MapMode::Trinary, io::MapMode::Scale, io::MapMode::Raw,
                                       io::MapMode::Nav2Scale};
  if (bits & 2) info.mode = kModes[(bits >> 2) & 3];

  OccupancyGridData map;
  try
  {
    map = io::decodeMapImage(image, info, "fuzz.img");
  }
  catch (const std::runtime_error&)
  {
    return 0;
  }
  FUZZ_CHECK(validateGrid(map).ok(), "a decoded map is a valid grid");
  for (int8_t v : map.data)
  {
    if (info.mode == io::MapMode::Trinary) FUZZ_CHECK(v == -1 || v == 0 || v == 100, "trinary values");
    if (info.mode == io::MapMode::Scale || info.mode == io::MapMode::Nav2Scale)
      FUZZ_CHECK(v >= -1 && v <= 100, "scale values");
  }

  // Into a StaticLayer on a fixed costmap, as costmap_tool and the node do with a map file. Large
  // maps are checked above but not drawn (time per input).
  if (static_cast<uint64_t>(map.width) * map.height > (1u << 16)) return 0;
  LayeredCostmap lc("map", false, (bits & 16) != 0);
  lc.resizeMap(1, 1, 1.0, 0.0, 0.0);
  auto ctx = std::make_shared<FuzzContext>();
  auto layer = std::make_shared<StaticLayer>();
  layer->initialize(&lc, "static_layer", ctx);
  ctx->bind(*layer);
  lc.addPlugin(layer);
  FUZZ_CHECK(layer->setMap(std::make_shared<const OccupancyGridData>(map)).empty(), "a decoded map is accepted");
  lc.updateMap(0, 0, 0);
  FUZZ_CHECK(lc.getCostmap().getSizeInCellsX() == map.width && lc.getCostmap().getSizeInCellsY() == map.height,
             "the master takes the map's size");
  return 0;
}
