// FindContractionPlace (paper section 4.3) as a snapshot of every fitting plate
// (fast-shrink.md section 2; algorithm-notes problem C).
//
// A snapshot takes O(NV / 64 * log n) word operations for all six orientations; after it,
// the plate through a candidate voxel is found with O(n) bit tests instead of the O(n^2)
// per-candidate search of the paper's list scan.
#ifndef MEMBRANE_CORE_ENGINE_PLACE_FINDER_H_
#define MEMBRANE_CORE_ENGINE_PLACE_FINDER_H_

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/base/cancel_token.h"
#include "core/engine/flat_bitset.h"
#include "core/engine/local_snapshot.h"
#include "core/engine/packed_plane.h"
#include "core/engine/plate.h"
#include "core/engine/voxel_grid.h"
#include "core/engine/work_planes.h"

namespace membrane {

// Work planes of a snapshot. The anchors E_o of its six orientations (and, for plates of
// kAnchorRowsMinPlate and more, the anchor rows DC_o) are kept as packed copies (PackedPlane)
// until the next snapshot; below kAnchorRowsMinPlate, PlaceFor tests the n x n anchors of
// each orientation directly, without rows.
inline constexpr int kPlaceFinderPlanes = 8;
inline constexpr int kAnchorRowsMinPlate = 8;

class PlaceFinder {
 public:
  // Keeps references to `grid` and `planes` (made for that grid), which must outlive the
  // finder. A snapshot overwrites the first kPlaceFinderPlanes planes; PlaceFor reads only the
  // finder's own packed copies, so other users may write the planes in between. A local
  // snapshot's bricks are computed on the planes' threads.
  PlaceFinder(const VoxelGrid& grid, WorkPlanes& planes);

  // Takes a snapshot for plate size n >= 1 of the current grid: every plate whose cells are
  // all outside or boundary soft (not frozen), that lies off the array border, and whose back
  // side is all outside. Returns the candidates: boundary soft voxels covered by such a plate,
  // in increasing voxel index. Polls `cancel` between word passes: nullopt when
  // it fired.
  std::optional<std::vector<int64_t>> Snapshot(int n, const CancelToken& cancel);

  // The same snapshot (the same candidates and places) taken after a pass of chains, given
  // `written`: boxes holding every voxel written since the last snapshot, which had plate
  // size n. It is computed only near those voxels (local_snapshot.h), which keeps each
  // candidate's place instead of the anchors, while their bricks' boxes hold at most
  // options.max_share of the grid's voxels; otherwise, and for other n, it is Snapshot(n).
  std::optional<std::vector<int64_t>> SnapshotAfter(int n, const std::vector<VoxelBox>& written,
                                                    const LocalSnapshotOptions& options,
                                                    const CancelToken& cancel);

  // The plate the paper's list scan would take for candidate voxel `index` at the snapshot:
  // first orientation in kOrientations order, then smallest u0, then smallest v0
  // (FirstAnchoredPlate). nullopt when no fitting plate covers the voxel in the snapshot;
  // after a local snapshot, for every voxel that is not one of its candidates.
  std::optional<Plate> PlaceFor(int64_t index) const;

  // True when the last snapshot was taken near the writes only (SnapshotAfter).
  bool local() const { return local_taken_; }

  // Frees the last snapshot's copies (the steps after the generations take none); PlaceFor
  // must not be called until the next snapshot.
  void Release();

 private:
  const VoxelGrid& grid_;
  WorkPlanes& planes_;
  int n_ = 0;
  // Set by the last snapshot: E_o, the lowest corner of each fitting plate, and DC_o, E_o
  // dilated along v by n (when rows_).
  std::array<PackedPlane, 6> anchors_;
  std::array<PackedPlane, 6> anchor_rows_;
  bool rows_ = false;
  LocalSnapshot local_;
  bool local_taken_ = false;  // the last snapshot is local_'s
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_PLACE_FINDER_H_
