// Range checks of command-line values, with messages that name the flag as the user typed it
// (the core's own checks name struct fields, which a user never sees).
#ifndef MEMBRANE_CLIENT_FLAG_CHECKS_H_
#define MEMBRANE_CLIENT_FLAG_CHECKS_H_

#include <cstdint>
#include <string>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"

namespace membrane::client {

// OK when lo <= value <= hi; otherwise InvalidArgument
// "--initial-plate -3 is out of range [0, 100000]" followed by " (<note>)" when `note` is set.
absl::Status CheckIntRange(absl::string_view flag, int64_t value, int64_t lo, int64_t hi,
                           absl::string_view note = "");

// As above for real values; NaN and infinities are out of every range.
absl::Status CheckRealRange(absl::string_view flag, double value, double lo, double hi,
                            absl::string_view note = "");

// OK when a file can be written at `path`: it is not a directory, and the directory that
// would hold it (the current one for a bare name) exists and is writable. Otherwise
// InvalidArgument naming the flag, e.g. "-o: cannot write 'a/b.ply': directory 'a' does not
// exist" or "--stats-json: cannot write 'out': it is a directory". Creates nothing. Lets a
// long job fail at once rather than after its work, when the write fails. "-" (standard
// output) is always OK.
absl::Status CheckOutputPath(absl::string_view flag, const std::string& path);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_FLAG_CHECKS_H_
