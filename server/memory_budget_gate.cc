#include "server/memory_budget_gate.h"

#include <algorithm>

#include "absl/strings/str_cat.h"

namespace membrane::server {

absl::Status MemoryBudgetGate::AdmitGrid(const PlannedGrid& grid, int64_t /*points*/,
                                         const CancelToken& cancel) {
  grid_ = grid;
  return share_.Add(grid.bytes, cancel);
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
