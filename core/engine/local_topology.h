// Topology of a voxel's 3x3x3 neighbourhood, on 27-bit masks.
//
// Bit (dx+1) + 3*(dy+1) + 9*(dz+1) stands for the neighbour at offset (dx, dy, dz); bit 13 is
// the centre. The object (non-outside voxels) is 26-connected and the background (outside)
// 6-connected, the (26,6) pair of the paper's membranes. Used by the incursion test
// (local-arc connectivity, section 4.2), the topology guard (algorithm-notes 12) and
// relaxation, which moves only simple voxels.
#ifndef MEMBRANE_CORE_ENGINE_LOCAL_TOPOLOGY_H_
#define MEMBRANE_CORE_ENGINE_LOCAL_TOPOLOGY_H_

#include <cstdint>

#include "core/engine/voxel_grid.h"

namespace membrane {

inline constexpr uint32_t kCentreBit = 1u << 13;
inline constexpr uint32_t kAll27 = (1u << 27) - 1;

// Bit of the neighbour at offset (dx, dy, dz), each in {-1, 0, 1}.
constexpr int NeighbourBit(int dx, int dy, int dz) { return (dx + 1) + 3 * (dy + 1) + 9 * (dz + 1); }

// The 6 face neighbours, the 18 face and edge neighbours (centre excluded).
uint32_t FaceNeighboursMask();
uint32_t N18Mask();

// Mask of the 27 voxels around `index` (centre included) whose state satisfies `pred`.
// `index` must not lie on the array border.
template <typename Pred>
uint32_t NeighbourhoodMask(const VoxelGrid& grid, int64_t index, Pred pred) {
  const std::array<int64_t, 27>& offsets = grid.block_offsets();
  const VoxelState* s = grid.states().data() + index;
  uint32_t mask = 0;
  for (int k = 0; k < 27; ++k)
    if (pred(s[offsets[k]])) mask |= 1u << k;
  return mask;
}

// Mask of the outside voxels around `index` (centre included if outside).
uint32_t OutsideMask(const VoxelGrid& grid, int64_t index);

// The voxels of `allowed` reached from `seed` by face steps (6-connectivity), resp. by face,
// edge or corner steps (26-connectivity), inside the 3x3x3 block. `seed` is included when it
// lies in `allowed`.
uint32_t Flood6(uint32_t seed, uint32_t allowed);
uint32_t Flood26(uint32_t seed, uint32_t allowed);

// T6: the number of 6-components of background voxels among the 18 face and edge neighbours
// that contain a face neighbour of the centre (Bertrand-Malandain). Centre bit ignored.
int CountT6(uint32_t background);
// T26: the number of 26-components of object voxels among the 26 neighbours. Centre ignored.
int CountT26(uint32_t object);

// True when changing the centre between object and background changes no topology: the
// (26,6) simple-point test, T26(object) == 1 and T6(complement) == 1. Centre bit ignored.
bool IsSimple(uint32_t object);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_LOCAL_TOPOLOGY_H_
