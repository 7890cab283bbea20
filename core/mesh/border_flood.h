// The cave filling's flood of the outside space from the array border, on bit masks.
//
// The outside region is most of the grid, and a flood over it touches every voxel: one bit a
// voxel (64 a word) keeps its reads and writes an eighth of a byte mask's.
#ifndef MEMBRANE_CORE_MESH_BORDER_FLOOD_H_
#define MEMBRANE_CORE_MESH_BORDER_FLOOD_H_

#include <array>
#include <cstdint>

#include "core/engine/flat_bitset.h"

namespace membrane {

// Input: the array's dimensions (x fastest) and `open`, the bits of its open voxels.
// Returns the bits of the open voxels 6-connected, through open voxels, to an open voxel on the
// array border (any voxel with a coordinate 0 or dims[a] - 1). Cost: O(voxels / 64) words read
// per row of the array plus O(1) per run of open voxels along x. `threads` (<= 1: the calling
// thread) share large arrays (2^24 voxels and 16 planes or more) as slabs of z planes; the bits
// are the same for any count.
FlatBitset FloodFromBorder(const std::array<int, 3>& dims, const FlatBitset& open, int threads = 1);

// The same bits, the array cut into `slabs` slabs of whole z planes (clamped to [1, dims[2]])
// flooded on `threads` threads whatever the array's size: FloodFromBorder's threaded path,
// callable on small arrays and many slabs (tests).
FlatBitset FloodFromBorderOnSlabs(const std::array<int, 3>& dims, const FlatBitset& open,
                                  int threads, int slabs);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_BORDER_FLOOD_H_
