// The plane of voxels off the array border, shared by the place finder and the closed form.
#ifndef MEMBRANE_CORE_ENGINE_INTERIOR_PLANE_H_
#define MEMBRANE_CORE_ENGINE_INTERIOR_PLANE_H_

#include "core/engine/flat_bitset.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

// A bitset over `grid`'s voxels, set for every voxel not on the outermost array layer. Plates
// and plate-sized runs must stay off that layer, so a run of set bits never wraps around a
// row or a plane of the flat index.
FlatBitset InteriorPlane(const VoxelGrid& grid);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_INTERIOR_PLANE_H_
