// Homotopic cave filling, for the surface only (membrane-quality.md recipe 2; problem E of
// algorithm-notes).
//
// A cave is outside space reached from the exterior only through passages narrower than 3
// voxels: the hollow a plate dug behind a data hole, or a crevice the plates could not enter.
// Its surface lies far from the data. Filling it with simple voxels only (the (26,6) test of
// decision 12) removes that surface but never closes a real handle or pocket into a different
// topology, which a plain fill did (a pocket became a handle on the spot scan).
// The membrane and its reported topology stay as they are: this runs on a copy of the grid.
#ifndef MEMBRANE_CORE_MESH_CAVE_FILLING_H_
#define MEMBRANE_CORE_MESH_CAVE_FILLING_H_

#include <cstdint>

#include "core/engine/voxel_grid.h"

namespace membrane {

// Input: a grid (solid = non-outside), with at least one outside layer on the array border.
// Effect:
//   1. O = outside voxels; E = O eroded by the 3x3x3 box (voxels beyond the array count as
//      outside); R = the part of E 6-connected to the array border; D = R dilated by the box.
//   2. Caves = O minus D.
//   3. Passes over the cave voxels in index order, making each one kBoundarySoft when it is
//      (26,6)-simple against the current solid, until a pass adds nothing.
// Returns the number of voxels filled. Shells and genus of the solid never change.
// Cost: O(voxels / 64) words for steps 1-2 (the masks are bits: two of grid size at a time, a
// quarter byte a voxel) and one read of the states, then O(cave voxels) per pass.
// `threads` (<= 1: the calling thread) share step 1's box filters, its flood (on large grids,
// as slabs of z planes) and step 2, plane by plane; step 3 runs on the calling thread. The grid
// is the same for any count.
int64_t FillCaves(VoxelGrid& grid, int threads = 1);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_CAVE_FILLING_H_
