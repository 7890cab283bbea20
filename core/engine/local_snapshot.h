// A place finder's snapshot taken again only near the voxels the last pass's chains wrote.
//
// A pass's candidates all lie within n of a voxel that pass wrote: each candidate's chain
// either writes its start plate (committed, or backtracked and frozen) or finds that plate no
// longer fitting (a voxel of the plate or its back side was written). A voxel farther than
// 2n from every voxel written keeps its state and every anchor whose plate could cover it, so
// it is a candidate of the next pass only if it was one of this pass, which it was not. The
// next pass's candidates therefore lie within 2n of the writes, and its anchors need to be
// known only within n of those: bricks around the writes, each computed on its own box (the
// brick and n + 2 voxels around it), give the dense snapshot's candidates and places.
#ifndef MEMBRANE_CORE_ENGINE_LOCAL_SNAPSHOT_H_
#define MEMBRANE_CORE_ENGINE_LOCAL_SNAPSHOT_H_

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/base/cancel_token.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/packed_plane.h"
#include "core/engine/plate.h"
#include "core/engine/voxel_box.h"
#include "core/engine/voxel_grid.h"
#include "core/engine/voxel_state.h"

namespace membrane {

// When and how a later pass's snapshot is local (ShrinkOptions::local_snapshots).
struct LocalSnapshotOptions {
  // Largest share of the grid's voxels the bricks' boxes may hold; above it, and at 0, the
  // snapshot is dense.
  double max_share = 0.5;
  int brick = 32;  // side of the bricks (voxels), >= 1
};

class LocalSnapshot {
 public:
  // Keeps a reference to `grid`, which must outlive the snapshot. The bricks of a snapshot
  // are computed on `threads` threads (>= 1), with the same candidates and places for any
  // count.
  explicit LocalSnapshot(const VoxelGrid& grid, int threads = 1)
      : grid_(grid), work_(static_cast<size_t>(threads < 1 ? 1 : threads)) {}

  // Takes the snapshot for plate size n >= 1 on the bricks within 2n + 1 of `written`, the
  // boxes holding every voxel written since the last snapshot of the same plate size on this
  // grid. Returns its candidates (the dense snapshot's, in increasing voxel index), or
  // nullopt when the bricks' boxes would hold more than options.max_share of the grid (the
  // caller takes the dense snapshot; nothing is kept) or `cancel` fired.
  std::optional<std::vector<int64_t>> Take(int n, const std::vector<VoxelBox>& written,
                                           const LocalSnapshotOptions& options,
                                           const CancelToken& cancel);

  // PlaceFinder::PlaceFor on the last snapshot taken here, for one of its candidates.
  std::optional<Plate> PlaceFor(int64_t index) const;

  // Frees the bricks' planes.
  void Release();

 private:
  struct Brick {
    Coord lo;                            // the box's lowest voxel in the grid
    std::array<int, 3> dims;             // the box's size
    std::array<PackedPlane, 6> anchors;  // per orientation, over the box
  };
  // Index in slot_ of the brick (bx, by, bz), x fastest.
  int64_t BrickIndex(int bx, int by, int bz) const {
    return bx + static_cast<int64_t>(brick_counts_[0]) *
                    (by + static_cast<int64_t>(brick_counts_[1]) * bz);
  }
  // The states and planes of the box being computed: one set per thread.
  struct BoxPlanes {
    std::vector<VoxelState> bytes;
    FlatBitset free, out, bs, free_z, out_z, free_sq, out_sq, covered, anchor, scratch;
  };
  // Computes the anchors of `brick` (core [core_lo, core_lo + brick_)) in `w`, and appends
  // the core's candidates to `candidates` in increasing voxel index.
  void Compute(Brick& brick, const Coord& core_lo, BoxPlanes& w,
               std::vector<int64_t>& candidates) const;

  const VoxelGrid& grid_;
  int n_ = 0;
  int brick_ = 1;
  std::array<int, 3> brick_counts_ = {0, 0, 0};
  std::vector<int32_t> slot_;  // per brick of the grid: its index in bricks_, or -1
  std::vector<Brick> bricks_;
  std::vector<BoxPlanes> work_;  // per thread
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_LOCAL_SNAPSHOT_H_
