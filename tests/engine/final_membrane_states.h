// Test grids shaped as the shrink leaves them.
#ifndef MEMBRANE_TESTS_ENGINE_FINAL_MEMBRANE_STATES_H_
#define MEMBRANE_TESTS_ENGINE_FINAL_MEMBRANE_STATES_H_

#include <cstdint>

#include "core/engine/local_topology.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

// Gives the non-outside voxels of `grid` the positions and frozen states of a final membrane:
// a voxel beside the outside (26-neighbour) BOUNDARY, a soft one with an outside face
// neighbour FROZEN (Property 3). Voxels on the array border are left as they are.
inline void SetFinalMembraneStates(VoxelGrid& grid) {
  for (int64_t v = 0; v < grid.size(); ++v) {
    if (IsOutside(grid.at(v)) || grid.OnArrayBorder(grid.CoordOf(v))) continue;
    const uint32_t outside = OutsideMask(grid, v);
    if ((outside & ~kCentreBit) == 0) continue;
    VoxelState s = grid.at(v) | kBoundaryBit;
    if (s == kBoundarySoft && (outside & FaceNeighboursMask()) != 0) s = kBoundaryFrozen;
    grid.set(v, s);
  }
}

}  // namespace membrane

#endif  // MEMBRANE_TESTS_ENGINE_FINAL_MEMBRANE_STATES_H_
