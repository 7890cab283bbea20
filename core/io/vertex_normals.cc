#include "core/io/vertex_normals.h"

#include "core/geometry/vec3.h"

namespace membrane {

std::vector<Point3f> AreaWeightedVertexNormals(const TriangleMesh& mesh) {
  std::vector<Vec3d> sums(mesh.vertices.size(), Vec3d{0, 0, 0});
  for (const std::array<int32_t, 3>& face : mesh.faces) {
    // TriangleNormal is twice the area vector: the factor 2 cancels in the normalization.
    const Vec3d area = TriangleNormal(ToVec3d(mesh.vertices[face[0]]),
                                      ToVec3d(mesh.vertices[face[1]]),
                                      ToVec3d(mesh.vertices[face[2]]));
    for (int32_t index : face) sums[index] = sums[index] + area;
  }
  std::vector<Point3f> normals;
  normals.reserve(sums.size());
  for (const Vec3d& sum : sums) normals.push_back(ToPoint3f(Normalized(sum)));
  return normals;
}

}  // namespace membrane
