// Eight voxel states read as one 64-bit word, for grid scans that rule out eight voxels at a
// time before testing them one by one (the states are one byte each, so a row's neighbours
// along x are the word's bytes).
#ifndef MEMBRANE_CORE_ENGINE_VOXEL_STATE_WORDS_H_
#define MEMBRANE_CORE_ENGINE_VOXEL_STATE_WORDS_H_

#include <cstdint>
#include <cstring>

#include "core/engine/voxel_state.h"

namespace membrane {

static_assert(sizeof(VoxelState) == 1 && kOutsideBit == 0x80 && kBoundaryBit == 0x01);

// The outside bit of each of the eight states of a word.
inline constexpr uint64_t kOutsideBits8 = 0x8080808080808080ull;
// Bit 0 of each byte of a word.
inline constexpr uint64_t kLowBits8 = 0x0101010101010101ull;

// The eight states from `s` on (all eight must exist).
inline uint64_t LoadStates8(const VoxelState* s) {
  uint64_t w;
  std::memcpy(&w, s, 8);
  return w;
}

// True when one of the eight states from `s` on is a boundary voxel: boundary bit set,
// outside bit clear.
inline bool AnyBoundary8(const VoxelState* s) {
  const uint64_t w = LoadStates8(s);
  return (w & ~(w >> 7) & kLowBits8) != 0;
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_VOXEL_STATE_WORDS_H_
