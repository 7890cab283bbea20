// Bit-planes over a grid's voxels shared by the place finder and the closed form in one shrink.
//
// Neither keeps anything in its planes from one generation to the next (a closed-form
// generation runs before its generation's first snapshot, and a snapshot is taken again at
// the start of every generation that runs chains), so one set serves both: 8 planes, 88 MB on
// a 70 M voxel grid and 2.2 GB on a 10M-point torus's 2.2e9 voxels (as much as the grid).
#ifndef MEMBRANE_CORE_ENGINE_WORK_PLANES_H_
#define MEMBRANE_CORE_ENGINE_WORK_PLANES_H_

#include <memory>
#include <vector>

#include "core/base/cancel_token.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/plane_arena.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

class WorkPlanes {
 public:
  // Keeps a reference to `grid`, which must outlive the planes. Allocates nothing yet. The
  // planes' word passes run on `threads` threads (FlatBitset::set_threads).
  explicit WorkPlanes(const VoxelGrid& grid, int threads = 1) : grid_(grid), threads_(threads) {}
  // Not copied or moved: the planes point at the halo this object holds.
  WorkPlanes(const WorkPlanes&) = delete;
  WorkPlanes& operator=(const WorkPlanes&) = delete;

  // Makes planes 0 .. count-1 available, one bit per voxel of the grid, allocating the
  // missing ones (zeroed) and polling `cancel` between allocations: false when it fired. A
  // plane's contents are whatever its last user left; references from plane() stay valid when
  // later calls add planes.
  bool Ensure(int count, const CancelToken& cancel);

  // Frees every plane and their halo (the steps after the generations need none); Ensure
  // makes them again.
  void Release();

  // The threads the planes' word passes run on (at least 1).
  int threads() const { return threads_; }

  // Planes cut from one arena (PlaneArena); more are allocated on their own.
  static constexpr int kArenaPlanes = 8;

  // Plane i < the largest count ensured so far.
  FlatBitset& plane(int i) { return *planes_[static_cast<size_t>(i)]; }

 private:
  const VoxelGrid& grid_;
  const int threads_;
  // Declared before the planes, so destroyed after them.
  std::unique_ptr<PlaneArena> arena_;
  // The halo every plane's passes save (FlatBitset::set_halo_store): the planes' users run one
  // plane's pass at a time, so one halo serves them all, not one of up to a sixteenth of a
  // plane each (134 MB over 8 planes of a 2e9-voxel grid).
  std::vector<uint64_t> halo_;
  std::vector<std::unique_ptr<FlatBitset>> planes_;  // stable addresses
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_WORK_PLANES_H_
