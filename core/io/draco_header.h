// What a Draco point cloud's first bytes promise, checked before Draco is trusted with them.
//
// Draco 1.5.5 believes the int32 point count at the start of a point cloud's geometry and
// allocates (and loops over) that many points before reading any of them, and it allocates
// each metadata entry at the size the entry declares: 150 bytes can ask for gigabytes. These
// checks read the header and walk the metadata (Draco's format: varint counts, u8-prefixed
// names, varint-prefixed values) without allocating, so that such input is refused at once.
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
// kMaxDracoPointsPerByte per byte) or when the data ends before the count (Draco then fails on
// its own). InvalidArgument, naming what is wrong, when the count is impossible, or when the
// metadata before it is malformed or runs past the end of the data.
absl::Status CheckDracoPointCount(absl::string_view bytes);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_DRACO_HEADER_H_
