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
// each coordinate then lies within 1/64 voxel of its float32 value, under the surface's own
// error on clean clouds (0.01-0.02 voxel: the rocker arm's uniform cloud, Chamfer 0.0053 % of
// the diagonal, reads 0.0095 at an 11-bit step of 0.11 voxel and 0.0059 at 0.028;
// tests/bench/2026-12-05-output-step.txt). Coarser steps also cost the surface its time: the
// fit's snapped vertices cross each other's faces by the thousands (a 0.64-voxel step: 118,158
// crossing pairs and 86 searches against 301 and 2 at 0.16).
inline constexpr double kMaxOutputStepVoxels = 1.0 / 32;

// The fewest bits, at least `bits` and at most 30, whose OutputGrid over `membrane` has a
// step of at most kMaxOutputStepVoxels voxels; 0 (lossless) stays 0. From 11: 13 bits on the
// grids of 100k-point clouds (about 150 voxels wide), 16 on a 1295-voxel grid.
int OutputBitsForVoxel(const VoxelGrid& membrane, int bits);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_OUTPUT_GRID_H_
