// Masks over a voxel grid as bits (voxel i is bit i of the flat index, 64 a word) and the 3x3x3
// box filters on them, for the surface clean-up's passes over every voxel.
//
// A byte a voxel, the cave filling's masks were two bytes a voxel beside the grid and its copy:
// 4.3 GB on a 10M-point cloud's grid of 2.2e9 voxels, the run's peak. As bits they are a
// quarter byte, and a filter pass reads and writes an eighth of the bytes.
#ifndef MEMBRANE_CORE_MESH_VOXEL_BIT_MASKS_H_
#define MEMBRANE_CORE_MESH_VOXEL_BIT_MASKS_H_

#include <array>
#include <cstdint>

#include "core/engine/flat_bitset.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

// Returns the bits of `grid`'s outside voxels (bits past the last voxel 0). `threads` (<= 1:
// the calling thread) share the words; the result is the same for any count.
FlatBitset OutsideBits(const VoxelGrid& grid, int threads);

// bits := for each voxel, the AND (erode) or OR (dilate) of `bits` over its 3x3x3 box, voxels
// beyond the array reading as set for an erosion and clear for a dilation. Three passes of
// whole words (along x, y, z), each a flat shift of the bitset by the axis' stride, so a row's
// first voxel reads the row before it where a voxel beyond the array would be: the result is
// exact at every voxel off the array border, and at the border voxels too for an erosion of
// bits set on the whole array border. Bits past the last voxel stay 0. `scratch` must have the
// size of `bits`; its contents are overwritten (every word is written before one is read, so it
// may be made unset). `threads` as for OutsideBits.
void BoxFilterBits(const std::array<int, 3>& dims, bool erode, FlatBitset& bits,
                   FlatBitset& scratch, int threads);

// The 8 bits of `bits` from voxel `first` on (first + 7 must be a voxel), as the low byte.
inline uint64_t EightBits(const FlatBitset& bits, int64_t first) {
  const uint64_t* const words = bits.words();
  const int64_t q = first >> 6;
  const int r = static_cast<int>(first & 63);
  uint64_t v = words[q] >> r;
  if (r > 56) v |= words[q + 1] << (64 - r);
  return v & 0xff;
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_VOXEL_BIT_MASKS_H_
