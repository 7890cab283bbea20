// "-" where a command takes a file: standard input for an input, standard output for an
// output, so that membrane sits in a pipe as other command-line tools do.
#ifndef MEMBRANE_CLIENT_STD_STREAMS_H_
#define MEMBRANE_CLIENT_STD_STREAMS_H_

#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace membrane::client {

// The name that stands for standard input (as an input) or standard output (as an output).
inline constexpr char kStdStreamName[] = "-";

// True when `path` is "-".
bool IsStdStream(absl::string_view path);

// The bytes of the input `path`: the regular file's (ReadFileBytes, whose errors it returns),
// or for "-" all of standard input. InvalidArgument "stdin is empty" for an empty standard
// input (a pipe whose writer failed), "stdin: ..." naming errno's text when it cannot be read.
absl::StatusOr<std::string> ReadInputBytes(const std::string& path);

// Writes `bytes` to the output `path`: replaces the file (WriteFileBytes), or for "-" writes
// them to standard output and flushes it. InvalidArgument naming the file, or "stdout: ..."
// with errno's text (a closed pipe), when they cannot all be written.
absl::Status WriteOutputBytes(const std::string& path, absl::string_view bytes);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_STD_STREAMS_H_
