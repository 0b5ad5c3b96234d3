#include "costmap_layers/core/kernels/simd_targets.hpp"

#include <atomic>

#include <hwy/highway.h>
#include <hwy/targets.h>

namespace costmap_layers
{
namespace
{
/// The forced target (a single Highway target bit), or 0 for the automatic choice.
std::atomic<int64_t> g_forced{0};

/// The targets compiled (HWY_TARGETS, with the same definitions as every kernel file) and supported.
int64_t available()
{
  return hwy::SupportedTargets() & HWY_TARGETS;
}
}  // namespace

std::vector<std::string> simdTargets()
{
  const int64_t forced = g_forced.load();
  if (forced != 0) hwy::SetSupportedTargetsForTest(0);  // list what the CPU runs, not the restriction
  std::vector<std::string> names;
  // Lower bits are better targets in Highway's numbering.
  for (int64_t targets = available(); targets != 0; targets &= targets - 1)
    names.emplace_back(hwy::TargetName(targets & -targets));
  if (forced != 0) hwy::SetSupportedTargetsForTest(forced);
  return names;
}

bool setSimdTarget(const std::string& name)
{
  if (name.empty())
  {
    g_forced = 0;
    hwy::SetSupportedTargetsForTest(0);
    return true;
  }
  hwy::SetSupportedTargetsForTest(0);
  for (int64_t targets = available(); targets != 0; targets &= targets - 1)
  {
    const int64_t t = targets & -targets;
    if (name == hwy::TargetName(t))
    {
      g_forced = t;
      hwy::SetSupportedTargetsForTest(t);
      return true;
    }
  }
  if (g_forced.load() != 0) hwy::SetSupportedTargetsForTest(g_forced.load());
  return false;
}

std::string simdTarget()
{
  const int64_t targets = available();
  return targets != 0 ? hwy::TargetName(targets & -targets) : "none";
}
}  // namespace costmap_layers
