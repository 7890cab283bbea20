// What the topology guard looks at before it lets a small plate open a tunnel: the outside loop
// the tunnel would close, where the hard neighbours lie, the generations on its two sides. They
// tell the notch that starts a split of a thin soft bridge from a hole through a wall
// (docs/engine-decisions.md "Shrink").
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

// True when every voxel of the 27-bit `mask` (centre ignored) lies in one face layer of the
// 3x3x3 block: the 9 voxels whose offset along one axis is -1, or the 9 whose offset is +1.
// True for an empty mask.
bool InOneFaceLayer(uint32_t mask);

// True when, along some axis, both face neighbours of the voxel at `index` are outside, lie in
// different 6-components of the outside face and edge neighbours (`outside`, the 27-bit mask
// around `index`) and carry the same generation label: the tunnel would join two sides that
// one generation turned outside. `index` must not lie on the array border.
bool SameGenerationAcrossTunnel(const VoxelGrid& grid, int64_t index, uint32_t outside);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_TUNNEL_LOOP_H_
