#include "server/memory_budget_gate.h"

#include <algorithm>

#include "absl/strings/str_cat.h"

namespace membrane::server {

int64_t DracoTableBytes(int quantization_bits) {
  if (quantization_bits <= 0) return 0;
  return int64_t{4} << std::min(quantization_bits, 30);
}

absl::Status MemoryBudgetGate::AdmitGrid(const PlannedGrid& grid, int64_t /*points*/,
                                         const CancelToken& cancel) {
  grid_ = grid;
  return share_.Add(grid.bytes, cancel);
}

absl::Status MemoryBudgetGate::AdmitSurface(const MembraneCounts& membrane,
                                            const CancelToken& cancel) {
  // The share holds the grid's peak already; the surface's estimate counts the grid too.
  const int64_t more =
      std::max<int64_t>(SurfaceBytesEstimate(grid_, membrane) - grid_.bytes, 0) +
      DracoTableBytes(output_quantization_bits_);
  absl::Status admission = share_.Add(more, cancel);
  if (!absl::IsResourceExhausted(admission)) return admission;
  return absl::ResourceExhaustedError(absl::StrCat("the surface of a membrane of ",
                                                   membrane.membrane_voxels(),
                                                   " voxels (a noisy cloud makes a foam of "
                                                   "one): ",
                                                   admission.message()));
}

}  // namespace membrane::server
