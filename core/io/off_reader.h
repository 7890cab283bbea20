// Reading Object File Format (OFF) files from memory: the format of Princeton's shape
// benchmark, CGAL, Geomview and many academic data sets.
#ifndef MEMBRANE_CORE_IO_OFF_READER_H_
#define MEMBRANE_CORE_IO_OFF_READER_H_

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

// The vertices of the OFF text in `data`: a header keyword "OFF" (also "COFF", "NOFF",
// "CNOFF": colour and normal columns after x y z are ignored), the counts "V F E" (on the
// header line or the next), V lines "x y z ...", then F lines "n i1 ... in [colour]".
// '#' starts a comment; blank lines are skipped. InvalidArgument naming `source`, the line
// and byte offset for a missing keyword, counts that are not numbers or exceed what the
// bytes can hold, a vertex line with fewer than three numbers, or fewer vertex lines than
// announced. Coordinates are not yet checked for finiteness.
absl::StatusOr<PointCloud> ReadOffPointCloud(absl::string_view data, absl::string_view source);

// As ReadOffPointCloud, plus the F faces: polygons are fan-triangulated, faces of fewer than
// 3 vertices dropped. Also InvalidArgument for a face line whose count or indices are not
// numbers, an index outside the V vertices, or fewer face lines than announced.
absl::StatusOr<TriangleMesh> ReadOffMesh(absl::string_view data, absl::string_view source);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_OFF_READER_H_
