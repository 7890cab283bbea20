// The two ways a PLY body stores values -- packed binary in either byte order, or ascii
// tokens -- behind one interface, so one walker reads both.
#ifndef MEMBRANE_CORE_IO_PLY_VALUE_SOURCE_H_
#define MEMBRANE_CORE_IO_PLY_VALUE_SOURCE_H_

#include <cstddef>
#include <cstdint>
#include <string>

#include "absl/strings/string_view.h"
#include "core/io/ascii_scan.h"
#include "core/io/binary_scalar.h"
#include "core/io/ply_header.h"

namespace membrane {

// Values packed back to back in `order`. Never reads outside `data`.
class PlyBinarySource {
 public:
  // Reads `data` from byte `offset` on.
  PlyBinarySource(absl::string_view data, size_t offset, ByteOrder order)
      : data_(data), offset_(offset), order_(order) {}

  // Offset of the next value from the start of `data`.
  size_t offset() const { return offset_; }
  size_t remaining() const { return data_.size() - offset_; }

  // Stores the next value, read as `type`, in *value; false (see problem()) when the data ends.
  bool Read(ScalarType type, double* value);
  // Skips `count` values of `type`; false when fewer remain.
  bool Skip(uint64_t count, ScalarType type);
  // Returns the next `bytes` bytes and moves past them; nullptr when fewer remain.
  const char* Take(size_t bytes);
  // Whether `count` more values of `type` could still follow.
  bool MayHold(uint64_t count, ScalarType type) const;
  // The fewest bytes one row of `element` can take: lists may be empty.
  size_t MinRowBytes(const PlyElement& element) const;
  // Whether `rows` rows of at least `min_row_bytes` each could still follow.
  bool MayHoldRows(uint64_t rows, size_t min_row_bytes) const;
  // Why, and at which offset, the last Read or Skip failed.
  std::string problem() const;
  size_t failure_offset() const { return offset_; }

  ByteOrder order() const { return order_; }

 private:
  absl::string_view data_;
  size_t offset_;
  ByteOrder order_;
};

// Values as whitespace-separated decimal tokens; row and line structure is not enforced.
class PlyAsciiSource {
 public:
  // Reads `data` from byte `offset` on.
  PlyAsciiSource(absl::string_view data, size_t offset)
      : tokens_(data.substr(offset), offset), size_(data.size()), offset_(offset) {}

  // Offset just past the last token read.
  size_t offset() const { return offset_; }
  size_t remaining() const { return size_ - offset_; }

  // Stores the next token's number in *value; false at the end or on a non-number. Values of
  // integer types are not checked for range or integrality here; the caller does that where
  // it matters (list lengths, vertex indices).
  bool Read(ScalarType type, double* value);
  // Skips `count` tokens without parsing them; false when fewer remain.
  bool Skip(uint64_t count, ScalarType type);
  // Whether `count` more tokens could still follow: each takes a character and a separator.
  bool MayHold(uint64_t count, ScalarType type) const;
  // Two bytes per property: a one-character token and its separator.
  size_t MinRowBytes(const PlyElement& element) const;
  // Whether `rows` rows of at least `min_row_bytes` each could still follow.
  bool MayHoldRows(uint64_t rows, size_t min_row_bytes) const;
  // Why, and at which offset, the last Read or Skip failed: the end of the data, or the
  // (escaped, shortened) token that is not a number.
  std::string problem() const;
  size_t failure_offset() const { return failure_offset_; }

 private:
  bool NextToken(absl::string_view* token);

  TokenScanner tokens_;
  size_t size_;
  size_t offset_;
  size_t failure_offset_ = 0;
  absl::string_view bad_token_;  // Empty when the last failure was the end of the data.
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_PLY_VALUE_SOURCE_H_
