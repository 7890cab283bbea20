#include "tests/io/fuzz/fuzz_check.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "absl/strings/string_view.h"
#include "core/io/coordinate_shift.h"
#include "core/io/mesh_io.h"
#include "core/io/point_cloud_io.h"

namespace membrane::fuzzing {
namespace {

void Require(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "io fuzz invariant violated: %s\n", what);
  std::abort();
}

// An origin is 0 or a whole number of units in [kShiftFrom, kShiftUpTo] (CoordinateShift).
bool ValidOrigin(const Origin3d& origin) {
  for (double v : origin) {
    const double m = std::fabs(v);
    if (v != 0 && !(m >= kShiftFrom && m <= kShiftUpTo && v == std::round(v))) return false;
  }
  return true;
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
  if (cloud.ok()) {
    Require(AllFinite(cloud->points), "a point cloud with non-finite points");
    Require(ValidOrigin(cloud->origin), "a point cloud with an invalid origin");
  }
  if (format != FileFormat::kPly && format != FileFormat::kObj && format != FileFormat::kDrc &&
      format != FileFormat::kStl && format != FileFormat::kOff) {
    return;
  }
  absl::StatusOr<TriangleMesh> mesh = ReadMeshFromBuffer(bytes, format, "fuzz");
  if (!mesh.ok()) return;
  Require(AllFinite(mesh->vertices), "a mesh with non-finite vertices");
  Require(ValidOrigin(mesh->origin), "a mesh with an invalid origin");
  const int64_t vertex_count = static_cast<int64_t>(mesh->vertices.size());
  for (const auto& face : mesh->faces) {
    for (int32_t index : face) Require(index >= 0 && index < vertex_count, "a dangling face index");
  }
}

}  // namespace membrane::fuzzing
