// The plane of voxels off the array border, shared by the place finder and the closed form.
#ifndef MEMBRANE_CORE_ENGINE_INTERIOR_PLANE_H_
#define MEMBRANE_CORE_ENGINE_INTERIOR_PLANE_H_

#include <array>

#include "core/engine/flat_bitset.h"
#include "core/engine/voxel_grid.h"

namespace membrane {

// A bitset over the voxels of a box of `dims` (flat index x + nx * (y + ny * z)), set for
// every voxel not on the outermost layer. Plates and plate-sized runs must stay off that
// layer, so a run of set bits never wraps around a row or a plane of the flat index.
FlatBitset InteriorPlane(const std::array<int, 3>& dims);

// The same over `grid`'s voxels.
inline FlatBitset InteriorPlane(const VoxelGrid& grid) { return InteriorPlane(grid.dims()); }

// Clears the bits of `plane` (over a box of `dims`) on the outermost layer: the same bits as
// And(InteriorPlane(dims)), without a plane of its own (a grid-sized plane is 271 MB on a
// 10M-point torus's 2.2e9 voxels) and touching only the layer's words.
void ClearArrayBorder(const std::array<int, 3>& dims, FlatBitset& plane);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_INTERIOR_PLANE_H_
