// Reading Wavefront OBJ files from memory: "v" positions and "f" polygons.
#ifndef MEMBRANE_CORE_IO_OBJ_READER_H_
#define MEMBRANE_CORE_IO_OBJ_READER_H_

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

// The positions of the "v x y z" lines of the OBJ text in `data` (a fourth weight or colour
// columns are ignored); every other line is ignored. InvalidArgument naming `source`, the line
// and byte offset when a "v" line has fewer than three numbers. Coordinates are not yet
// checked for finiteness.
absl::StatusOr<PointCloud> ReadObjPointCloud(absl::string_view data, absl::string_view source);

// As ReadObjPointCloud, plus the "f" lines: references "a", "a/b", "a//c", "a/b/c" with
// 1-based or negative (relative to the vertices so far) indices; polygons are
// fan-triangulated, faces of fewer than 3 vertices dropped. Also InvalidArgument for a
// malformed reference or an index outside the vertices.
absl::StatusOr<TriangleMesh> ReadObjMesh(absl::string_view data, absl::string_view source);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_OBJ_READER_H_
