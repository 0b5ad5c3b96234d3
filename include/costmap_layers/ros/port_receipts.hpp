// What arrived on a subscribed topic, for /diagnostics: counted when a message arrives (before tf or
// validation), so that "nothing arrives" and "everything arriving is dropped" read differently.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>

namespace costmap_layers_ros
{
/// How many messages arrived on a topic and when (ros::SteadyTime, seconds; 0 = never). Any thread.
struct PortReceipts
{
  std::atomic<uint64_t> count{0};
  std::atomic<double> last{0.0};
  /// One more message, now (steady clock).
  void note();
};

/// The diagnostics text of a topic's receipts: "nothing yet" when count is 0, else
/// "N message(s), last X s ago" with X = now - last [s] (never below 0), two decimals.
std::string receiptText(uint64_t count, double last, double now);
}  // namespace costmap_layers_ros
