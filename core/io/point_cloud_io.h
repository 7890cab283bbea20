// Reading and writing point clouds in every supported format, chosen by extension or by the
// caller (for uploads held in memory).
#ifndef MEMBRANE_CORE_IO_POINT_CLOUD_IO_H_
#define MEMBRANE_CORE_IO_POINT_CLOUD_IO_H_

#include <cstddef>
#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/geometry/point_cloud.h"
#include "core/io/draco_codec.h"
#include "core/io/file_format.h"

namespace membrane {

// What a reader does with points that have a NaN or infinite coordinate. Organized scans
// (PCD, PLY from depth cameras and PCL) keep their rows and columns by marking the pixels
// without a return so.
enum class InvalidPoints {
  kRefuse,  // InvalidArgument "<source>: 12 points have NaN or infinite coordinates"
  kDrop,    // dropped from the cloud; the others keep their order
};

// The point cloud in the file at `path`, its format chosen by the extension
// (case-insensitive): .ply, .obj, .xyz/.txt/.pts, .pcd, .drc (a Draco mesh gives its
// vertices). NotFound naming the path when it does not exist; otherwise as
// ReadPointCloudFile with `path` as the source.
absl::StatusOr<PointCloud> ReadPointCloud(const std::string& path,
                                          InvalidPoints invalid = InvalidPoints::kRefuse,
                                          size_t* dropped = nullptr);

// The point cloud in the file at `path`, read as `format`, `source` naming it in messages: as
// ReadFileBytes then ReadPointCloudFromBuffer (their errors), but a binary PLY file is read in
// pieces into the points (StreamPlyPointCloud), never whole: a scan's file and its points are
// not both held.
absl::StatusOr<PointCloud> ReadPointCloudFile(const std::string& path, FileFormat format,
                                              absl::string_view source,
                                              InvalidPoints invalid = InvalidPoints::kRefuse,
                                              size_t* dropped = nullptr);

// The point cloud in `data`, read as `format`. `source` names the input in messages. A cloud
// of zero points is OK when the file is well formed. Errors:
//   InvalidArgument "<source>: ..." for empty input, a format that cannot hold point clouds
//     (kStl), malformed, truncated or lying input (with the byte offset where it went wrong),
//     and, with InvalidPoints::kRefuse, "<source>: 12 points have NaN or infinite
//     coordinates". With kDrop those points are left out, and `dropped` (when not null) is
//     set to how many were (Draco excepted: its decoder refuses them either way).
// Never allocates more than a small multiple of data.size() (PCD binary_compressed: its
// uncompressed size, at most kLzfMaxExpansion times its compressed bytes). Draco input is
// decoded in-process (see draco_codec.h about crafted input). Coordinates from 10^4 on in
// text or binary doubles are moved near 0 (CoordinateShift), and the cloud's origin says by
// how much; binary float32 positions (PLY, PCD, Draco) are taken as they are.
absl::StatusOr<PointCloud> ReadPointCloudFromBuffer(absl::string_view data, FileFormat format,
                                                    absl::string_view source = "<buffer>",
                                                    InvalidPoints invalid = InvalidPoints::kRefuse,
                                                    size_t* dropped = nullptr);

// The bytes of `cloud` in `format`: binary little-endian PLY, XYZ text, OBJ "v" lines, or
// Draco with `draco` options; with an origin, at position + origin in double (PLY, XYZ, OBJ).
// InvalidArgument for non-finite coordinates, a format that cannot be written (PCD, STL),
// invalid Draco options, an empty cloud for Draco, or an origin with Draco
// (CheckOriginFitsFormat); Internal when the Draco encoder fails.
absl::StatusOr<std::string> WritePointCloudToBuffer(const PointCloud& cloud, FileFormat format,
                                                    const DracoOptions& draco = {});

// Writes `cloud` to `path` in the format of its extension (.ply, .xyz, .obj, .drc).
// InvalidArgument listing the supported extensions for any other; otherwise the errors of
// WritePointCloudToBuffer and WriteFileBytes.
absl::Status WritePointCloud(const PointCloud& cloud, const std::string& path,
                             const DracoOptions& draco = {});

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_POINT_CLOUD_IO_H_
