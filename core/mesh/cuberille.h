// Cuberille surface of a membrane: the voxel faces between the solid and the outside
// (paper section 6, "the outside faces of the 6-connected boundary voxel sets"), made a closed
// 2-manifold with the (26,6) topology of the voxel solid (algorithm-notes 13).
#ifndef MEMBRANE_CORE_MESH_CUBERILLE_H_
#define MEMBRANE_CORE_MESH_CUBERILLE_H_

#include "core/engine/voxel_grid.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

// Input: a membrane grid (the solid is every non-outside voxel; the array's outer layer must be
// outside, which the 2 padding layers guarantee).
// Output: two triangles per solid/outside voxel face, counter-clockwise seen from outside,
// vertices in model units (origin + lattice corner * voxel_size). Where the solid is not a
// manifold the surface is split (voxel_boundary.h) and the split vertices moved slightly off
// the lattice corner, toward the outside region they bound, so that the two sheets do not touch:
//   - a vertex whose corner has several fans: 0.2 voxel toward its outside octants;
//   - a midpoint on an edge where two solid voxels touch: 0.2 voxel toward its outside voxel;
//   - two solid voxels touching only at a corner: both corners cut back 0.25 voxel along their
//     3 edges, and the two small triangles joined by a tube of 6 triangles through the corner.
// The result is closed, manifold, oriented outward and free of self-intersections, with one
// shell per 26-component of the solid and the genus of the union of its closed voxel cubes.
// An all-outside grid gives an empty mesh.
TriangleMesh Cuberille(const VoxelGrid& membrane);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_CUBERILLE_H_
