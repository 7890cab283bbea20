// The quantization grid a surface of a membrane is delivered on (see position_grid.h).
#ifndef MEMBRANE_CORE_MESH_OUTPUT_GRID_H_
#define MEMBRANE_CORE_MESH_OUTPUT_GRID_H_

#include "core/engine/voxel_grid.h"
#include "core/geometry/position_grid.h"

namespace membrane {

// The grid of `bits` (0: lossless) whose box is `membrane`'s, rounded outward to values that
// Draco's options keep (DecimalSafeBound): every surface vertex lies in the grid's voxels, and
// the box is known before the surface is built (the mesh's own bounding box is not, and a grid
// taken from it would move under the fit).
PositionGrid OutputGrid(const VoxelGrid& membrane, int bits);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_OUTPUT_GRID_H_
