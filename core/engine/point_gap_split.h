// Pieces of data told apart by their points where their hard voxels touch (issue 18; docs/
// engine-decisions.md "Pieces of data separated after the shrink").
//
// Two objects whose nearest points lie 2.5 voxels apart can still have 26-adjacent hard
// voxels: each point fills the voxel it falls in, and two voxels meeting at a corner hold
// points up to 3.5 voxels apart. Their hard voxels are then one 26-component, yet a tube of one
// voxel around each object's points (the tube that defines the expected shells) keeps them
// apart. The points tell it: across the contact, no point of one voxel comes within two voxels
// of a point of the other.
#ifndef MEMBRANE_CORE_ENGINE_POINT_GAP_SPLIT_H_
#define MEMBRANE_CORE_ENGINE_POINT_GAP_SPLIT_H_

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/engine/hard_voxel_points.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

// Input: `component`, a 26-component of hard voxels of `grid` (grid indices, in any order),
// and the points of the hard voxels.
// Returns its parts joined by evidence: two voxels of it are joined when a point of one lies
// within `reach` voxels of a point of the other (the one-voxel tubes around their points touch,
// for a reach of 2), and the parts are the classes of that relation: sparse points of one
// surface, whose diagonal neighbours' points lie farther apart, are joined through the voxels
// beyond. When two or more parts hold at least `min_voxels` voxels each, those parts are
// returned (each keeping the component's order; the smaller parts, stray points between them,
// belong to none); otherwise {component} unchanged. Cost: one union-find over the component's
// pairs of voxels at most ceil(reach) apart along each axis, the points of a pair read only
// when the pair's voxels are not yet joined.
std::vector<std::vector<int64_t>> SplitAtPointGaps(const VoxelGrid& grid,
                                                   const HardVoxelPoints& points,
                                                   const std::vector<int64_t>& component,
                                                   double reach, int64_t min_voxels);

// The pieces of data of a grid: its big 26-components of hard voxels, split at point gaps.
struct DataPieces {
  int count = 0;           // pieces of data
  std::vector<std::vector<int64_t>> pieces;  // their voxels, only when count >= 2
  int64_t min_voxels = 0;  // min_fraction of the hard voxels, rounded up (at least 1)
  bool split = false;      // a component was split into two or more pieces
};

// Input: a grid, its hard voxels' points (nullptr: none) and min_fraction in (0, 0.5].
// Returns the pieces of data: the 26-components of the hard voxels holding at least
// min_voxels of them, in the order of their least voxel, each replaced by SplitAtPointGaps(
// grid, *points, component, reach, min_voxels)'s parts when `points` and a reach above 0 are
// given; with two or more pieces, each lists its voxels in the order SplitAtPointGaps keeps for
// a component listed breadth first from its least voxel (26-steps in the grid's neighbour
// order): the order the waves between the pieces read. Fewer than two: the count alone.
// CancelledError when `cancel` fires.
// Cost: one pass over the grid listing the hard voxels (64 states to a word), one union-find
// over them in index order with SplitAtPointGaps's 26-neighbour pairs (each pair's points read
// only while its two voxels are not yet joined), no search through the grid. When one class
// then holds all but fewer than min_voxels of the hard voxels there is one piece and nothing
// more is done; otherwise the components are searched breadth first, and the wider pairs read
// row by row through the list around the components with two big classes.
absl::StatusOr<DataPieces> FindDataPieces(const VoxelGrid& grid, const HardVoxelPoints* points,
                                          double reach, double min_fraction,
                                          const CancelToken& cancel);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_POINT_GAP_SPLIT_H_
