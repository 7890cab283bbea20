// The outside loop a tunnel would close: tells the notch that starts a split of a thin soft
// bridge from a hole through a wall (topology guard, docs/engine-decisions.md "Shrink").
#ifndef MEMBRANE_CORE_ENGINE_TUNNEL_LOOP_H_
#define MEMBRANE_CORE_ENGINE_TUNNEL_LOOP_H_

#include <cstdint>

#include "core/engine/voxel_grid.h"

namespace membrane {

// `outside` is the 27-bit outside mask around the non-outside voxel at `index` (bit layout of
// local_topology.h; centre ignored). True when removing the voxel would open exactly one tunnel
// (T6 == 2) and its two local outside components are joined, through the grid, by a 6-path of at
// most `max_steps` outside voxels that avoids `index`: the loop the tunnel closes is short, so
// the non-outside voxels it goes around form a bridge about one voxel thick. False when T6 != 2
// or no such path exists. Visits at most the outside voxels within `max_steps` face steps of the
// neighbourhood; never reads past the array border.
bool TunnelClosesShortLoop(const VoxelGrid& grid, int64_t index, uint32_t outside, int max_steps);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_TUNNEL_LOOP_H_
