// Exact-enough intersection predicates for closed triangles in 3-D, used by the mesh check
// (self-intersection count) and by the point fitting (no move may make the surface cross
// itself; membrane-quality.md recipe 3 steps 5-6).
//
// All tests run in double on coordinates that are usually float32 values. Signs come from
// orientation determinants (no epsilons, no divisions), so touching counts as intersecting.
// Every sign is exact: a floating-point filter (Shewchuk's first stage) decides most, exact
// expansion arithmetic the rest (nearly degenerate configurations: coplanar, collinear,
// touching). So every answer is a function of the positions alone, never of the order of the
// vertices in a face or of the faces in a mesh. That matters on a quantization grid, where
// such configurations are common: the same mesh decoded with another vertex order must check
// the same (with rounded signs, 1 to 3 crossings appeared or vanished that way on 3 of the 10
// real clouds). Degenerate (zero-area) triangles never intersect
// anything here; the mesh check counts them separately.
#ifndef MEMBRANE_CORE_MESH_TRIANGLE_INTERSECTION_H_
#define MEMBRANE_CORE_MESH_TRIANGLE_INTERSECTION_H_

#include <array>
#include <cstdint>

#include "core/geometry/vec3.h"

namespace membrane {

using Triangle3d = std::array<Vec3d, 3>;

// The triangle's normal (twice its area vector, CCW) computed from its vertices in sorted
// order: the same bits whichever vertex comes first.
Vec3d CanonicalNormal(const Triangle3d& t);

// What the tests need of a face, computed once per face: its plane through its smallest
// vertex, with the canonical normal (which also chooses the plane a coplanar pair is projected
// to, and tells degenerate faces) and the magnitudes that bound the rounding of a point's
// side of it.
struct FacePlane {
  Vec3d base;    // the smallest vertex (lexicographic order)
  Vec3d normal;  // CanonicalNormal
  Vec3d bound;   // per axis, the sum of the magnitudes of the two products of its component
};
FacePlane MakeFacePlane(const Triangle3d& t);

// True when two closed triangles share a point (touching included). Degenerate triangles give
// false. Meant for triangles with no vertex in common.
bool TrianglesIntersect(const Triangle3d& a, const Triangle3d& b);

// The mesh-aware test used by CheckMesh and the fitting. `ia`, `ib` are the vertex indices of
// the two faces, `a`, `b` their positions.
//   - no shared index: TrianglesIntersect;
//   - one shared vertex: true only for a NON-TRIVIAL overlap, i.e. a common point other than
//     the shared vertex (one face's opposite edge meets the other face);
//   - a shared edge: true only when the faces are coplanar and folded onto each other (apexes
//     on the same side of the edge);
//   - three shared indices (a duplicated face): true.
bool MeshTrianglesIntersect(const std::array<int32_t, 3>& ia, const Triangle3d& a,
                            const std::array<int32_t, 3>& ib, const Triangle3d& b);

// The same with the faces' planes given (MakeFacePlane of a and b): a search that tests each
// face against its dozen neighbours computes them once.
bool MeshTrianglesIntersect(const std::array<int32_t, 3>& ia, const Triangle3d& a,
                            const FacePlane& pa, const std::array<int32_t, 3>& ib,
                            const Triangle3d& b, const FacePlane& pb);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_TRIANGLE_INTERSECTION_H_
