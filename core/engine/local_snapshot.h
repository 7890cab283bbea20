// A place finder's snapshot taken again only near the voxels the last pass's chains wrote.
//
// A pass's candidates all lie within n of a voxel that pass wrote: each candidate's chain
// either writes its start plate (committed, or backtracked and frozen) or finds that plate no
// longer fitting (a voxel of the plate or its back side was written). A voxel farther than
// 2n from every voxel written keeps its state and every anchor whose plate could cover it, so
// it is a candidate of the next pass only if it was one of this pass, which it was not. The
// next pass's candidates therefore lie within 2n of the writes, and its anchors need to be
// known only within n of those: bricks around the writes, each computed on its own box (the
// brick and n voxels around it, whose outermost layer is left out as the grid's border is),
// give the dense snapshot's candidates and places.
//
// A brick keeps no planes: while its box's anchors are in cache, each of its candidates looks
// for its place (FirstAnchoredPlate, the dense search) and the snapshot keeps the places, eight
// bytes a candidate, sorted by voxel. A snapshot's anchors never change once it is taken, so a
// place found early is the one a later PlaceFor would find (the chain verifies its start plate
// on the current grid anyway); the boxes overlap several times near the membrane, so planes
// kept per brick would cost a multiple of the dense snapshot's.
#ifndef MEMBRANE_CORE_ENGINE_LOCAL_SNAPSHOT_H_
#define MEMBRANE_CORE_ENGINE_LOCAL_SNAPSHOT_H_

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/base/cancel_token.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/plate.h"
#include "core/engine/voxel_box.h"
#include "core/engine/voxel_grid.h"
#include "core/engine/voxel_state.h"

namespace membrane {

// When and how a later pass's snapshot is local (ShrinkOptions::local_snapshots).
struct LocalSnapshotOptions {
  // Largest share of the grid's voxels the bricks' boxes may hold; above it, and at 0, the
  // snapshot is dense.
  double max_share = 1.0;
  int brick = 32;  // least side of the bricks (voxels), >= 1
  // Bricks are at least this many plates wide (>= 0): a brick's box has n voxels of margin
  // on each side, which a narrower brick would spend most of the box on.
  int brick_plates = 4;
};

class LocalSnapshot {
 public:
  // Keeps a reference to `grid`, which must outlive the snapshot. The bricks of a snapshot
  // are computed on `threads` threads (>= 1), with the same candidates and places for any
  // count.
  explicit LocalSnapshot(const VoxelGrid& grid, int threads = 1)
      : grid_(grid), work_(static_cast<size_t>(threads < 1 ? 1 : threads)) {}

  // Takes the snapshot for plate size n >= 1 on the bricks (of side max(options.brick,
  // options.brick_plates * n)) within 2n + 1 of `written`, the boxes holding every voxel
  // written since the last snapshot of the same plate size on this grid. Returns its
  // candidates (the dense snapshot's, in increasing voxel index) and keeps the place of each.
  // Returns nullopt, keeping nothing, when the bricks' boxes would hold more than
  // options.max_share of the grid or a candidate's index and place would not fit in 64 bits
  // together (the caller takes the dense snapshot), or when `cancel` fired.
  std::optional<std::vector<int64_t>> Take(int n, const std::vector<VoxelBox>& written,
                                           const LocalSnapshotOptions& options,
                                           const CancelToken& cancel);

  // PlaceFinder::PlaceFor on the last snapshot taken here: the place kept for candidate
  // `index`, nullopt for a voxel that was not a candidate. O(log candidates).
  std::optional<Plate> PlaceFor(int64_t index) const;

  // Frees the places and the planes the bricks were computed on.
  void Release();

 private:
  // Index of the brick (bx, by, bz), x fastest.
  int64_t BrickIndex(int bx, int by, int bz) const {
    return bx + static_cast<int64_t>(brick_counts_[0]) *
                    (by + static_cast<int64_t>(brick_counts_[1]) * bz);
  }
  // The states and planes of the box being computed: one set per thread. The anchors E_o and
  // their rows DC_o (E_o dilated along v by n) of the six orientations are all held while the
  // box's candidates look for their places.
  struct BoxPlanes {
    std::vector<VoxelState> bytes;
    FlatBitset free, out, bs, free_z, out_z, free_sq, out_sq, covered, scratch;
    std::array<FlatBitset, 6> anchors, rows;
  };
  // Sets n_, brick_ and the rest for the snapshot Take describes and returns the bricks it
  // is computed on, in increasing brick index; nullopt when it is not taken locally.
  std::optional<std::vector<int64_t>> Plan(int n, const std::vector<VoxelBox>& written,
                                           const LocalSnapshotOptions& options);
  // Computes the anchors of the box of the brick with core [core_lo, core_lo + brick_) in `w`,
  // and appends a key (keys_) per candidate of the core, in increasing voxel index, to `keys`.
  void Compute(const Coord& core_lo, BoxPlanes& w, std::vector<uint64_t>& keys) const;

  const VoxelGrid& grid_;
  int n_ = 0;
  int brick_ = 1;
  std::array<int, 3> brick_counts_ = {0, 0, 0};
  // Per candidate in increasing voxel index: index << place_bits_ | place, where place =
  // (orientation * n + u - u0) * n + v - v0 for the candidate's plate (u, v its own in-plane
  // coordinates): sorting the keys sorts the candidates.
  std::vector<uint64_t> keys_;
  int place_bits_ = 0;
  std::vector<BoxPlanes> work_;  // per thread
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_LOCAL_SNAPSHOT_H_
