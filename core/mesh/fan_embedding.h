// A cheap sufficient test that the triangles around one vertex of a closed manifold mesh do not
// overlap each other: the fast path of the fit's per-move check (point_fitting.h,
// membrane-quality.md recipe 3 step 5), where the exhaustive test of every pair of the moved
// vertex's triangles would be a third of the fit's cost.
#ifndef MEMBRANE_CORE_MESH_FAN_EMBEDDING_H_
#define MEMBRANE_CORE_MESH_FAN_EMBEDDING_H_

#include <array>
#include <cstdint>
#include <vector>

#include "absl/types/span.h"
#include "core/geometry/triangle_mesh.h"
#include "core/geometry/vec3.h"
#include "core/mesh/vertex_stars.h"

namespace membrane {

// Input: `centre` a vertex and `ring` its k >= 3 neighbours in fan order, i.e. its faces are
// (centre, ring[i], ring[(i + 1) % k]) up to rotation, all in the mesh's orientation.
// Returns true only when it proves, with margins far above double rounding, that seen along the
// sum N of the faces' normals every face is positively oriented (normal . N > 0) and the ring
// winds exactly once around the centre. The faces then tile a disc around the centre in that
// projection, so no two of them share a point other than the centre and, for neighbours, their
// common edge: MeshTrianglesIntersect is false for every pair of them, and none is degenerate.
// False means "not proven" (a fold, a cone too sharp for one projection, a near-degenerate
// face); the caller then tests the pairs one by one.
bool FanIsEmbedded(const Vec3d& centre, absl::Span<const Vec3d> ring);

// The fans of a closed mesh, for FanIsEmbedded: for each vertex its neighbours in fan order
// (ring(v)), or an empty ring when its faces do not form one closed fan (a non-manifold or
// boundary vertex, a vertex in a duplicated face), which is then never proven embedded.
class MeshFans {
 public:
  explicit MeshFans(const TriangleMesh& mesh);
  // The same rings of a mesh's `faces`, every vertex id of them in range, from `stars`, their
  // FacesAroundVertices (for any thread count): ranges of vertices walk their fans on `threads`
  // (<= 1: the calling thread), from 2^16 vertices on. A vertex's ring depends on its star
  // alone, so it is the one MeshFans(mesh) gives, for any thread count.
  MeshFans(const std::vector<std::array<int32_t, 3>>& faces, const VertexStars& stars,
           int threads);
  absl::Span<const int32_t> ring(int32_t v) const {
    return absl::MakeConstSpan(ring_.data() + start_[v], size_[v]);
  }

 private:
  void WalkFans(const std::vector<std::array<int32_t, 3>>& faces, const VertexStars& stars,
                int threads);

  // Vertex v's ring is ring_[start_[v] .. start_[v] + size_[v]), where its star is in the
  // stars' arrays; size_[v] is 0 when its faces make no single closed fan.
  StarArray start_, size_, ring_;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_FAN_EMBEDDING_H_
