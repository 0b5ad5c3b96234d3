// rosrun costmap_layers costmap_filter_info_server _type:=1 _mask_topic:=/speed_filter_mask _base:=100.0
//     _multiplier:=-1.0 [_filter_info_topic:=/costmap_filter_info]
// Publishes, latched, one costmap_layers/CostmapFilterInfo built from its parameters: what Nav2's
// costmap_filter_info_server does, with the same parameter names and defaults, for filters configured
// with filter_info_topic. Nav2's parameter file (without its `ros__parameters:` level) loads unchanged:
// at the launch file's top level, or with ns="costmap_filter_info_server" (see node_params.hpp).
//
// Parameters (checked; a bad one ends the node with exit code 1 and a message naming it and its value):
//   type               0                      0 keepout/lanes, 1 speed in percent, 2 speed in m/s, 3 binary
//   filter_info_topic  "costmap_filter_info"  where the info is published
//   mask_topic         "filter_mask"          the mask topic the info names
//   base               0.0                    a mask value v means base + multiplier * v (float32 in the message)
//   multiplier         1.0
#include <ros/ros.h>

#include <cfloat>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "costmap_layers/CostmapFilterInfo.h"
#include "costmap_layers/core/filters/filter_info.hpp"
#include "costmap_layers/ros/node_params.hpp"
#include "costmap_layers/ros/program_main.hpp"

namespace
{
const char* kNode = "costmap_filter_info_server";

float checkFloat32(const costmap_layers_ros::NodeParams& params, const std::string& name, double def)
{
  const double v = params.getDouble(name, def);
  if (std::fabs(v) > FLT_MAX)
    throw std::invalid_argument("parameter " + params.where() + name + " does not fit the message's float32 (got " +
                                std::to_string(v) + ")");
  const float f = static_cast<float>(v);
  if (static_cast<double>(f) != v)
    ROS_WARN("%s: parameter %s%s = %.17g is sent as the float32 %.9g [%s/%s]", kNode, params.where().c_str(),
             name.c_str(), v, static_cast<double>(f), kNode, name.c_str());
  return f;
}

/// Warnings about a configuration that is valid but will not do what it seems to.
void warnAboutMeaning(const costmap_layers::FilterInfoData& info, const std::string& where)
{
  namespace fi = costmap_layers::filter_info;
  if ((info.type == fi::kKeepout || info.type == fi::kBinary || info.type == fi::kZoneParameter) &&
      (info.base != fi::kBaseDefault || info.multiplier != fi::kMultiplierDefault))
    ROS_WARN(
        "%s: type %d (%s) with %sbase %g and multiplier %g: keepout, lanes and zone parameter filters read mask "
        "values as they are and ignore both (Nav2 expects 0 and 1) [%s/base]",
        kNode, info.type, costmap_layers::filterInfoTypeName(info.type), where.c_str(), info.base, info.multiplier,
        kNode);
  if (info.type == fi::kSpeedPercent || info.type == fi::kSpeedAbsolute)
  {
    // Nav2's rule per mask value 1..100: percent outside [0, 100], or m/s below 0, is "no limit".
    int first_bad = 0, last_bad = 0, bad = 0;
    for (int v = 1; v <= 100; ++v)
    {
      const double limit = info.base + info.multiplier * v;
      const bool ok = info.type == fi::kSpeedPercent ? limit >= 0.0 && limit <= 100.0 : limit >= 0.0;
      if (ok) continue;
      if (bad++ == 0) first_bad = v;
      last_bad = v;
    }
    if (bad == 100)
      ROS_WARN(
          "%s: with base %g and multiplier %g no mask value 1..100 gives a limit %s: every zone means no limit "
          "[%s/multiplier]",
          kNode, info.base, info.multiplier, info.type == fi::kSpeedPercent ? "in [0, 100] %" : ">= 0 m/s", kNode);
    else if (bad > 0)
      ROS_WARN(
          "%s: with base %g and multiplier %g, %d mask values in %d..%d give a limit %s, which the speed filter "
          "replaces by no limit [%s/multiplier]",
          kNode, info.base, info.multiplier, bad, first_bad, last_bad,
          info.type == fi::kSpeedPercent ? "outside [0, 100] %" : "below 0 m/s", kNode);
  }
}

int run()
{
  ros::NodeHandle nh, pnh("~");
  costmap_layers::FilterInfoData info;
  std::string info_topic;
  {
    const costmap_layers_ros::NodeParams params(pnh);
    if (params.nested())
      ROS_INFO("%s: reading the parameters under %s [%s/namespace]", kNode, params.where().c_str(), kNode);
    params.warnUseSimTime(kNode, kNode);
    const std::vector<std::string> known = {"type", "filter_info_topic", "mask_topic", "base", "multiplier"};
    if (!params.hasAny(known))
      ROS_WARN(
          "%s: none of type, filter_info_topic, mask_topic, base, multiplier is set in %s: publishing the "
          "defaults (type 0, mask filter_mask on costmap_filter_info) [%s/parameters]",
          kNode, params.where().c_str(), kNode);
    for (const auto& key : params.unknownKeys(known))
      ROS_WARN(
          "%s: parameter %s%s is not one of type, filter_info_topic, mask_topic, base, multiplier: ignored "
          "[%s/unknown]",
          kNode, params.where().c_str(), key.c_str(), kNode);
    const int type = params.getInt("type", 0);
    if (!costmap_layers::isKnownFilterInfoType(type))
      throw std::invalid_argument("parameter " + params.where() + "type must be 0 (keepout/lanes), 1 (speed limit in " +
                                  "percent), 2 (speed limit in m/s), 3 (binary) or 4 (zone parameters) (got " +
                                  std::to_string(type) + ")");
    info.type = static_cast<uint8_t>(type);
    info_topic = params.getTopic("filter_info_topic", "costmap_filter_info");
    // The filters' own rule for the mask topic they are told (a '~private' name is refused there: it
    // would be the filter's namespace, not this node's), checked here where the value is set.
    info.filter_mask_topic = params.getTopic("mask_topic", "filter_mask", false);
    info.base = checkFloat32(params, "base", 0.0);
    info.multiplier = checkFloat32(params, "multiplier", 1.0);
    if (const costmap_layers::InputError e = costmap_layers::validateFilterInfo(info); !e.ok())
      throw std::invalid_argument("parameters in " + params.where() +
                                  " make an info every filter refuses: " + e.message);
    warnAboutMeaning(info, params.where());
  }
  costmap_layers::CostmapFilterInfo msg;
  msg.header.stamp = ros::Time::now();
  msg.type = info.type;
  msg.filter_mask_topic = info.filter_mask_topic;
  msg.base = static_cast<float>(info.base);
  msg.multiplier = static_cast<float>(info.multiplier);
  ros::Publisher pub = nh.advertise<costmap_layers::CostmapFilterInfo>(info_topic, 1, true);
  pub.publish(msg);
  ROS_INFO("%s: publishing on %s: type %d (%s), mask %s, value = %g + %g * mask value [%s/published]", kNode,
           pub.getTopic().c_str(), info.type, costmap_layers::filterInfoTypeName(info.type),
           info.filter_mask_topic.c_str(), info.base, info.multiplier, kNode);
  ros::spin();
  return 0;
}
}  // namespace

int main(int argc, char** argv)
{
  return costmap_layers_ros::runProgram(argc, argv, kNode, [] { return run(); });
}
