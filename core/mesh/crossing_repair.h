// Back-off repair of self-intersections: the vertices of crossing triangles move toward
// positions known to be embedded until nothing crosses (the back-off of membrane-quality.md
// recipe 3 step 6). SurfaceNets() uses it to fall back toward the cuberille geometry of the
// same faces; FitToPoints() does the same inside its own final check.
#ifndef MEMBRANE_CORE_MESH_CROSSING_REPAIR_H_
#define MEMBRANE_CORE_MESH_CROSSING_REPAIR_H_

#include <cstdint>
#include <vector>

#include "core/geometry/triangle_mesh.h"

namespace membrane {

struct CrossingRepair {
  int64_t checks = 0;          // whole-mesh intersection searches run
  int64_t moved_vertices = 0;  // vertex moves, summed over the rounds
  int64_t crossings_left = 0;  // pairs still crossing at the end (0 when `safe` is embedded)
};

// Input: `mesh`, and `safe` (one position per vertex, model units) at which the mesh with the
// same faces is free of self-intersections.
// Effect: finds every intersecting face pair (FindIntersectingFaces); moves each vertex of
// those faces halfway toward its safe position, up to `halvings` times, then all the way;
// repeats until a search finds nothing. Vertices of faces that never cross do not move.
// After: no self-intersection when `safe` has none; every vertex on the segment between its
// old and its safe position (rounded to float32).
CrossingRepair RepairCrossings(TriangleMesh& mesh, const std::vector<Point3f>& safe,
                               int halvings = 6);

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_CROSSING_REPAIR_H_
