// Reading plain-text point lists (.xyz, .txt, .pts) from memory.
#ifndef MEMBRANE_CORE_IO_XYZ_READER_H_
#define MEMBRANE_CORE_IO_XYZ_READER_H_

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/geometry/point_cloud.h"

namespace membrane {

// The points of the text in `data`: one "x y z [extra columns...]" per line, numbers
// separated by whitespace, commas or semicolons; blank lines and lines starting with "#" or
// "//" are ignored. The first data line may be a single integer point count (as .pts files
// have); if present, the number of points must equal it. InvalidArgument naming `source`, the
// line and byte offset for a line without three leading numbers, or naming `source` and the
// end offset for a count that does not match. Coordinates are not yet checked for finiteness.
absl::StatusOr<PointCloud> ReadXyzPointCloud(absl::string_view data, absl::string_view source);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_XYZ_READER_H_
