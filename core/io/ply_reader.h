// Reading PLY files (ascii, binary little and big endian) from memory.
#ifndef MEMBRANE_CORE_IO_PLY_READER_H_
#define MEMBRANE_CORE_IO_PLY_READER_H_

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

// The x, y, z of the "vertex" element of the PLY file in `data`; other properties and
// elements (faces, normals, colours, lists) are skipped but must be well formed. `source`
// names the input in messages. InvalidArgument naming `source` (and the byte offset where
// one applies) for a malformed, truncated or lying file. Coordinates are not yet checked for
// finiteness.
absl::StatusOr<PointCloud> ReadPlyPointCloud(absl::string_view data, absl::string_view source);

// As ReadPlyPointCloud, plus the "face" element's vertex lists fan-triangulated (a file
// without faces gives a mesh without faces). Also InvalidArgument for face indices outside
// the vertex range.
absl::StatusOr<TriangleMesh> ReadPlyMesh(absl::string_view data, absl::string_view source);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_PLY_READER_H_
