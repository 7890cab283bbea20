// Decimation of a closed surface to a face budget by edge collapses in the order of the quadric
// error metric (Garland and Heckbert 1997), keeping every promise of the surface step: closed,
// 2-manifold, outward, no face crossing another, the same shells and genus (issue 21's
// `--target-faces`; docs/surface-decisions.md, "Decimation").
#ifndef MEMBRANE_CORE_MESH_MESH_DECIMATION_H_
#define MEMBRANE_CORE_MESH_MESH_DECIMATION_H_

#include <cstdint>

#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/base/progress_meter.h"
#include "core/geometry/position_grid.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

// The fewest faces a decimation accepts as a target.
inline constexpr int64_t kMinTargetFaces = 4;

struct DecimationOptions {
  int64_t target_faces = 0;  // >= kMinTargetFaces
  // Every vertex a collapse places lies on this grid (PositionGrid::Snap), so that the mesh
  // written is the mesh checked; lossless: float32.
  PositionGrid grid;
};

struct DecimationStats {
  int64_t target_faces = 0;
  int64_t faces_before = 0, faces_after = 0;
  int64_t vertices_before = 0, vertices_after = 0;
  // Collapses made; edges whose collapse a guarantee refused (counted each time one is
  // tried); passes over all remaining edges (a pass ends when its queue runs dry).
  int64_t collapses = 0;
  int64_t refused = 0;
  int passes = 0;
};

// The fewest faces a closed orientable triangulated surface of genus `genus` (>= 0) can have:
// 2 V - 4 + 4 g with V the least vertex count of such a triangulation (Jungerman and Ringel:
// ceil((7 + sqrt(1 + 48 g)) / 2), 10 for g = 2). 4 for a sphere, 14 for a torus.
int64_t MinimumFacesOfGenus(int genus);

// Decimates `mesh` in place to at most options.target_faces faces, or to as few as the
// guarantees allow. Each step collapses the edge of least quadric error (area-weighted planes
// of the faces each vertex has absorbed) to the point that minimises it, snapped to
// options.grid. A collapse is made only when
//   - its edge passes the link condition (the two vertices share exactly the two neighbours
//     opposite the edge) and neither opposite vertex has only three faces (a tetrahedron):
//     the mesh stays a closed 2-manifold of the same topology;
//   - none of the faces it moves turns over or past 78 degrees, becomes degenerate, or gets
//     much thinner than it was;
//   - none of the faces it moves meets another face (the exact predicates of
//     MeshTrianglesIntersect, against every face near them in a grid of face boxes).
// When the queue runs dry above the target, it is filled again from the remaining edges, until
// a pass collapses nothing. Faces and vertices keep their relative order; removed ones are
// dropped and the faces renumbered.
//
// Requires a closed, oriented, manifold mesh (every directed edge once, its reverse once,
// each vertex's faces one fan); faces crossing each other already stay as they are.
// Returns the counts. Errors: InvalidArgument when options.target_faces is below
// kMinTargetFaces or below the fewest faces the mesh's shells can have (the sum of
// MinimumFacesOfGenus over them), naming both; FailedPrecondition when the mesh is not closed,
// oriented and manifold (it is left unchanged); Cancelled when `cancel` fires (polled every
// few thousand collapses; the mesh is then valid but partly decimated). `progress` counts the
// faces removed against the faces above the target, as often as `cancel` is polled.
absl::StatusOr<DecimationStats> DecimateMesh(TriangleMesh& mesh, const DecimationOptions& options,
                                             const CancelToken& cancel = CancelToken::Never(),
                                             ProgressRange progress = ProgressRange());

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_MESH_DECIMATION_H_
