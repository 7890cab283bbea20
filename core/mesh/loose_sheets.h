// Loose-sheet removal before the smooth surface (membrane-quality.md recipe 3 step 1).
//
// A 26-component of membrane voxels with no inside voxel is a sheet left where a chain was
// undone (frozen walls, problem E of algorithm-notes), not a solid with volume: its surface
// would be a flat double layer far from the data. The membrane keeps it; only the surface
// drops it, so this runs on a copy of the final grid.
#ifndef MEMBRANE_CORE_MESH_LOOSE_SHEETS_H_
#define MEMBRANE_CORE_MESH_LOOSE_SHEETS_H_

#include <cstdint>

#include "core/engine/voxel_grid.h"

namespace membrane {

// Input: a membrane grid (outside / boundary / inside states; the array border outside).
// Effect: every 26-component of non-outside voxels that holds no inside voxel becomes
// OutsideState(0). Components with an inside voxel are untouched.
// Returns the number of voxels removed. O(voxels). `threads` (<= 1: the calling thread) share
// the scan of the grid, plane by plane, and on large grids (2^24 voxels and 16 planes or more)
// the flood, as slabs of z planes. The grid is the same for any count.
int64_t RemoveLooseSheets(VoxelGrid& grid, int threads = 1);

// The same, the flood cut into `slabs` slabs of the inner z planes (clamped to [1, planes])
// on `threads` threads whatever the grid's size: RemoveLooseSheets' threaded path, callable on
// small grids and many slabs (tests).
int64_t RemoveLooseSheetsOnSlabs(VoxelGrid& grid, int threads, int slabs);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_LOOSE_SHEETS_H_
