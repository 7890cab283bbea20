// Uniform error statuses for malformed input, so every reader names the input and the place.
#ifndef MEMBRANE_CORE_IO_PARSE_ERROR_H_
#define MEMBRANE_CORE_IO_PARSE_ERROR_H_

#include <cstddef>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"

namespace membrane {

// InvalidArgument "<source>: at byte <offset>: <what>". `source` is a path or a buffer name;
// `offset` counts bytes from the start of the input.
absl::Status ParseError(absl::string_view source, size_t offset, absl::string_view what);

// InvalidArgument "<source>: line <line> (byte <offset>): <what>", for text formats where
// the line is what a person looks for first. `line` is 1-based.
absl::Status LineError(absl::string_view source, size_t line, size_t offset,
                       absl::string_view what);

// `status` with "<prefix>: " put in front of its message, same code; OK stays OK.
absl::Status PrefixStatus(absl::string_view prefix, const absl::Status& status);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_PARSE_ERROR_H_
