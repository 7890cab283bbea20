// The incursion test (paper section 4.2; algorithm-notes 7 and 15, membrane-quality recipe 1).
#ifndef MEMBRANE_CORE_ENGINE_INCURSION_TEST_H_
#define MEMBRANE_CORE_ENGINE_INCURSION_TEST_H_

#include <cstdint>

#include "core/engine/voxel_grid.h"

namespace membrane {

// The paper's test on the hard or frozen, non-outside voxel at `index`: for some axis, its two
// face neighbours A and B are outside with different generations and are not local-arc
// connected (no 6-path of outside voxels joins them inside the 3x3x3 block around the voxel).
// `index` must lie at least one voxel from the array border.
bool PaperIncursion(const VoxelGrid& grid, int64_t index);

// The thick-wall extension: for some axis, the run of hard or frozen non-outside voxels through
// the voxel (at most `max_run` long) is longer than one, the voxels A and B just beyond its ends
// are outside with different generations, and no 6-path of outside voxels joins A and B inside
// the box spanning A..B along the axis and one voxel either side across it, nor (when
// detour > 0) inside the cube of radius `detour` around the voxel: A and B joined around the
// run within a few voxels are the two sides of a thin part, not a wall with a dig behind it.
// A or B outside that cube counts as not joined; the cube is clipped to the array. `index`
// must lie at least max_run voxels from the array border (the padding guarantees it for hard
// voxels when max_run <= 3).
bool ThickWallIncursion(const VoxelGrid& grid, int64_t index, int max_run, int detour);

// Either test fires (the thick one only when max_run > 1).
inline bool IncursionAt(const VoxelGrid& grid, int64_t index, int max_run, int detour) {
  return PaperIncursion(grid, index) ||
         (max_run > 1 && ThickWallIncursion(grid, index, max_run, detour));
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_INCURSION_TEST_H_
