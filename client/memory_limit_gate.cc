#include "client/memory_limit_gate.h"

#include <string>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace membrane::client {
namespace {

// ResourceExhausted when `bytes` are over `limit` (> 0): "<who_needs> about <bytes><purpose>,
// over the memory limit of <limit> (...)<advice>".
absl::Status CheckMemoryLimit(int64_t bytes, int64_t limit, const std::string& who_needs,
                              const char* purpose, const char* advice) {
  if (limit <= 0 || bytes <= limit) return absl::OkStatus();
  return absl::ResourceExhaustedError(absl::StrCat(
      who_needs, " about ", BytesText(bytes), purpose, ", over the memory limit of ",
      BytesText(limit), " (--memory-limit, by default the memory available)", advice));
}

}  // namespace

absl::Status MemoryLimitGate::AdmitGrid(const PlannedGrid& grid, int64_t points,
                                        const CancelToken& /*cancel*/) {
  grid_ = grid;
  return CheckMemoryLimit(
      grid.bytes, limit_,
      absl::StrFormat("the grid of %d voxels and the %d points need", grid.voxels, points), "",
      "; use a larger --voxel-size");
}

absl::Status MemoryLimitGate::AdmitSurface(const MembraneCounts& membrane,
                                           const CancelToken& /*cancel*/) {
  return CheckMemoryLimit(
      SurfaceBytesEstimate(grid_, membrane), limit_,
      absl::StrFormat("the membrane (%d voxels) needs", membrane.membrane_voxels()),
      " for its surface and the grid",
      "; noise makes a foam of a membrane: is this the scan of one object?");
}

}  // namespace membrane::client
