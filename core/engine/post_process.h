// Post-process of paper section 7: hard voxels left inside the final membrane are connected to
// it, so that their points lie within d = sqrt(3) l of the membrane's outer surface.
#ifndef MEMBRANE_CORE_ENGINE_POST_PROCESS_H_
#define MEMBRANE_CORE_ENGINE_POST_PROCESS_H_

#include <cstdint>

#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

struct PostProcessStats {
  int64_t inside_hard_before = 0;
  int64_t inside_hard_after = 0;
  int64_t carved_voxels = 0;  // soft voxels made outside to reach them
  int64_t bridge_voxels = 0;  // voxels added by BridgeMembraneContacts
  double seconds = 0;         // wall time of the post-process (set by the shrink that runs it)
};

// Makes the non-outside voxel `index` (not on the array border) outside with generation label 0
// and restores the membrane invariants around it: inside voxels 26-adjacent to it become
// BOUNDARY, soft boundary ones 6-adjacent to it FROZEN (Property 3). Reads and writes only its
// 3x3x3 block.
void CarveToOutside(VoxelGrid& grid, int64_t index);

// For every INSIDE hard voxel, finds the shortest 6-path of soft non-outside voxels from it to
// a voxel with an outside face neighbour (within `max_path` steps) and carves the path from the
// outside end inwards, each voxel only if it is (26,6)-simple, so shells and genus never change
// (a dent, not a tunnel). The hard voxel becomes BOUNDARY; inside voxels 26-adjacent to a carved
// voxel become BOUNDARY, and soft ones 6-adjacent to it FROZEN, so the membrane invariants
// (Property 3 included) still hold. Searches skip the soft components known to have no way out
// (so a sealed interior is searched once, not once per hard voxel on its wall), and all of them
// together visit at most 4 voxels per grid voxel: past that, the remaining inside hard voxels
// are left as they are (inside_hard_after counts them). Cancelled when `cancel` fires.
// `threads` (>= 1) share BridgeMembraneContacts's reading of the grid: the same grid for any
// count.
absl::StatusOr<PostProcessStats> ConnectInsideHardVoxels(VoxelGrid& grid,
                                                         const CancelToken& cancel,
                                                         int max_path = 64, int threads = 1);

// Makes the membrane of each shell 6-connected (section 4.1: a DM is face-connected). The
// (26,6) shrink may leave two boundary voxels touching only along an edge or at a corner (a
// hard voxel of a sparse region whose last soft face neighbour a plate removed). Each such
// contact gets a face-connected path inside the 3x3x3 block: one or two voxels, or, for an edge
// contact whose one-voxel paths are not simple, a detour of three off the contact's plane. An
// inside voxel becomes BOUNDARY, an outside one FROZEN BOUNDARY only when (26,6)-simple, so
// neither the shells nor the genus change. Returns the number of voxels changed. The grid is read for
// contacts on `threads` (>= 1) and bridged on the calling thread, in voxel order: the same
// grid for any count.
int64_t BridgeMembraneContacts(VoxelGrid& grid, int threads = 1);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_POST_PROCESS_H_
