// Surface nets on the final membrane (paper section 6; algorithm-notes 13; membrane-quality.md
// recipe 3 steps 3-4): the unfitted smooth surface. The full `smooth` surface, with the grid
// clean-up before and the fitting to the points after, is SmoothSurface() (smooth_surface.h).
#ifndef MEMBRANE_CORE_MESH_SURFACE_NETS_H_
#define MEMBRANE_CORE_MESH_SURFACE_NETS_H_

#include <cstdint>
#include <vector>

#include "core/engine/voxel_grid.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

// Input: a voxel grid; inside = non-outside, lattice = voxel centres; the array's outer layer
// must be outside (the membrane's padding).
// Output, in model units: one quad per lattice edge joining an inside and an outside voxel
// centre; in each 2x2x2 cell of voxel centres one vertex per fan of quads (voxel_boundary.h:
// on an ambiguous lattice face the two quads sharing the OUTSIDE point are paired), placed at
// the mean of the fan's edge crossings, so every vertex lies inside its cell, within
// sqrt(3)/2 voxel of the cell's centre; a midpoint vertex where the two pairs of an ambiguous
// face end on the same two vertices; each quad split along the flatter diagonal, a quad with a
// midpoint fanned from it.
// In rare configurations (a few in a thousand random 10^3 solids) those positions make two
// triangles cross; the vertices of crossing triangles are then moved back toward an embedded
// fallback with the same faces, the cuberille's positions (lattice corners, split copies 0.2
// voxel toward their outside octants, midpoints 0.2 voxel off their edge; two voxels meeting at
// a corner pull it 0.25 voxel in), halfway up to 6 times, then all the way (crossing_repair.h).
// The mesh is closed, manifold, oriented outward (counter-clockwise seen from outside) and
// free of self-intersections. Its shells and genus are the (26,6) topology of the solid
// wherever no two solid voxels meet only at a corner; bridge such contacts first
// (diagonal_bridging.h). `stats` may be null.
struct SurfaceNetsStats {
  int64_t corner_contacts = 0;    // corner-only contacts (each splits a shell locally)
  int64_t repaired_vertices = 0;  // vertex moves made by the crossing repair
  int64_t crossings_left = 0;     // 0 unless the fallback itself crossed (never seen)
};
TriangleMesh SurfaceNets(const VoxelGrid& grid, SurfaceNetsStats* stats = nullptr);

// SurfaceNets() without its crossing repair: the mesh as placed (which may cross itself in the
// rare configurations above) and, per vertex, the embedded fallback position. For a caller that
// searches the whole mesh for crossings anyway (FitToPoints in SmoothSurface), so the search
// runs once instead of twice. The voxel boundary, the placement, the triangulation and the
// Morton order run on `threads` threads (the same mesh for any count).
struct UnrepairedSurfaceNets {
  TriangleMesh mesh;
  std::vector<Point3f> fallback;
  int64_t corner_contacts = 0;
};
UnrepairedSurfaceNets SurfaceNetsBeforeRepair(const VoxelGrid& grid, int threads = 1);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_SURFACE_NETS_H_
