// The faces around each vertex of a mesh (its star), as one array in vertex order: the fit's
// index for its moves' local checks (point_fitting.cc).
#ifndef MEMBRANE_CORE_MESH_VERTEX_STARS_H_
#define MEMBRANE_CORE_MESH_VERTEX_STARS_H_

#include <array>
#include <cstdint>
#include <vector>

#include "core/engine/arena_allocator.h"

namespace membrane {

// Left unset when made: the ranges on the threads write them first (their page faults
// included).
using StarArray = std::vector<int32_t, UnfilledAllocator<int32_t>>;

struct VertexStars {
  // faces[start[v] .. start[v + 1]) are the faces that use vertex v, in increasing order (a
  // face using v twice is listed twice). start has num_vertices + 1 entries.
  StarArray start, faces;
};

// Input: faces whose vertex ids are in [0, num_vertices). With threads > 1 and 2^16 vertices or
// more, ranges of faces count their vertices' uses on the threads, one array of counts a range,
// and place their faces from the counts' prefix (a vertex's faces from earlier ranges first):
// the one-thread counting sort's arrays for any thread count.
VertexStars FacesAroundVertices(const std::vector<std::array<int32_t, 3>>& faces,
                                int32_t num_vertices, int threads);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_VERTEX_STARS_H_
