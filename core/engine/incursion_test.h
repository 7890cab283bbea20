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
// the box spanning A..B along the axis and one voxel either side across it. `index` must lie at
// least max_run voxels from the array border (the padding guarantees it for hard voxels when
// max_run <= 3).
bool ThickWallIncursion(const VoxelGrid& grid, int64_t index, int max_run);

// Either test fires (the thick one only when max_run > 1).
inline bool IncursionAt(const VoxelGrid& grid, int64_t index, int max_run) {
  return PaperIncursion(grid, index) || (max_run > 1 && ThickWallIncursion(grid, index, max_run));
}

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_INCURSION_TEST_H_
