// A shared secret kept in a file (membraned --token-file, membrane --token-file).
#ifndef MEMBRANE_CORE_IO_TOKEN_FILE_H_
#define MEMBRANE_CORE_IO_TOKEN_FILE_H_

#include <string>

#include "absl/status/statusor.h"

namespace membrane {

// The token in the file at `path`: its first line without surrounding whitespace, so that
// `echo SECRET > file` and a Kubernetes secret mounted as a file both work. InvalidArgument
// naming the path when the file cannot be read, holds no token, or the token holds a space or
// a byte outside visible ASCII (it travels as a gRPC metadata value, which cannot carry them).
absl::StatusOr<std::string> ReadTokenFile(const std::string& path);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_TOKEN_FILE_H_
