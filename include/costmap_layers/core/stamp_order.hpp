// Whether a map, mask or speed-limit message arrived out of order. Latched topics re-send their last
// message on every reconnection, and a second publisher (an old map server left running) can send an
// older grid after a newer one: applying it would silently roll the costmap back.
#pragma once

#include <cstdint>
#include <string>

namespace costmap_layers
{
/// True when a message stamped stamp_ns is older than the one in force (stamped in_force_ns) and must
/// be dropped. A zero stamp on either side carries no time and never makes a message stale. When the
/// clock went back below the stamp in force (a restarted simulation, a looping bag: now_ns < in_force_ns),
/// every message is accepted, or nothing would ever be accepted again.
inline bool isOutOfOrder(uint64_t stamp_ns, uint64_t in_force_ns, uint64_t now_ns)
{
  return stamp_ns != 0 && in_force_ns != 0 && stamp_ns < in_force_ns && in_force_ns <= now_ns;
}

/// "header.stamp 12.500 s is older than the <what> in force (stamped 20.000 s)": the error a layer
/// reports for an out-of-order message; it starts with the field's name, the key its report is
/// throttled by.
std::string outOfOrderError(uint64_t stamp_ns, uint64_t in_force_ns, const std::string& what);
}  // namespace costmap_layers
