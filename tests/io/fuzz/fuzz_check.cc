#include "tests/io/fuzz/fuzz_check.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "absl/strings/string_view.h"
#include "core/io/mesh_io.h"
#include "core/io/point_cloud_io.h"

namespace membrane::fuzzing {
namespace {

void Require(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "io fuzz invariant violated: %s\n", what);
  std::abort();
}

bool AllFinite(const std::vector<Point3f>& points) {
  for (const Point3f& p : points) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) return false;
  }
  return true;
}

}  // namespace

void CheckReaders(const uint8_t* data, size_t size, FileFormat format) {
  const absl::string_view bytes(reinterpret_cast<const char*>(data), size);
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(bytes, format, "fuzz");
  if (cloud.ok()) Require(AllFinite(cloud->points), "a point cloud with non-finite points");
  if (format != FileFormat::kPly && format != FileFormat::kObj && format != FileFormat::kDrc) {
    return;
  }
  absl::StatusOr<TriangleMesh> mesh = ReadMeshFromBuffer(bytes, format, "fuzz");
  if (!mesh.ok()) return;
  Require(AllFinite(mesh->vertices), "a mesh with non-finite vertices");
  const int64_t vertex_count = static_cast<int64_t>(mesh->vertices.size());
  for (const auto& face : mesh->faces) {
    for (int32_t index : face) Require(index >= 0 && index < vertex_count, "a dangling face index");
  }
}

}  // namespace membrane::fuzzing
