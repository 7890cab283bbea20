// The header of a Point Cloud Library .pcd file: fields, point count, data encoding.
#ifndef MEMBRANE_CORE_IO_PCD_HEADER_H_
#define MEMBRANE_CORE_IO_PCD_HEADER_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace membrane {

enum class PcdEncoding { kAscii, kBinary, kBinaryCompressed };

struct PcdField {
  std::string name;
  size_t size = 4;     // bytes per value: 1, 2, 4 or 8
  char type = 'F';     // 'I' signed, 'U' unsigned, 'F' floating point
  uint64_t count = 1;  // values per point
};

struct PcdHeader {
  std::vector<PcdField> fields;
  uint64_t points = 0;  // as declared; nothing has checked it against the body yet
  PcdEncoding encoding = PcdEncoding::kAscii;
  size_t body_offset = 0;  // just past the DATA line
};

// Parses the header at the start of `data`, up to and including the DATA line. POINTS, or
// WIDTH x HEIGHT when POINTS is absent, gives the point count (they must agree when both are
// present); COUNT defaults to 1 per field. InvalidArgument naming `source`, the line and the
// byte offset for unknown keywords, malformed or inconsistent FIELDS/SIZE/TYPE/COUNT, a
// field COUNT exceeding the file size, or a missing DATA line.
absl::StatusOr<PcdHeader> ParsePcdHeader(absl::string_view data, absl::string_view source);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_PCD_HEADER_H_
