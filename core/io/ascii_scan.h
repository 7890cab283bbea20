// Scanning text formats (OBJ, XYZ, PCD, ascii PLY and STL) in place, without copies, while
// keeping the byte offsets that error messages report.
#ifndef MEMBRANE_CORE_IO_ASCII_SCAN_H_
#define MEMBRANE_CORE_IO_ASCII_SCAN_H_

#include <cstddef>
#include <cstdint>
#include <optional>

#include "absl/strings/string_view.h"

namespace membrane {

// Splits `text` into lines ended by "\n" (a trailing "\r" is dropped, so "\r\n" files read
// the same). The last line need not end with "\n".
class LineScanner {
 public:
  // `base_offset` is the offset of `text` within the whole input, added to line_offset().
  explicit LineScanner(absl::string_view text, size_t base_offset = 0)
      : text_(text), base_offset_(base_offset) {}

  // Stores the next line, without its terminator, in *line; false at the end of the text.
  bool Next(absl::string_view* line);

  // The offset of the line last returned by Next(), from the start of the whole input.
  size_t line_offset() const { return base_offset_ + line_start_; }
  // The 1-based number of the line last returned by Next(), counted from `text`'s start.
  size_t line_number() const { return line_number_; }
  // The offset just past the line last returned (and its terminator).
  size_t end_offset() const { return base_offset_ + position_; }

 private:
  absl::string_view text_;
  size_t base_offset_;
  size_t position_ = 0;
  size_t line_start_ = 0;
  size_t line_number_ = 0;
};

// Splits text into tokens separated by ASCII whitespace and by any of `extra_separators`.
class TokenScanner {
 public:
  explicit TokenScanner(absl::string_view text, size_t base_offset = 0,
                        absl::string_view extra_separators = "")
      : text_(text), base_offset_(base_offset), extra_separators_(extra_separators) {}

  // Stores the next token in *token; false when only separators remain.
  bool Next(absl::string_view* token);

  // The offset of the token last returned, or of the end of the text after Next() returned
  // false, from the start of the whole input.
  size_t token_offset() const { return base_offset_ + token_start_; }

 private:
  bool IsSeparator(char c) const;

  absl::string_view text_;
  size_t base_offset_;
  absl::string_view extra_separators_;
  size_t position_ = 0;
  size_t token_start_ = 0;
};

// The decimal number in `token` ("1", "-2.5e3", "+.5", "nan", "inf"), or nullopt when the
// token is not entirely a number. Magnitudes beyond double's range give +-infinity (so the
// finiteness check reports them) and tiny ones give zero. Independent of the C locale.
std::optional<double> ParseDouble(absl::string_view token);

// The unsigned decimal integer in `token` (digits only, optional leading "+"), or nullopt
// when it is not one or does not fit in 64 bits.
std::optional<uint64_t> ParseUint64(absl::string_view token);

// The signed decimal integer in `token`, or nullopt when it is not one or does not fit.
std::optional<int64_t> ParseInt64(absl::string_view token);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_ASCII_SCAN_H_
