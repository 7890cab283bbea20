#include "core/io/obj_writer.h"

#include "absl/strings/str_cat.h"
#include "core/io/ascii_format.h"
#include "core/io/vertex_normals.h"

namespace membrane {
namespace {

void AppendVertexLines(const std::vector<Point3f>& vertices, const Origin3d& origin,
                       std::string* out) {
  for (const Point3f& p : vertices) {
    out->append("v ");
    AppendPointText(p, origin, out);
    out->push_back('\n');
  }
}

}  // namespace

std::string EncodeObjPointCloud(const PointCloud& cloud) {
  std::string out = "# written by membrane\n";
  AppendVertexLines(cloud.points, cloud.origin, &out);
  return out;
}

std::string EncodeObjMesh(const TriangleMesh& mesh) {
  std::string out = "# written by membrane\n";
  AppendVertexLines(mesh.vertices, mesh.origin, &out);
  for (const Point3f& normal : AreaWeightedVertexNormals(mesh)) {
    out.append("vn ");
    AppendPointText(normal, Origin3d{0, 0, 0}, &out);
    out.push_back('\n');
  }
  for (const std::array<int32_t, 3>& face : mesh.faces) {
    // OBJ indices are 1-based; int64 so the largest int32 index cannot overflow. Vertex i
    // has normal i: "v//vn" with the same number.
    const int64_t a = int64_t{face[0]} + 1, b = int64_t{face[1]} + 1, c = int64_t{face[2]} + 1;
    absl::StrAppend(&out, "f ", a, "//", a, " ", b, "//", b, " ", c, "//", c, "\n");
  }
  return out;
}

}  // namespace membrane
