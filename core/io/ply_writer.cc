#include "core/io/ply_writer.h"

#include "absl/strings/str_cat.h"
#include "core/io/binary_scalar.h"
#include "core/io/vertex_normals.h"

namespace membrane {
namespace {

constexpr size_t kFloatsPerVertex = 3;

bool HasOrigin(const Origin3d& origin) { return origin != Origin3d{0, 0, 0}; }

// A mesh's header (`face_count` set) has the vertex normals after x, y, z.
void AppendHeader(size_t vertex_count, const size_t* face_count, const Origin3d& origin,
                  std::string* out) {
  const absl::string_view type = HasOrigin(origin) ? "double" : "float";
  absl::StrAppend(out,
                  "ply\n"
                  "format binary_little_endian 1.0\n"
                  "comment written by membrane\n"
                  "element vertex ",
                  vertex_count, "\n", "property ", type, " x\n", "property ", type, " y\n",
                  "property ", type, " z\n");
  if (face_count != nullptr) {
    absl::StrAppend(out, "property float nx\nproperty float ny\nproperty float nz\n",
                    "element face ", *face_count, "\n",
                    "property list uchar int vertex_indices\n");
  }
  absl::StrAppend(out, "end_header\n");
}

// Each vertex's position: float32 as computed; with an origin, double sums, which hold the
// file's coordinates. Followed by its float32 normal when `normals` is not null.
void AppendVertices(const std::vector<Point3f>& vertices, const Origin3d& origin,
                    const std::vector<Point3f>* normals, std::string* out) {
  const bool double_positions = HasOrigin(origin);
  for (size_t i = 0; i < vertices.size(); ++i) {
    const Point3f& p = vertices[i];
    for (size_t axis = 0; axis < kFloatsPerVertex; ++axis) {
      if (double_positions) {
        AppendFloat64Le(static_cast<double>(p[axis]) + origin[axis], out);
      } else {
        AppendFloat32Le(p[axis], out);
      }
    }
    if (normals == nullptr) continue;
    for (float component : (*normals)[i]) AppendFloat32Le(component, out);
  }
}

size_t VertexBytes(const Origin3d& origin) {
  return kFloatsPerVertex * (HasOrigin(origin) ? sizeof(double) : sizeof(float));
}

}  // namespace

std::string EncodePlyPointCloud(const PointCloud& cloud) {
  std::string out;
  AppendHeader(cloud.points.size(), nullptr, cloud.origin, &out);
  out.reserve(out.size() + cloud.points.size() * VertexBytes(cloud.origin));
  AppendVertices(cloud.points, cloud.origin, nullptr, &out);
  return out;
}

std::string EncodePlyMesh(const TriangleMesh& mesh) {
  std::string out;
  const size_t face_count = mesh.faces.size();
  AppendHeader(mesh.vertices.size(), &face_count, mesh.origin, &out);
  const size_t normal_bytes = 3 * sizeof(float);
  out.reserve(out.size() + mesh.vertices.size() * (VertexBytes(mesh.origin) + normal_bytes) +
              face_count * (1 + 3 * sizeof(int32_t)));
  const std::vector<Point3f> normals = AreaWeightedVertexNormals(mesh);
  AppendVertices(mesh.vertices, mesh.origin, &normals, &out);
  for (const std::array<int32_t, 3>& face : mesh.faces) {
    out.push_back(static_cast<char>(3));
    for (int32_t index : face) AppendInt32Le(index, &out);
  }
  return out;
}

}  // namespace membrane
