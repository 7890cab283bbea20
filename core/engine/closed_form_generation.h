// Closed-form generations for big plates (fast-shrink.md section 4).
//
// When no incursion and no guard refusal happens in a generation, its result does not depend
// on the order of the chains: it is the least fixed point of "a plate with no hard or frozen
// cell and an all-outside back side becomes outside". That fixed point is computed here with
// word operations on bit-planes, then checked: the incursion test on every hard or frozen
// voxel next to a new outside voxel, and the topology guard on every new outside voxel next to
// a hard one. If any check fails the grid is restored and the caller runs the chains.
#ifndef MEMBRANE_CORE_ENGINE_CLOSED_FORM_GENERATION_H_
#define MEMBRANE_CORE_ENGINE_CLOSED_FORM_GENERATION_H_

#include <cstdint>

#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/engine/contraction.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/voxel_grid.h"
#include "core/engine/work_planes.h"

namespace membrane {

struct ClosedFormOutcome {
  bool applied = false;        // false: rejected by a check, the grid is as it was
  int64_t new_outside = 0;     // voxels the fixed point turned outside
  int64_t incursions = 0;      // hard or frozen voxels where the incursion test fired
  int64_t guard_refusals = 0;  // new outside voxels the topology guard refused
  int rounds = 0;              // rounds of the sweeps (three axes, both fronts at once)
  int64_t checks = 0;          // incursion and guard tests run on the result
  bool voxelwise = false;      // applied (and checked) voxel by voxel: few new outside voxels
};

// Work planes a closed-form generation uses (see RunClosedFormGeneration).
inline constexpr int kClosedFormPlanes = 8;

// Runs generation `options` (plate size, label, guard and incursion settings) in closed form
// on `grid`. On success the grid is the generation's result, the same as the chains would
// give (every new outside voxel has generation options.generation_label; inside voxels next to
// them became boundary). Cancelled when `cancel` fires (the grid is then restored).
// `planes` must have been made for this grid; the first kClosedFormPlanes of them are
// overwritten. A result of at most `voxelwise_max` new outside voxels is applied and checked
// voxel by voxel, a larger one by whole-grid planes: the same grid and outcome either way.
absl::StatusOr<ClosedFormOutcome> RunClosedFormGeneration(VoxelGrid& grid,
                                                          const ChainOptions& options,
                                                          int64_t voxelwise_max,
                                                          const CancelToken& cancel,
                                                          WorkPlanes& planes);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_CLOSED_FORM_GENERATION_H_
