// Reading STL files (binary, and ascii "solid" text) from memory.
#ifndef MEMBRANE_CORE_IO_STL_READER_H_
#define MEMBRANE_CORE_IO_STL_READER_H_

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

// The triangles of the STL file in `data`, with bitwise-equal corner positions merged into
// shared vertices (STL stores every triangle's corners separately) so that connectivity can
// be checked. Binary is recognised by its size (84 + 50 x triangle count, trailing bytes
// allowed); otherwise text starting with "solid" is read as ascii, with polygon loops
// fan-triangulated. InvalidArgument naming `source` and the byte offset for a truncated
// binary file or a malformed ascii one. Coordinates are not yet checked for finiteness.
absl::StatusOr<TriangleMesh> ReadStlMesh(absl::string_view data, absl::string_view source);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_STL_READER_H_
