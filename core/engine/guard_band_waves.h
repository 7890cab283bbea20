// The interior guard's band split by two waves (interior_guard.h), run a coarse voxel at a
// time: the k^3 fine voxels of a coarse voxel are one 64-bit word (a brick), and a wave steps
// by shifts and masks within a brick and across its six faces. Only the band's bricks hold
// soft voxels a wave can enter, so a step costs the wave's front, not the grid.
#ifndef MEMBRANE_CORE_ENGINE_GUARD_BAND_WAVES_H_
#define MEMBRANE_CORE_ENGINE_GUARD_BAND_WAVES_H_

#include <array>
#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

// The class of a coarse voxel after the coarse shrink and refill.
enum CoarseClass : uint8_t {
  kCoarseOutside = 0,  // outside the coarse membrane (the coarse padding included)
  kCoarseBand = 1,     // in the coarse solid, the rest
  kCoarseCore = 2,     // in the coarse solid, no hard voxel in its 3x3x3 block, few axis rays
                       // reaching the outside (GuardInteriors)
};

// Input: `grid`, before its first generation, whose frozen voxels are the core's (the fine
// voxels of kCoarseCore coarse voxels); a coarse grid of `coarse_dims`, `k` (2..4) times
// coarser over the same data region (fine (x, y, z) in coarse ((x - p) / k + p, ...), p the
// padding), with classes[c] the class of coarse voxel c and band_voxels the kCoarseBand ones,
// increasing. Two breadth-first waves through the band's fine INSIDE soft voxels (face steps),
// one from the outside (fine voxels out of the data region, boundary voxels and the fine
// voxels of kCoarseOutside voxels) and one from the frozen voxels, the outside's first at each
// distance, so that a voxel both reach at once is the outside's; the core's wave never enters
// a voxel with a hard voxel among its 26 neighbours (so the fine membrane finds the skin's
// pores and inner face as it would without the guard). The voxels the core's wave reaches
// become INSIDE frozen. Returns how many, or Cancelled when `cancel` fires (the grid then
// holds part of them). The bricks' reads and the waves' steps run on `threads` (>= 1); the
// result is the same for any thread count.
absl::StatusOr<int64_t> FreezeBandByWaves(VoxelGrid& grid, const std::array<int, 3>& coarse_dims,
                                          int k, const std::vector<uint8_t>& classes,
                                          const std::vector<int64_t>& band_voxels,
                                          const CancelToken& cancel, int threads = 1);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_GUARD_BAND_WAVES_H_
