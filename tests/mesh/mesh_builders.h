// Small analytic meshes for the mesh-check tests.
#ifndef MEMBRANE_TESTS_MESH_MESH_BUILDERS_H_
#define MEMBRANE_TESTS_MESH_MESH_BUILDERS_H_

#include <array>

#include "core/geometry/triangle_mesh.h"

namespace membrane::testing {

// Axis-aligned cube [lo, lo + size]^3, 12 triangles, outward.
TriangleMesh CubeMesh(std::array<float, 3> lo = {0, 0, 0}, float size = 1);
// Torus around z, `rings` x `segments` quads split in two, outward.
TriangleMesh TorusMesh(int rings, int segments, float major_radius, float minor_radius);
// Concatenation of two meshes.
TriangleMesh Concat(const TriangleMesh& a, const TriangleMesh& b);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_MESH_MESH_BUILDERS_H_
