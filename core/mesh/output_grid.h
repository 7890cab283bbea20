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

// The largest step of an output grid chosen for the voxel (OutputBitsForVoxel), in voxels:
// each coordinate then lies within 0.2 voxel of its float32 value. On coarser grids the fit's
// vertices, snapped, cross each other's faces by the thousands and the crossing searches
// after the fit take most of the surface's time (a 0.64-voxel step: 118,158 crossing pairs and
// 86 searches against 301 and 2 at 0.16; tests/bench/2026-12-03-surface-scale.txt).
inline constexpr double kMaxOutputStepVoxels = 0.4;

// The fewest bits, at least `bits` and at most 30, whose OutputGrid over `membrane` has a
// step of at most kMaxOutputStepVoxels voxels; 0 (lossless) stays 0. Only grids wider than
// about 800 voxels need more than 11 bits.
int OutputBitsForVoxel(const VoxelGrid& membrane, int bits);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_OUTPUT_GRID_H_
