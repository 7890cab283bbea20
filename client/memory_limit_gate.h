// `membrane reconstruct --local --memory-limit`: a run refused before it allocates more than
// the limit by the core's estimates (core/pipeline/memory_estimate.h), instead of being ended
// by the kernel's OOM killer.
#ifndef MEMBRANE_CLIENT_MEMORY_LIMIT_GATE_H_
#define MEMBRANE_CLIENT_MEMORY_LIMIT_GATE_H_

#include <cstdint>

#include "core/pipeline/resource_gate.h"

namespace membrane::client {

class MemoryLimitGate : public ResourceGate {
 public:
  // `limit_bytes` <= 0: no limit. `output_quantization_bits`: the run's Draco encoding's
  // (ReconstructionOptions; 0 for PLY, OBJ, STL or float32 output), whose tables the surface's
  // check counts as membraned's memory gate does (SurfacePeakBytes).
  MemoryLimitGate(int64_t limit_bytes, int output_quantization_bits)
      : limit_(limit_bytes), output_quantization_bits_(output_quantization_bits) {}

  // ResourceExhausted "the grid of V voxels and the P points need about B, over the memory
  // limit of L (--memory-limit, ...); --voxel-size S or larger fits (R times this grid's)"
  // when the grid's bytes are over the limit (S: SmallestVoxelSizeWithin the limit; "; use a
  // larger --voxel-size" when no size fits). Never waits.
  absl::Status AdmitGrid(const PlannedGrid& grid, int64_t points,
                         const CancelToken& cancel) override;

  // ResourceExhausted "the membrane (N voxels) needs about B for its surface and the grid,
  // over the memory limit ...; noise makes a foam of a membrane: ..." when the stages from the
  // surface on (SurfacePeakBytes: the grid held beside the surface and Draco's tables
  // included) are over the limit; with the tables, the message names them and fewer
  // --quantization bits. Never waits.
  absl::Status AdmitSurface(const MembraneCounts& membrane, const CancelToken& cancel) override;

 private:
  int64_t limit_;
  int output_quantization_bits_;
  PlannedGrid grid_;  // admitted by AdmitGrid
};

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_MEMORY_LIMIT_GATE_H_
