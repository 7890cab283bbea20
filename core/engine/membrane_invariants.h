// The membrane invariants, checkable from tests (paper section 4.4).
#ifndef MEMBRANE_CORE_ENGINE_MEMBRANE_INVARIANTS_H_
#define MEMBRANE_CORE_ENGINE_MEMBRANE_INVARIANTS_H_

#include <cstdint>

#include "absl/status/status.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

struct InvariantOptions {
  // Property 3 holds only for a final DMS (after the n = 1 generation).
  bool require_property3 = true;
  // Number of voxels that held points, when known (-1: unknown): Property 4 then also checks
  // that none of them became outside (every hard voxel is still there). After a shrink, pass
  // that number less the hard voxels the piece separation cut (PieceSeparationStats::
  // hard_cut_voxels).
  int64_t expected_hard_voxels = -1;
};

// Checks: outside voxels are soft and every hard voxel survives (Property 4); no INSIDE voxel
// is 26-adjacent to an outside voxel (the DMS separates inside from outside, Property 2);
// boundary voxels 6-adjacent to outside are hard or frozen (Property 3); the boundary voxels of
// each shell form one 6-connected membrane; the outside is 6-connected to the array border.
// OK, or FailedPrecondition listing each violated invariant with a count and one example voxel.
absl::Status CheckMembraneInvariants(const VoxelGrid& grid, const InvariantOptions& options);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_MEMBRANE_INVARIANTS_H_
