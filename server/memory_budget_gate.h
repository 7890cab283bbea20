// A job's share of the server's memory budget (memory_budget.h), reserved as the pipeline
// asks: the grid's estimate before it is allocated, the surface's once the membrane is known
// (the larger of the two is the job's peak: the share grows to it, never by their sum).
#ifndef MEMBRANE_SERVER_MEMORY_BUDGET_GATE_H_
#define MEMBRANE_SERVER_MEMORY_BUDGET_GATE_H_

#include "core/pipeline/resource_gate.h"
#include "server/memory_budget.h"

namespace membrane::server {

class MemoryBudgetGate : public ResourceGate {
 public:
  // `budget` (not owned) must outlive the gate. The share is held until the gate is
  // destroyed: keep it until the job has ended. `output_quantization_bits` is the job's Draco
  // encoding's (0: none): the encoder's tables join the surface's share (SurfacePeakBytes).
  MemoryBudgetGate(MemoryBudget& budget, int output_quantization_bits)
      : budget_(budget), share_(budget), output_quantization_bits_(output_quantization_bits) {}

  // Adds the grid's bytes to the share (MemoryBudget::Share::Add: waits while other jobs hold
  // the memory; its ResourceExhausted and Cancelled as they are, but that a grid over the
  // whole budget is told which voxel_size fits: "...; use a larger voxel_size: S or larger
  // fits", S being SmallestVoxelSizeWithin the budget).
  absl::Status AdmitGrid(const PlannedGrid& grid, int64_t points,
                         const CancelToken& cancel) override;

  // Grows the share to SurfacePeakBytes (the surface's bytes, which count the grid held
  // beside it, when they are above the grid's, plus the Draco encoder's tables); a
  // ResourceExhausted then begins "the surface of a membrane of N voxels (a noisy cloud makes a
  // foam of one): ".
  absl::Status AdmitSurface(const MembraneCounts& membrane, const CancelToken& cancel) override;

 private:
  MemoryBudget& budget_;
  MemoryBudget::Share share_;
  const int output_quantization_bits_;
  PlannedGrid grid_;  // admitted by AdmitGrid
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_MEMORY_BUDGET_GATE_H_
