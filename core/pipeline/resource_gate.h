// Who admits a reconstruction's memory before it is taken: `membrane reconstruct --local`'s
// --memory-limit, the server's memory budget shared by its jobs. The pipeline plans the grid
// and asks twice, on the estimates of memory_estimate.h: before the grid is allocated, and
// once the membrane is final, before its surface is built (a noisy cloud's surface can take
// many times its grid's bytes).
#ifndef MEMBRANE_CORE_PIPELINE_RESOURCE_GATE_H_
#define MEMBRANE_CORE_PIPELINE_RESOURCE_GATE_H_

#include <cstdint>

#include "absl/status/status.h"
#include "core/base/cancel_token.h"
#include "core/pipeline/membrane_counts.h"
#include "core/pipeline/memory_estimate.h"

namespace membrane {

// Both calls come on the reconstructing thread, in this order, at most once each per run. A
// non-OK status ends the run as it is (the gate names its limit and what to change). A gate
// may wait for memory others hold; it then returns Cancelled soon after `cancel` fires (the
// server's: within 50 ms). What a gate grants is the run's until the caller destroys the gate.
class ResourceGate {
 public:
  virtual ~ResourceGate() = default;

  // Before the voxel grid and the shrink's working sets are allocated: `grid` as PlanGrid
  // plans it (its bytes count the cloud's `points` too).
  virtual absl::Status AdmitGrid(const PlannedGrid& grid, int64_t points,
                                 const CancelToken& cancel) = 0;

  // Once the membrane is final (relaxed, when the options relax), before the surface is
  // built: `membrane` is its census (the statistics' "membrane"), for SurfaceBytesEstimate.
  // The grid's bytes admitted before are still in use.
  virtual absl::Status AdmitSurface(const MembraneCounts& membrane,
                                    const CancelToken& cancel) = 0;
};

// A gate that admits everything: runs without a memory limit (tests, benchmarks).
class NoResourceLimit : public ResourceGate {
 public:
  absl::Status AdmitGrid(const PlannedGrid&, int64_t, const CancelToken&) override {
    return absl::OkStatus();
  }
  absl::Status AdmitSurface(const MembraneCounts&, const CancelToken&) override {
    return absl::OkStatus();
  }
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_RESOURCE_GATE_H_
