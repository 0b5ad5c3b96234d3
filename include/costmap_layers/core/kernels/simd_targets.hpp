// The SIMD targets of the core's kernels (distance engine, lanes costs, mask gather). They are written
// once with Highway and compiled for every target Highway attains on this architecture (on x86:
// scalar, SSSE3, SSE4, AVX2, AVX-512 -- "AVX3"; on Arm: scalar, NEON, SVE); Highway's dispatcher
// runs the best one this CPU supports. Tests and benchmarks use these functions to run each in turn.
// (Highway stays out of the public headers: these are plain names.)
#pragma once

#include <string>
#include <vector>

namespace costmap_layers
{
/// Highway's names of the targets this build compiled and this CPU runs, best first; the last one is
/// the scalar fallback ("SCALAR" or "EMU128").
std::vector<std::string> simdTargets();
/// Restricts every kernel to one target of simdTargets() (process-wide, for tests and benchmarks);
/// an empty name returns to the automatic choice. Returns false, changing nothing, for another name.
bool setSimdTarget(const std::string& name);
/// The target the kernels run now.
std::string simdTarget();
}  // namespace costmap_layers
