// The hole caps' gap search (hole_caps.h): which vertices of a mesh have no input point near
// them, on several threads.
#ifndef MEMBRANE_CORE_MESH_GAP_VERTICES_H_
#define MEMBRANE_CORE_MESH_GAP_VERTICES_H_

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/types/span.h"
#include "core/base/cancel_token.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"
#include "core/mesh/point_row_grid.h"

namespace membrane {

struct GapVertices {
  std::vector<char> gap;  // per vertex: 1 when no point lies within the radius
  int64_t count = 0;      // vertices with gap 1
  // histogram[k]: the vertices with k points within the radius (k >= 1; the last bin holds
  // every larger count); histogram[0] stays 0.
  std::vector<int64_t> histogram;
  // The points with no vertex within the radius, in the order of a PointRowGrid of `points`
  // with cells of the radius (only when asked for and `count` reaches the caller's minimum).
  std::vector<Point3f> remote;
};

// Input: `mesh` in model units, `points` the input cloud, `radius` > 0 (model units),
// `last_bin` >= 1 the histogram's last bin. Output: each vertex's gap flag, their count, the
// histogram of the others' point counts and, when `collect_remote` and at least
// `remote_min_count` vertices are gaps, the remote points (a caller with fewer gaps has no use
// for them: a mesh without holes holds no list of its points). The
// vertices are split into blocks over `threads` (<= 1: the calling thread); the result is the
// same for any thread count. `grid`, if not null, is the PointRowGrid of `points` with cells of
// `radius` (built with any thread count), read instead of building one. Errors: Cancelled when
// `cancel` fired.
absl::StatusOr<GapVertices> FindGapVertices(const TriangleMesh& mesh,
                                            absl::Span<const Point3f> points, double radius,
                                            int last_bin, bool collect_remote,
                                            int64_t remote_min_count, int threads,
                                            const CancelToken& cancel,
                                            const PointRowGrid* grid = nullptr);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_GAP_VERTICES_H_
