// The rules of a costmap filter info (Nav2's CostmapFilterInfo; here costmap_layers/CostmapFilterInfo,
// published by costmap_filter_info_server): what its type means, and which infos a filter can use.
//
// type  meaning (Nav2's filter_values.hpp)              filters here that take it
//  0    keepout / preferred lanes                        KeepoutFilter, LanesFilter
//  1    speed limit in percent of the robot's maximum    SpeedFilter
//  2    speed limit in m/s                               SpeedFilter
//  3    binary filter                                    BinaryFilter
//  4    zone parameters (Nav2's ZONE_PARAMETER_FILTER)   ZoneParameterFilter
// Every other value is invalid.
//
// A mask value v maps to the filter's quantity as base + multiplier * v (Nav2's rule). The keepout
// and lanes filters use the mask values as they are: Nav2's KeepoutFilter expects base 0 and
// multiplier 1 and only complains otherwise; so do the filters here (a warning, the info is used).
#pragma once

#include <cstdint>
#include <string>

#include "costmap_layers/core/data/grid_data.hpp"
#include "costmap_layers/core/config/input_error.hpp"

namespace costmap_layers
{
namespace filter_info
{
constexpr uint8_t kKeepout = 0;
constexpr uint8_t kSpeedPercent = 1;
constexpr uint8_t kSpeedAbsolute = 2;
constexpr uint8_t kBinary = 3;
constexpr uint8_t kZoneParameter = 4;
constexpr double kBaseDefault = 0.0;
constexpr double kMultiplierDefault = 1.0;
}  // namespace filter_info

/// "keepout/lanes", "speed limit in percent", "speed limit in m/s", "binary", "zone parameters", or
/// "unknown".
const char* filterInfoTypeName(int type);

/// Whether `type` is one of the five types above.
bool isKnownFilterInfoType(int type);

/// The checks every filter makes of an info, whatever its type: filter_mask_topic not empty, at most
/// 1024 characters and a valid-looking topic name (no blanks or control characters), base and
/// multiplier finite, type known.
/// @return ok() when usable, else the field at fault ("type", "filter_mask_topic", "base",
///         "multiplier") and one line naming it and its value.
InputError validateFilterInfo(const FilterInfoData& info);

/// validateFilterInfo() plus what a filter of the given kind accepts: keepout/lanes filters take
/// type 0 only, the speed filter types 1 and 2, the binary filter type 3, the zone parameter filter
/// type 4 (other types are an error naming the type and the filter the info is meant for).
enum class FilterFamily
{
  Keepout,       ///< KeepoutFilter, LanesFilter
  Speed,         ///< SpeedFilter
  Binary,        ///< BinaryFilter (type 3)
  ZoneParameter  ///< ZoneParameterFilter (type 4)
};
InputError checkFilterInfoFor(FilterFamily family, const FilterInfoData& info);
}  // namespace costmap_layers
