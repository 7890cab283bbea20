// The grid's voxels that are not outside, as runs along each axis: per grid row, the first and
// last coordinate of each stretch of non-outside voxels, in order. A walk through the outside
// along an axis then ends where a binary search over its row says, instead of stepping voxel
// by voxel (along z each step is a plane away, a cache and TLB miss). The gap refill's rays
// from the membrane walk the outside this way.
#ifndef MEMBRANE_CORE_ENGINE_OUTSIDE_RUNS_H_
#define MEMBRANE_CORE_ENGINE_OUTSIDE_RUNS_H_

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/engine/voxel_grid.h"

namespace membrane {

class OutsideRuns {
 public:
  // Reads every voxel of `grid` twice (counting the runs, then writing them), a slab of z
  // planes a task on `threads` (>= 1) threads: the same runs for any count. Memory: 4 bytes a
  // grid row and axis, 8 bytes a run, and while they are read 4 bytes per (x, y) column and
  // thread. nullopt, before anything past the counts is allocated, when the runs would take
  // more than `max_bytes` (a membrane of many thin crossings; the caller then walks another
  // way). The runs describe the grid as it is now: they go stale when a voxel changes between
  // outside and not.
  static std::optional<OutsideRuns> Read(const VoxelGrid& grid, int threads, int64_t max_bytes);

  // Walks from voxel `c` (off the array's border) along axis `d` (0..2) in direction `sign`
  // (+1 or -1) while the voxels stepped on are outside, stopping on the first that is not or
  // on the array's border layer (coordinate 0 or dim - 1, not tested): returns that voxel's
  // coordinate along d. The voxel c itself is not tested. The same answer as a walk voxel by
  // voxel, for the grid these runs were read from.
  int WalkOutside(const Coord& c, int d, int sign) const;

  // Runs held, over the three axes.
  int64_t runs() const;

 private:
  OutsideRuns() = default;

  std::array<int, 3> dims_{};
  // Per axis: row r's runs are [first_[d][r], first_[d][r + 1]) of lo_[d] and hi_[d], the
  // first and last coordinate of each, rising.
  std::array<std::vector<uint32_t>, 3> first_;
  std::array<std::vector<int32_t>, 3> lo_, hi_;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_OUTSIDE_RUNS_H_
