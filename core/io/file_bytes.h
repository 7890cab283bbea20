// Whole-file reads and writes: every reader parses from memory, so uploads and files share
// one code path and binary bodies are decoded in bulk.
#ifndef MEMBRANE_CORE_IO_FILE_BYTES_H_
#define MEMBRANE_CORE_IO_FILE_BYTES_H_

#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace membrane {

// The contents of the regular file at `path`. NotFound naming the path when it does not
// exist; InvalidArgument when it is not a regular file (a directory, a FIFO: reading those
// could block forever); Internal (with errno's text) when it cannot be read.
absl::StatusOr<std::string> ReadFileBytes(const std::string& path);

// Replaces the file at `path` with `bytes`. Internal naming the path when it cannot be
// opened or fully written (missing directory, permissions, full disk).
absl::Status WriteFileBytes(const std::string& path, absl::string_view bytes);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_FILE_BYTES_H_
