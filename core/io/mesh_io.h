// Reading and writing triangle meshes in every supported format, chosen by extension or by
// the caller.
#ifndef MEMBRANE_CORE_IO_MESH_IO_H_
#define MEMBRANE_CORE_IO_MESH_IO_H_

#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/geometry/triangle_mesh.h"
#include "core/io/draco_codec.h"
#include "core/io/file_format.h"

namespace membrane {

// The mesh in the file at `path`, its format chosen by the extension (case-insensitive):
// .ply, .obj, .stl, .drc. NotFound naming the path when it does not exist; otherwise as
// ReadMeshFromBuffer with `path` as the source.
absl::StatusOr<TriangleMesh> ReadMesh(const std::string& path);

// The mesh in `data`, read as `format`; polygons are fan-triangulated, and STL corners with
// equal positions become shared vertices. Face orientation is kept as stored. A file without
// faces gives a mesh without faces. InvalidArgument "<source>: ..." for empty input, XYZ or
// PCD, malformed, truncated or lying input (with the byte offset where it went wrong), face
// indices out of range, and "<source>: 3 vertices have NaN or infinite coordinates".
// Coordinates from 10^4 on in text or binary doubles are moved near 0 (CoordinateShift), and
// the mesh's origin says by how much; binary float32 positions (PLY, STL, Draco) are taken as
// they are.
absl::StatusOr<TriangleMesh> ReadMeshFromBuffer(absl::string_view data, FileFormat format,
                                                absl::string_view source = "<buffer>");

// The bytes of `mesh` in `format`: binary little-endian PLY (float xyz, "property list uchar
// int vertex_indices"), OBJ, binary STL, or Draco with `draco` options. A mesh with an origin
// is written at vertex + origin, in double (PLY, OBJ). InvalidArgument for non-finite
// vertices, face indices out of range, XYZ or PCD, invalid Draco options, a mesh without faces
// for Draco, or an origin with STL or Draco (CheckOriginFitsFormat); Internal when the Draco
// encoder fails.
absl::StatusOr<std::string> WriteMeshToBuffer(const TriangleMesh& mesh, FileFormat format,
                                              const DracoOptions& draco = {});

// Writes `mesh` to `path` in the format of its extension (.ply, .obj, .stl, .drc).
// InvalidArgument listing the supported extensions for any other; otherwise the errors of
// WriteMeshToBuffer and WriteFileBytes.
absl::Status WriteMesh(const TriangleMesh& mesh, const std::string& path,
                       const DracoOptions& draco = {});

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_MESH_IO_H_
