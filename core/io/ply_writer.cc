#include "core/io/ply_writer.h"

#include "absl/strings/str_cat.h"
#include "core/io/binary_scalar.h"

namespace membrane {
namespace {

constexpr size_t kFloatsPerVertex = 3;

void AppendHeader(size_t vertex_count, const size_t* face_count, std::string* out) {
  absl::StrAppend(out,
                  "ply\n"
                  "format binary_little_endian 1.0\n"
                  "comment written by membrane\n"
                  "element vertex ",
                  vertex_count, "\n",
                  "property float x\n"
                  "property float y\n"
                  "property float z\n");
  if (face_count != nullptr) {
    absl::StrAppend(out, "element face ", *face_count, "\n",
                    "property list uchar int vertex_indices\n");
  }
  absl::StrAppend(out, "end_header\n");
}

void AppendVertices(const std::vector<Point3f>& vertices, std::string* out) {
  for (const Point3f& p : vertices) {
    for (size_t axis = 0; axis < kFloatsPerVertex; ++axis) AppendFloat32Le(p[axis], out);
  }
}

}  // namespace

std::string EncodePlyPointCloud(const PointCloud& cloud) {
  std::string out;
  AppendHeader(cloud.points.size(), nullptr, &out);
  out.reserve(out.size() + cloud.points.size() * kFloatsPerVertex * sizeof(float));
  AppendVertices(cloud.points, &out);
  return out;
}

std::string EncodePlyMesh(const TriangleMesh& mesh) {
  std::string out;
  const size_t face_count = mesh.faces.size();
  AppendHeader(mesh.vertices.size(), &face_count, &out);
  out.reserve(out.size() + mesh.vertices.size() * kFloatsPerVertex * sizeof(float) +
              face_count * (1 + 3 * sizeof(int32_t)));
  AppendVertices(mesh.vertices, &out);
  for (const std::array<int32_t, 3>& face : mesh.faces) {
    out.push_back(static_cast<char>(3));
    for (int32_t index : face) AppendInt32Le(index, &out);
  }
  return out;
}

}  // namespace membrane
