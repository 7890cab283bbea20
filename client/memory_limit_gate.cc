#include "client/memory_limit_gate.h"

#include <string>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/pipeline/memory_estimate.h"

namespace membrane::client {
namespace {

// ResourceExhausted when `bytes` are over `limit` (> 0): "<who_needs> about <bytes><purpose>,
// over the memory limit of <limit> (...)<advice>".
absl::Status CheckMemoryLimit(int64_t bytes, int64_t limit, const std::string& who_needs,
                              const std::string& purpose, const char* advice) {
  if (limit <= 0 || bytes <= limit) return absl::OkStatus();
  return absl::ResourceExhaustedError(absl::StrCat(
      who_needs, " about ", BytesText(bytes), purpose, ", over the memory limit of ",
      BytesText(limit), " (--memory-limit, by default the memory available)", advice));
}

}  // namespace

absl::Status MemoryLimitGate::AdmitGrid(const PlannedGrid& grid, int64_t points,
                                        const CancelToken& /*cancel*/) {
  grid_ = grid;
  if (limit_ <= 0 || grid.bytes <= limit_) return absl::OkStatus();
  const double fitting = SmallestVoxelSizeWithin(grid, limit_);
  const std::string advice =
      fitting > 0 ? absl::StrFormat("; --voxel-size %.3g or larger fits (%.2f times this grid's)",
                                    fitting, fitting / grid.voxel_size)
                  : std::string("; use a larger --voxel-size");
  return CheckMemoryLimit(
      grid.bytes, limit_,
      absl::StrFormat("the grid of %d voxels and the %d points need", grid.voxels, points), "",
      advice.c_str());
}

absl::Status MemoryLimitGate::AdmitSurface(const MembraneCounts& membrane,
                                           const CancelToken& /*cancel*/) {
  const int64_t tables = DracoTableBytes(output_quantization_bits_);
  const std::string purpose =
      tables == 0 ? std::string(" for its surface and the grid")
                  : absl::StrCat(" for its surface, the grid and the Draco encoder's tables (",
                                 BytesText(tables), " at ", output_quantization_bits_,
                                 " bits: fewer --quantization bits take less)");
  return CheckMemoryLimit(
      SurfacePeakBytes(grid_, membrane, output_quantization_bits_), limit_,
      absl::StrFormat("the membrane (%d voxels) needs", membrane.membrane_voxels()), purpose,
      "; noise makes a foam of a membrane: is this the scan of one object?");
}

}  // namespace membrane::client
