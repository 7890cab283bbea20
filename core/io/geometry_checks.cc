#include "core/io/geometry_checks.h"

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "absl/strings/str_cat.h"

namespace membrane {

absl::Status CheckFinitePoints(absl::Span<const Point3f> points, absl::string_view source,
                               bool is_mesh) {
  size_t bad = 0;
  for (const Point3f& p : points) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) ++bad;
  }
  if (bad == 0) return absl::OkStatus();
  const absl::string_view noun = is_mesh ? (bad == 1 ? "vertex has" : "vertices have")
                                         : (bad == 1 ? "point has" : "points have");
  return absl::InvalidArgumentError(
      absl::StrCat(source, ": ", bad, " ", noun, " NaN or infinite coordinates"));
}

size_t DropNonFinitePoints(std::vector<Point3f>* points) {
  const size_t before = points->size();
  std::erase_if(*points, [](const Point3f& p) {
    return !std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]);
  });
  return before - points->size();
}

absl::Status CheckFaceIndices(const TriangleMesh& mesh, absl::string_view source) {
  const int64_t vertex_count = static_cast<int64_t>(mesh.vertices.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    for (int32_t index : mesh.faces[f]) {
      if (index < 0 || index >= vertex_count) {
        return absl::InvalidArgumentError(absl::StrCat(source, ": face ", f, " refers to vertex ",
                                                       index, " but there are ", vertex_count,
                                                       " vertices"));
      }
    }
  }
  return absl::OkStatus();
}

}  // namespace membrane
