#include "server/memory_budget_gate.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/pipeline/memory_estimate.h"

namespace membrane::server {

absl::Status MemoryBudgetGate::AdmitGrid(const PlannedGrid& grid, int64_t /*points*/,
                                         const CancelToken& cancel) {
  grid_ = grid;
  absl::Status admission = share_.Add(grid.bytes, cancel);
  if (!absl::IsResourceExhausted(admission) || grid.bytes <= budget_.total()) return admission;
  const double fitting = SmallestVoxelSizeWithin(grid, budget_.total());
  if (fitting <= 0) return admission;
  return absl::ResourceExhaustedError(
      absl::StrFormat("%s: %.3g or larger fits", admission.message(), fitting));
}

absl::Status MemoryBudgetGate::AdmitSurface(const MembraneCounts& membrane,
                                            const CancelToken& cancel) {
  // The share holds the grid's peak already.
  const int64_t more =
      SurfacePeakBytes(grid_, membrane, output_quantization_bits_) - grid_.bytes;
  absl::Status admission = share_.Add(more, cancel);
  if (!absl::IsResourceExhausted(admission)) return admission;
  return absl::ResourceExhaustedError(absl::StrCat("the surface of a membrane of ",
                                                   membrane.membrane_voxels(),
                                                   " voxels (a noisy cloud makes a foam of "
                                                   "one): ",
                                                   admission.message()));
}

}  // namespace membrane::server
