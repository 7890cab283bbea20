// Diagonal-contact bridging before the smooth surface (membrane-quality.md recipe 3 step 2).
//
// Two solid voxels meeting only at a corner are one 26-component, but no surface through the
// 2x2x2 cell of voxel centres around that corner can join them (the cell's 6 other voxels are
// outside). Adding one of those 6 voxels when it is (26,6)-simple joins the two through a face
// without changing the solid's topology, so the surface nets then has the membrane's shells and
// genus. Runs on the copy of the grid that feeds the surface.
#ifndef MEMBRANE_CORE_MESH_DIAGONAL_BRIDGING_H_
#define MEMBRANE_CORE_MESH_DIAGONAL_BRIDGING_H_

#include <cstdint>

#include "core/engine/voxel_grid.h"

namespace membrane {

struct BridgingResult {
  int64_t added = 0;      // voxels made solid (kBoundarySoft)
  int64_t remaining = 0;  // corner-only contacts left after the last scan
};

// Input: a grid (solid = non-outside; the array border outside).
// Effect: up to `max_scans` scans over every 2x2x2 block holding exactly two solid voxels on a
// body diagonal; in each, the first of the other six in index order that is (26,6)-simple
// (IsSimple of its 3x3x3 object mask) and not on the array border becomes kBoundarySoft.
// Stops early after a scan that finds no contact. Shells and genus of the solid never change.
// A scan's search runs on `threads` (>= 1) until its first bridge: the same bridges for any
// thread count.
BridgingResult BridgeDiagonalContacts(VoxelGrid& grid, int max_scans = 3, int threads = 1);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_DIAGONAL_BRIDGING_H_
