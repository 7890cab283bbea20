// Census of a final membrane (DMS): the "membrane" object of the statistics JSON.
#ifndef MEMBRANE_CORE_PIPELINE_MEMBRANE_COUNTS_H_
#define MEMBRANE_CORE_PIPELINE_MEMBRANE_COUNTS_H_

#include <cstdint>
#include <vector>

#include "core/engine/voxel_grid.h"

namespace membrane {

struct MembraneCounts {
  // BOUNDARY voxels by hardness: the membrane itself.
  int64_t hard_voxels = 0;
  int64_t frozen_voxels = 0;
  int64_t soft_voxels = 0;  // neither: none touches an outside face (Property 3)
  // All BOUNDARY voxels.
  int64_t membrane_voxels() const { return hard_voxels + frozen_voxels + soft_voxels; }
  // INSIDE voxels by hardness.
  int64_t inside_hard_voxels = 0;  // points the post-process could not reach
  int64_t inside_soft_voxels = 0;
  int64_t inside_frozen_voxels = 0;
  // Topology of the voxel solid (non-outside voxels, 26-connected).
  int shells = 0;
  std::vector<int> genus;  // per shell
};

// Counts the voxel states of `grid` and computes its shells and genus (ComputeVoxelTopology
// of core/engine). `grid` must have an outside border layer, as every membrane has.
// O(voxels), its passes over the voxels on `threads`: the same counts for any thread count.
MembraneCounts CountMembrane(const VoxelGrid& grid, int threads = 1);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_MEMBRANE_COUNTS_H_
