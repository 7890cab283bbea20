// Reading Point Cloud Library .pcd files from memory.
#ifndef MEMBRANE_CORE_IO_PCD_READER_H_
#define MEMBRANE_CORE_IO_PCD_READER_H_

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/geometry/point_cloud.h"

namespace membrane {

// The x, y, z fields (TYPE F, SIZE 4 or 8, COUNT 1) of the PCD file in `data`, DATA ascii,
// binary (little endian) or binary_compressed (PCL's LZF, see pcd_compressed.h); other
// fields are skipped using their SIZE and COUNT. InvalidArgument naming `source` (with the
// byte offset where one applies) for a malformed header, missing x/y/z, a body shorter than
// POINTS declares, an ascii body with a wrong number of values on a line or more lines than
// POINTS, or compressed data whose sizes or LZF stream are wrong (DecompressPcdBody). Coordinates
// are not yet checked for finiteness (organized clouds mark missing points with NaN, which
// the caller then rejects).
absl::StatusOr<PointCloud> ReadPcdPointCloud(absl::string_view data, absl::string_view source);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_PCD_READER_H_
