// Silhouette pre-shrink (paper Fig. 21b; algorithm-notes 3): the initial membrane is shrunk to
// the visual hull of the hard voxels seen along the three axes. Off by default (notes 3).
#ifndef MEMBRANE_CORE_ENGINE_SILHOUETTE_H_
#define MEMBRANE_CORE_ENGINE_SILHOUETTE_H_

#include <cstdint>

#include "core/engine/voxel_grid.h"

namespace membrane {

// Turns OUTSIDE (generation 0) every voxel of the initial membrane's interior that some axis
// projection of the hard voxels, dilated by one pixel (so 1-pixel sampling gaps carve no
// tunnels), does not cover; then the non-outside voxels 26-adjacent to outside become BOUNDARY.
// `grid` must be as Voxelize built it. Returns the number of voxels made outside.
int64_t SilhouettePreshrink(VoxelGrid& grid);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_SILHOUETTE_H_
