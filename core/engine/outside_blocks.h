// The grid's outside voxels in blocks of 8 x 8 x 8: a bit a block, set when every voxel of the
// block is outside, so that a walk along an axis through the outside steps over a block at a
// time. The gap refill's rays from the membrane walk the outside to the array's border or to
// the solid across it; along z every voxel step is a plane (1.3 MB on a 10M-point grid) away,
// a cache and TLB miss, where a block bit lies in an array of a few hundred KB.
#ifndef MEMBRANE_CORE_ENGINE_OUTSIDE_BLOCKS_H_
#define MEMBRANE_CORE_ENGINE_OUTSIDE_BLOCKS_H_

#include <array>
#include <cstdint>
#include <vector>

#include "core/engine/voxel_grid.h"

namespace membrane {

class OutsideBlocks {
 public:
  // Reads every voxel of `grid` once, a plane of blocks a task on `threads` (>= 1) threads:
  // the same bits for any count. Memory: a bit per 512 voxels (0.5 MB for 2e9 voxels). The
  // bits describe the grid as it is now: they go stale when an outside voxel is written.
  OutsideBlocks(const VoxelGrid& grid, int threads);

  // Walks from voxel `c` (in the array) along axis `d` (0..2) in direction `sign` (+1 or -1)
  // while the voxels stepped on are outside, stopping on the first that is not or on the
  // array's border layer (coordinate 0 or dim - 1, not tested): returns that voxel's
  // coordinate along d. The voxel c itself is not tested. The same answer as a walk voxel by
  // voxel, for the grid these bits were read from.
  int WalkOutside(const VoxelGrid& grid, const Coord& c, int d, int sign) const;

 private:
  bool AllOutside(const Coord& b) const {
    const int64_t bit = b.z * plane_bits_ + b.x + static_cast<int64_t>(blocks_[0]) * b.y;
    return (bits_[static_cast<size_t>(bit >> 6)] >> (bit & 63)) & 1;
  }

  std::array<int, 3> blocks_{};  // blocks along x, y, z
  int64_t plane_bits_ = 0;       // bits of a plane of blocks, a whole number of words
  std::vector<uint64_t> bits_;
  // Per axis, per row of blocks along it: the lowest and highest block coordinate of a block
  // that is not all outside (lowest > highest when none): past them a ray is in the open.
  std::array<std::vector<int32_t>, 3> solid_lo_, solid_hi_;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_OUTSIDE_BLOCKS_H_
