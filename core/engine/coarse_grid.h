// A voxelized grid seen k times coarser: the interior guard's coarse membrane
// (interior_guard.h) and the shrink's big plates (coarse_plates.h) both work on it.
#ifndef MEMBRANE_CORE_ENGINE_COARSE_GRID_H_
#define MEMBRANE_CORE_ENGINE_COARSE_GRID_H_

#include "core/engine/voxel_grid.h"

namespace membrane {

// The grid `k` times coarser over the same data region, as Voxelize() leaves a grid: padding
// outside, the data region inside with its outer layer boundary, a voxel hard when any of its
// fine voxels is, else frozen when any of its fine voxels is (the interior guard's: the big
// plates on the coarse grid stop at the interior it holds, as the fine plates do). Coarse
// voxel kPadding + c of an axis covers the fine voxels kPadding + c k up to k of them, the last
// one clipped at the data region's end. `fine` must be as Voxelize() left it (no outside voxel
// in its data region), frozen voxels allowed. A coarse z plane a task on `threads`.
VoxelGrid CoarseGrid(const VoxelGrid& fine, int k, int threads);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_COARSE_GRID_H_
