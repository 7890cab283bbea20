// How many threads a reconstruction may use: the bound every entry point checks against, and
// the default when nobody says (`membrane reconstruct --threads 0`, membraned's cores).
#ifndef MEMBRANE_CORE_PIPELINE_THREAD_LIMITS_H_
#define MEMBRANE_CORE_PIPELINE_THREAD_LIMITS_H_

#include <algorithm>
#include <thread>

namespace membrane {

inline constexpr int kMaxReconstructionThreads = 256;

// The machine's cores as std::thread::hardware_concurrency() counts them (0, "unknown", counts
// as 1), at most kMaxReconstructionThreads. On a container that is the node's count, not the
// container's CPU limit: deployments there set their counts explicitly.
inline int MachineThreads() {
  return static_cast<int>(
      std::clamp<unsigned>(std::thread::hardware_concurrency(), 1, kMaxReconstructionThreads));
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_THREAD_LIMITS_H_
