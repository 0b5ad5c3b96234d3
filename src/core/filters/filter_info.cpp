#include "costmap_layers/core/filters/filter_info.hpp"

#include <cctype>
#include <cmath>
#include <sstream>

namespace costmap_layers
{
const char* filterInfoTypeName(int type)
{
  switch (type)
  {
    case filter_info::kKeepout:
      return "keepout/lanes";
    case filter_info::kSpeedPercent:
      return "speed limit in percent";
    case filter_info::kSpeedAbsolute:
      return "speed limit in m/s";
    case filter_info::kBinary:
      return "binary";
    case filter_info::kZoneParameter:
      return "zone parameters";
    default:
      return "unknown";
  }
}

bool isKnownFilterInfoType(int type)
{
  return type >= filter_info::kKeepout && type <= filter_info::kZoneParameter;
}

InputError validateFilterInfo(const FilterInfoData& info)
{
  std::ostringstream err;
  if (!isKnownFilterInfoType(info.type))
  {
    err << "type must be 0 (keepout/lanes), 1 (speed limit in percent), 2 (speed limit in m/s), 3 (binary) or 4 "
           "(zone parameters) (got "
        << static_cast<int>(info.type) << ")";
    return InputError::of("type", err.str());
  }
  if (info.filter_mask_topic.empty()) return InputError::of("filter_mask_topic", "filter_mask_topic is empty");
  constexpr std::size_t kMaxTopicLength = 1024;  // it is printed in reports
  if (info.filter_mask_topic.size() > kMaxTopicLength)
    return InputError::of("filter_mask_topic", "filter_mask_topic is " + std::to_string(info.filter_mask_topic.size()) +
                                                   " characters long, more than " + std::to_string(kMaxTopicLength));
  for (const char c : info.filter_mask_topic)
    if (std::isspace(static_cast<unsigned char>(c)) || std::iscntrl(static_cast<unsigned char>(c)))
    {
      // The topic is printed in the message: keep it to printable characters.
      std::string shown;
      for (const char d : info.filter_mask_topic)
        shown += std::isprint(static_cast<unsigned char>(d)) && d != ' ' ? d : '?';
      return InputError::of("filter_mask_topic", "filter_mask_topic '" + shown.substr(0, 200) +
                                                     "' is not a topic name (blank or control characters)");
    }
  // ROS's name rule (roscpp would refuse any other name, after the info is in force); '~' (a private
  // name) is refused too: it would be the filter node's own namespace, not the sender's.
  const std::string problem = rosNameProblem(info.filter_mask_topic, false);
  if (!problem.empty()) return InputError::of("filter_mask_topic", "filter_mask_topic " + problem);
  if (!std::isfinite(info.base))
  {
    err << "base must be a finite number (got " << info.base << ")";
    return InputError::of("base", err.str());
  }
  if (!std::isfinite(info.multiplier))
  {
    err << "multiplier must be a finite number (got " << info.multiplier << ")";
    return InputError::of("multiplier", err.str());
  }
  return InputError::none();
}

InputError checkFilterInfoFor(FilterFamily family, const FilterInfoData& info)
{
  InputError error = validateFilterInfo(info);
  if (!error.ok()) return error;
  const int type = info.type;
  std::ostringstream err;
  if (family == FilterFamily::Keepout && type != filter_info::kKeepout)
  {
    err << "type " << type << " (" << filterInfoTypeName(type) << ") is not for this filter: a keepout or lanes "
        << "filter takes type 0" << (type == filter_info::kBinary ? " (type 3 is for a BinaryFilter)" : "");
    return InputError::of("type", err.str());
  }
  if (family == FilterFamily::Speed && type != filter_info::kSpeedPercent && type != filter_info::kSpeedAbsolute)
  {
    err << "type " << type << " (" << filterInfoTypeName(type) << ") is not for this filter: a speed filter takes "
        << "type 1 (percent) or 2 (m/s)" << (type == filter_info::kBinary ? " (type 3 is for a BinaryFilter)" : "");
    return InputError::of("type", err.str());
  }
  if (family == FilterFamily::Binary && type != filter_info::kBinary)
  {
    err << "type " << type << " (" << filterInfoTypeName(type) << ") is not for this filter: a binary filter takes "
        << "type 3";
    return InputError::of("type", err.str());
  }
  if (family == FilterFamily::ZoneParameter && type != filter_info::kZoneParameter)
  {
    err << "type " << type << " (" << filterInfoTypeName(type) << ") is not for this filter: a zone parameter "
        << "filter takes type 4";
    return InputError::of("type", err.str());
  }
  return InputError::none();
}
}  // namespace costmap_layers
