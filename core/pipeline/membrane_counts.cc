#include "core/pipeline/membrane_counts.h"

#include <utility>

#include "core/engine/voxel_state.h"
#include "core/engine/voxel_topology.h"

namespace membrane {

MembraneCounts CountMembrane(const VoxelGrid& grid) {
  MembraneCounts counts;
  for (const VoxelState s : grid.states()) {
    if (IsOutside(s)) continue;
    const bool boundary = IsBoundary(s);
    if (IsHard(s)) {
      ++(boundary ? counts.hard_voxels : counts.inside_hard_voxels);
    } else if (IsFrozen(s)) {
      ++(boundary ? counts.frozen_voxels : counts.inside_frozen_voxels);
    } else {
      ++(boundary ? counts.soft_voxels : counts.inside_soft_voxels);
    }
  }
  VoxelTopology topology = ComputeVoxelTopology(grid);
  counts.shells = topology.shells;
  counts.genus = std::move(topology.genus);
  return counts;
}

}  // namespace membrane
