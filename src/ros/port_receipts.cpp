#include "costmap_layers/ros/port_receipts.hpp"

#include <ros/time.h>

#include <algorithm>
#include <cstdio>

namespace costmap_layers_ros
{
void PortReceipts::note()
{
  count.fetch_add(1);
  // Arrival on the steady clock: the age shown is real time since the message came, also under
  // /use_sim_time or after a clock jump (ROS time behind the last arrival would read 0 s for as long).
  last.store(ros::SteadyTime::now().toSec());
}

std::string receiptText(uint64_t count, double last, double now)
{
  char text[96];
  if (count == 0)
    std::snprintf(text, sizeof(text), "nothing yet");
  else
    std::snprintf(text, sizeof(text), "%llu message(s), last %.2f s ago", static_cast<unsigned long long>(count),
                  std::max(0.0, now - last));
  return text;
}
}  // namespace costmap_layers_ros
