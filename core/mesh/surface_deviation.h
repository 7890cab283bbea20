// How far a set of points lies from a mesh: the error a decimation adds, measured from the
// vertices of the surface before it to the decimated surface (a one-sided Hausdorff distance
// sampled at those vertices).
#ifndef MEMBRANE_CORE_MESH_SURFACE_DEVIATION_H_
#define MEMBRANE_CORE_MESH_SURFACE_DEVIATION_H_

#include <cstdint>
#include <vector>

#include "core/base/cancel_token.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

struct SurfaceDeviation {
  int64_t points = 0;  // points measured
  double max = 0;      // largest distance to the mesh, model units
  double mean = 0;     // mean distance, model units
};

// The exact distance from each of `points` to the nearest face of `mesh` (faces with valid
// indices; degenerate ones count as their segments or points), summarised. Faces are entered
// in a uniform grid of cells of about the mean edge, searched ring by ring around each
// point until no unseen face can be nearer. `threads` (<= 1: the calling thread) share the
// points; the result does not depend on it. All zero for no points or a mesh without faces.
// `cancel` is polled every few thousand points; once it fires the result covers only the
// points measured.
SurfaceDeviation MeasureDeviation(const std::vector<Point3f>& points, const TriangleMesh& mesh,
                                  int threads = 1,
                                  const CancelToken& cancel = CancelToken::Never());

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_SURFACE_DEVIATION_H_
