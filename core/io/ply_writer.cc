#include "core/io/ply_writer.h"

#include "absl/strings/str_cat.h"
#include "core/io/binary_scalar.h"

namespace membrane {
namespace {

constexpr size_t kFloatsPerVertex = 3;

bool HasOrigin(const Origin3d& origin) { return origin != Origin3d{0, 0, 0}; }

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
    absl::StrAppend(out, "element face ", *face_count, "\n",
                    "property list uchar int vertex_indices\n");
  }
  absl::StrAppend(out, "end_header\n");
}

// float32 as computed; with an origin, double sums, which hold the file's coordinates.
void AppendVertices(const std::vector<Point3f>& vertices, const Origin3d& origin,
                    std::string* out) {
  if (!HasOrigin(origin)) {
    for (const Point3f& p : vertices) {
      for (size_t axis = 0; axis < kFloatsPerVertex; ++axis) AppendFloat32Le(p[axis], out);
    }
    return;
  }
  for (const Point3f& p : vertices) {
    for (size_t axis = 0; axis < kFloatsPerVertex; ++axis)
      AppendFloat64Le(static_cast<double>(p[axis]) + origin[axis], out);
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
  AppendVertices(cloud.points, cloud.origin, &out);
  return out;
}

std::string EncodePlyMesh(const TriangleMesh& mesh) {
  std::string out;
  const size_t face_count = mesh.faces.size();
  AppendHeader(mesh.vertices.size(), &face_count, mesh.origin, &out);
  out.reserve(out.size() + mesh.vertices.size() * VertexBytes(mesh.origin) +
              face_count * (1 + 3 * sizeof(int32_t)));
  AppendVertices(mesh.vertices, mesh.origin, &out);
  for (const std::array<int32_t, 3>& face : mesh.faces) {
    out.push_back(static_cast<char>(3));
    for (int32_t index : face) AppendInt32Le(index, &out);
  }
  return out;
}

}  // namespace membrane
