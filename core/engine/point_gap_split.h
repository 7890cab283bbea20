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

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_POINT_GAP_SPLIT_H_
