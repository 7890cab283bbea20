// The promises every surface of a membrane must keep, as one test helper.
#ifndef MEMBRANE_TESTS_MESH_SURFACE_EXPECTATIONS_H_
#define MEMBRANE_TESTS_MESH_SURFACE_EXPECTATIONS_H_

#include <vector>

#include "core/geometry/triangle_mesh.h"
#include "core/mesh/mesh_check.h"

namespace membrane::testing {

// Closed, manifold, oriented, positive volume, no self-intersection, no degenerate face, and
// `shells` shells whose genus, sorted, is `genus` sorted. Reports failures with EXPECT_*.
void ExpectValidSurface(const TriangleMesh& mesh, int shells, std::vector<int> genus);

// The same promises read from a report CheckMesh already made (tests that keep the report
// beside other figures of the run).
void ExpectValidReport(const MeshReport& report, int shells, std::vector<int> genus);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_MESH_SURFACE_EXPECTATIONS_H_
