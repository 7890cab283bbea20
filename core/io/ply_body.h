// The body of a PLY file: vertex positions and, for meshes, faces.
#ifndef MEMBRANE_CORE_IO_PLY_BODY_H_
#define MEMBRANE_CORE_IO_PLY_BODY_H_

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/geometry/triangle_mesh.h"
#include "core/io/ply_header.h"

namespace membrane {

// Reads the body of `data` described by `header`: x, y, z of the first element named
// "vertex" (any scalar types, moved near the origin by a CoordinateShift and narrowed to
// float; the mesh's origin says by how much) and, when `want_faces`, the vertex index
// list ("vertex_indices" or "vertex_index") of the first element named "face",
// fan-triangulated; faces of fewer than 3 vertices are dropped. Every element is walked to
// its end, so a file truncated anywhere fails. Element counts are checked against the bytes
// left before anything is allocated. InvalidArgument naming `source` and the byte offset for
// truncation, lying counts, malformed values and out-of-range vertex indices; for a missing
// vertex element or x/y/z property, naming `source`. Coordinates are not checked for
// finiteness here.
absl::StatusOr<TriangleMesh> ReadPlyBody(absl::string_view data, const PlyHeader& header,
                                         absl::string_view source, bool want_faces);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_PLY_BODY_H_
