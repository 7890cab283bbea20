// Triangle meshes as the core produces them: shared float32 vertices, int32 triangles.
#ifndef MEMBRANE_CORE_GEOMETRY_TRIANGLE_MESH_H_
#define MEMBRANE_CORE_GEOMETRY_TRIANGLE_MESH_H_

#include <array>
#include <cstdint>
#include <vector>

#include "core/geometry/point_cloud.h"

namespace membrane {

// A triangle mesh in model units. Faces index `vertices`; counter-clockwise seen from
// outside (outward normals) for every mesh the core writes.
struct TriangleMesh {
  std::vector<Point3f> vertices;
  std::vector<std::array<int32_t, 3>> faces;
  Origin3d origin{0, 0, 0};  // file coordinates = vertex + origin (see point_cloud.h)
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_GEOMETRY_TRIANGLE_MESH_H_
