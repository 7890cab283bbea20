// What a Draco point cloud's first bytes promise, checked before Draco is trusted with them.
//
// Draco 1.5.5 believes the int32 point count at the start of a point cloud's geometry, and
// allocates every declared attribute for that many points before it decodes any of them; it
// also allocates each metadata entry at the size the entry declares. So 67 bytes can ask for
// gigabytes. These checks read the header, walk the metadata and the attribute descriptors
// (Draco's format: varint counts, length-prefixed names and values) without allocating, so
// that such input is refused at once.
#ifndef MEMBRANE_CORE_IO_DRACO_HEADER_H_
#define MEMBRANE_CORE_IO_DRACO_HEADER_H_

#include <cstdint>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"

namespace membrane {

// Scans compress to a few points per byte; only massively duplicated points (measured: 1M
// copies of one point, 58 bytes) compress far beyond this, and those are useless anyway.
inline constexpr uint64_t kMaxDracoPointsPerByte = 1024;

// For `bytes` holding a Draco point cloud (the caller knows its geometry type): OK when the
// point count in its header is possible for the size of `bytes` (at most
// kMaxDracoPointsPerByte per byte), and, for the point-cloud coders, when the attributes it
// declares take at most 12 x kMaxDracoPointsPerByte decoded bytes per byte of `bytes` (what a
// float32 position per point at the count bound takes); also OK when the data ends before
// either is known (Draco then fails on its own). InvalidArgument, naming what is wrong, when a
// bound is broken, or when the metadata in front is malformed or runs past the end of the data.
absl::Status CheckDracoPointCloudHeader(absl::string_view bytes);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_DRACO_HEADER_H_
