// The body of a PCD file with DATA binary_compressed, as PCL writes it: a little-endian
// uint32 compressed size, a uint32 uncompressed size, then that many bytes of LZF data.
#ifndef MEMBRANE_CORE_IO_PCD_COMPRESSED_H_
#define MEMBRANE_CORE_IO_PCD_COMPRESSED_H_

#include <cstddef>
#include <cstdint>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace membrane {

// The most bytes LZF can make of one compressed byte: a 3-byte back reference copies at
// most 264 bytes. An uncompressed size beyond 88 times the compressed one is a lie.
inline constexpr uint64_t kLzfMaxExpansion = 88;

// The decompressed body of the PCD file in `data` whose DATA line ends at `body_offset`:
// `points` x `packed_row_bytes` bytes, each field other than the padding "_" stored for all
// points before the next (structure of arrays); `packed_row_bytes` > 0. Bytes after the
// compressed block are ignored, as PCL does. InvalidArgument naming `source` and the byte
// offset when fewer than 8 bytes follow DATA, the compressed size exceeds the bytes that
// follow, the uncompressed size differs from points x packed_row_bytes or exceeds what LZF
// can expand the compressed bytes to, or the LZF data is corrupt or decompresses to another
// size. Allocates the uncompressed
// size only after these checks (at most kLzfMaxExpansion x data.size()).
absl::StatusOr<std::string> DecompressPcdBody(absl::string_view data, size_t body_offset,
                                              uint64_t points, uint64_t packed_row_bytes,
                                              absl::string_view source);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_PCD_COMPRESSED_H_
