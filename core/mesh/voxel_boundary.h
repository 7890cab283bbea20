// The manifold boundary of a (26,6) voxel solid, as combinatorics shared by the cuberille and
// the surface nets (paper section 6; algorithm-notes 13; membrane-quality.md recipe 3 step 3).
//
// The two surfaces have the same faces: one quad per pair of face-adjacent voxels (solid,
// outside), with a vertex at each lattice corner (cuberille) or in each 2x2x2 cell of voxel
// centres (surface nets), which is the same thing. Where solid voxels touch only along an
// edge, four quads meet at one lattice edge; we pair the two quads that bound the same OUTSIDE
// voxel, which keeps the two solid voxels joined (26-connectivity of the solid) and the two
// outside voxels apart (6-connectivity of the outside). Around each lattice corner the quads
// then fall into fans; each fan gets its own vertex. Where both pairs of an edge end on the
// same two vertices, each pair gets a midpoint vertex so no edge is used by four triangles.
//
// What this does not resolve: two solid voxels meeting only at a corner (a 2x2x2 block with
// exactly two solid voxels on a body diagonal). Their fans get two vertices, so locally the
// surface has two sheets instead of one: the cuberille joins them with a small tube, the
// smooth surface bridges them beforehand (diagonal_bridging.h).
#ifndef MEMBRANE_CORE_MESH_VOXEL_BOUNDARY_H_
#define MEMBRANE_CORE_MESH_VOXEL_BOUNDARY_H_

#include <array>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "core/engine/unset_construct.h"
#include "core/engine/voxel_grid.h"
#include "core/geometry/vec3.h"

namespace membrane {

// Lattice corner `c` in lattice units (voxels, from the array's corner).
inline Vec3d LatticePosition(const Coord& c) {
  return {static_cast<double>(c.x), static_cast<double>(c.y), static_cast<double>(c.z)};
}

// The boundary's arrays: the join of ExtractVoxelBoundaryOnSlabs sizes them, then writes every
// element on the threads before any is read, so that each thread takes the page faults of
// what it writes (a value-initializing resize filled them on the calling thread, and the
// elements' member initializers would still be written there).
template <typename T>
using BoundaryArray = std::vector<T, UnsetConstruct<std::allocator<T>, true>>;

// Lattice corner (x, y, z) sits at model position origin + (x, y, z) * voxel_size, the lowest
// corner of voxel (x, y, z). The 8 voxels around it are its octants: octant o has bit k set when
// it lies on the + side of the corner along axis k. A corner's "config" has bit o set when
// octant o is solid (non-outside).
struct VoxelBoundary {
  // One vertex per fan of quads around a lattice corner.
  struct FanVertex {
    Coord corner;
    uint8_t config = 0;
    uint8_t fan = 0;  // index of the fan within its corner's config
  };
  // A vertex splitting one copy of a lattice edge whose two quad pairs would otherwise share
  // both end vertices.
  struct EdgeMidpoint {
    std::array<int32_t, 2> ends{};  // fan-vertex ids at the edge's two ends
    Coord edge_start;               // lower lattice corner of the edge
    int axis = 0;                   // direction of the edge
    Coord outside;                  // the outside voxel both quads of the pair bound
  };
  // One quad: the face between solid voxel `solid` and its outside neighbour along `axis`,
  // on the + side when `positive`.
  struct Quad {
    Coord solid;
    int8_t axis = 0;
    bool positive = false;
    // Vertex ids of the 4 lattice corners, counter-clockwise seen from the outside voxel.
    std::array<int32_t, 4> corners{};
    // Vertex id inserted on the edge corners[k] -> corners[k+1], or -1.
    std::array<int32_t, 4> midpoints{-1, -1, -1, -1};
  };

  // Vertex ids: [0, fan_vertices.size()) are fan vertices, then midpoints in order.
  BoundaryArray<FanVertex> fan_vertices;
  BoundaryArray<EdgeMidpoint> midpoints;
  BoundaryArray<Quad> quads;
  // Lattice corners where two solid voxels meet only at that corner.
  int64_t corner_contacts = 0;

  int64_t num_vertices() const {
    return static_cast<int64_t>(fan_vertices.size() + midpoints.size());
  }
};

// Input: a voxel grid whose outer layer is outside (membranes have 2 layers of padding).
// Output: every quad between a non-outside and an outside voxel, with fan-split corner vertices
// and edge midpoints as described above. Any placement of the vertices near their lattice
// corner (resp. cell) gives a closed, edge- and vertex-manifold mesh whose quads are oriented
// outward; its shells and genus are those of the (26,6) solid wherever `corner_contacts` is 0.
// Cost: O(voxels) scan plus O(quads) work. With 2 threads or more, on grids of 2^24 voxels and
// more, both run on slabs of z layers on the threads (ExtractVoxelBoundaryOnSlabs); otherwise
// the scan runs layer by layer on the threads and the quads are made on the calling thread.
// The result is the same for any thread count.
VoxelBoundary ExtractVoxelBoundary(const VoxelGrid& grid, int threads = 1);

// ExtractVoxelBoundary's pass on `slabs` slabs of z layers (clamped to 1 .. one a layer) on
// `threads` threads, whatever the grid's size: each slab numbers the quads, fan vertices and
// midpoints it makes as the one-thread pass does, taking the corners and midpoints of its lowest
// lattice plane that the layer below makes from the slab below; the slabs are then joined in
// order with their ids offset. The same result as the one-thread pass.
VoxelBoundary ExtractVoxelBoundaryOnSlabs(const VoxelGrid& grid, int threads, int slabs);

// The lattice corners of `quad`, in the order of quad.corners.
std::array<Coord, 4> QuadCornerCoords(const VoxelBoundary::Quad& quad);

// Facts about a corner config, from a 256-entry table.
int NumFans(int config);
// True when the config is exactly two solid octants on a body diagonal.
bool IsCornerContact(int config);
// Mean of the centres of the fan's quads, relative to the corner, in voxels: the surface-nets
// vertex of that fan (the quads' centres are where the lattice edges of the cell cross the
// surface).
Vec3d FanCentroid(int config, int fan);
// Sum of the unit octant directions (+-1 per axis) of the outside octants the fan's quads
// bound: where the fan's vertex may move without touching another fan of the same corner.
Vec3d FanOutsideDirection(int config, int fan);
// For a corner contact, the solid octant (0..7) enclosed by fan `fan`.
int FanSolidOctant(int config, int fan);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_VOXEL_BOUNDARY_H_
