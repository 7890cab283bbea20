// Checks applied to every geometry read and every mesh written, so that callers never see
// non-finite coordinates or dangling face indices.
#ifndef MEMBRANE_CORE_IO_GEOMETRY_CHECKS_H_
#define MEMBRANE_CORE_IO_GEOMETRY_CHECKS_H_

#include <cstddef>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

// OK when every coordinate of `points` is finite; otherwise InvalidArgument
// "<source>: 12 points have NaN or infinite coordinates" ("vertices" when `is_mesh`).
absl::Status CheckFinitePoints(absl::Span<const Point3f> points, absl::string_view source,
                               bool is_mesh = false);

// Removes the points of `points` that have a NaN or infinite coordinate, keeping the order of
// the others, and returns how many it removed.
size_t DropNonFinitePoints(std::vector<Point3f>* points);

// OK when every face index of `mesh` lies in [0, vertices.size()); otherwise InvalidArgument
// "<source>: face 7 refers to vertex 12 but there are 10 vertices".
absl::Status CheckFaceIndices(const TriangleMesh& mesh, absl::string_view source);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_GEOMETRY_CHECKS_H_
