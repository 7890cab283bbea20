// The state of one voxel, packed in one byte (paper section 4.1 and algorithm-notes 1-2).
//
// Layout:
//   bit 7 set   -> OUTSIDE. Outside voxels are always soft (Property 4), so bits 0..6 hold the
//                  generation label of the contraction that made the voxel outside
//                  (0 = padding or pre-shrink, 1.. = plate generations).
//   bit 7 clear -> bit 0: 1 = BOUNDARY, 0 = INSIDE; bits 1..2: hardness (0 soft, 1 hard, 2 frozen).
#ifndef MEMBRANE_CORE_ENGINE_VOXEL_STATE_H_
#define MEMBRANE_CORE_ENGINE_VOXEL_STATE_H_

#include <cstdint>

namespace membrane {

using VoxelState = uint8_t;

enum class Hardness : uint8_t { kSoft = 0, kHard = 1, kFrozen = 2 };
enum class Position : uint8_t { kInside = 0, kBoundary = 1, kOutside = 2 };

inline constexpr VoxelState kOutsideBit = 0x80;
inline constexpr VoxelState kBoundaryBit = 0x01;
inline constexpr VoxelState kHardnessMask = 0x06;
inline constexpr int kMaxGenerationLabel = 127;

inline constexpr VoxelState kInsideSoft = 0x00;
inline constexpr VoxelState kBoundarySoft = 0x01;
inline constexpr VoxelState kInsideHard = 0x02;
inline constexpr VoxelState kBoundaryHard = 0x03;
inline constexpr VoxelState kInsideFrozen = 0x04;
inline constexpr VoxelState kBoundaryFrozen = 0x05;

// An outside voxel of generation label `label` (0..127).
constexpr VoxelState OutsideState(int label) { return static_cast<VoxelState>(kOutsideBit | label); }
constexpr bool IsOutside(VoxelState s) { return (s & kOutsideBit) != 0; }
// Generation label of an outside voxel; meaningless for other states.
constexpr int GenerationLabel(VoxelState s) { return s & 0x7f; }
constexpr bool IsBoundary(VoxelState s) { return (s & (kOutsideBit | kBoundaryBit)) == kBoundaryBit; }
constexpr bool IsInside(VoxelState s) { return (s & (kOutsideBit | kBoundaryBit)) == 0; }
constexpr Hardness HardnessOf(VoxelState s) {
  return IsOutside(s) ? Hardness::kSoft : static_cast<Hardness>((s & kHardnessMask) >> 1);
}
constexpr bool IsHard(VoxelState s) { return !IsOutside(s) && (s & kHardnessMask) == 0x02; }
constexpr bool IsFrozen(VoxelState s) { return !IsOutside(s) && (s & kHardnessMask) == 0x04; }
// Hard or frozen: the voxels that stop plates and are tested for incursions (section 4.2).
constexpr bool IsHardOrFrozen(VoxelState s) { return !IsOutside(s) && (s & kHardnessMask) != 0; }
// Boundary, soft and not frozen: the only voxels a CONTRACTION may turn outside.
constexpr bool IsBoundarySoft(VoxelState s) { return s == kBoundarySoft; }
constexpr Position PositionOf(VoxelState s) {
  return IsOutside(s) ? Position::kOutside : (s & kBoundaryBit) ? Position::kBoundary : Position::kInside;
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_VOXEL_STATE_H_
