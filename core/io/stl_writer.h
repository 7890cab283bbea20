// Writing binary STL files.
#ifndef MEMBRANE_CORE_IO_STL_WRITER_H_
#define MEMBRANE_CORE_IO_STL_WRITER_H_

#include <string>

#include "absl/status/statusor.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

// The bytes of a binary STL file of `mesh`'s faces, each with its unit normal (zero for a
// degenerate face). The header does not start with "solid", so no reader mistakes it for
// text. The caller has checked the face indices. InvalidArgument when the mesh has 2^32 or
// more faces, which STL cannot count.
absl::StatusOr<std::string> EncodeStlMesh(const TriangleMesh& mesh);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_STL_WRITER_H_
