// The vertex normals the PLY and OBJ mesh writers add, so that viewers shade the surface
// smoothly instead of guessing normals or showing facets.
#ifndef MEMBRANE_CORE_IO_VERTEX_NORMALS_H_
#define MEMBRANE_CORE_IO_VERTEX_NORMALS_H_

#include <vector>

#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

// One unit normal per vertex of `mesh`: the sum of its faces' area vectors (each face's
// counter-clockwise normal times its area), normalized. On the core's meshes, whose faces
// are counter-clockwise seen from outside, it points outward. (0, 0, 0) for a vertex whose
// faces' area vectors sum to zero: no face, or only degenerate ones. Summed in double. The
// caller has checked the face indices (CheckFaceIndices).
std::vector<Point3f> AreaWeightedVertexNormals(const TriangleMesh& mesh);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_VERTEX_NORMALS_H_
