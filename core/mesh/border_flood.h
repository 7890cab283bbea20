// The cave filling's flood of the outside space from the array border, on bit masks.
//
// The outside region is most of the grid, and a flood over it touches every voxel: one bit a
// voxel (64 a word) keeps its reads and writes an eighth of a byte mask's.
#ifndef MEMBRANE_CORE_MESH_BORDER_FLOOD_H_
#define MEMBRANE_CORE_MESH_BORDER_FLOOD_H_

#include <array>
#include <cstdint>
#include <vector>

#include "core/engine/huge_page_allocator.h"

namespace membrane {

// One bit a voxel of a grid in index order: voxel i is bit (i & 63) of word i >> 6. Bits past
// the last voxel are 0.
using VoxelBits = std::vector<uint64_t, HugePageAllocator<uint64_t>>;

// Returns the bits of a byte mask of `count` voxels (bytes 0 or 1). `threads` (<= 1: the
// calling thread) share the words; the result is the same for any count.
VoxelBits PackVoxelBits(const char* bytes, int64_t count, int threads);

// Writes bits[0..count) as bytes 0 or 1 to `bytes`. `threads` as for PackVoxelBits.
void UnpackVoxelBits(const VoxelBits& bits, int64_t count, char* bytes, int threads);

// Input: the array's dimensions (x fastest) and `open`, the bits of its open voxels.
// Returns the bits of the open voxels 6-connected, through open voxels, to an open voxel on the
// array border (any voxel with a coordinate 0 or dims[a] - 1). Cost: O(voxels / 64) words read
// per row of the array plus O(1) per run of open voxels along x; one calling thread.
VoxelBits FloodFromBorder(const std::array<int, 3>& dims, const VoxelBits& open);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_BORDER_FLOOD_H_
