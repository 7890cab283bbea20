#include "client/std_streams.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "absl/strings/str_cat.h"
#include "client/io_errors.h"
#include "core/io/file_bytes.h"

namespace membrane::client {

bool IsStdStream(absl::string_view path) { return path == kStdStreamName; }

absl::StatusOr<std::string> ReadInputBytes(const std::string& path) {
  if (!IsStdStream(path)) return ReadFileBytes(path);
  std::string bytes;
  char buffer[1 << 16];
  size_t got = 0;
  while ((got = std::fread(buffer, 1, sizeof buffer, stdin)) > 0) bytes.append(buffer, got);
  if (std::ferror(stdin)) {
    return absl::InvalidArgumentError(absl::StrCat("stdin: ", std::strerror(errno)));
  }
  if (bytes.empty()) {
    return absl::InvalidArgumentError("stdin is empty: give a point cloud or a mesh on it");
  }
  return bytes;
}

absl::Status WriteOutputBytes(const std::string& path, absl::string_view bytes) {
  if (!IsStdStream(path)) return FileErrorAsInvalidInput(WriteFileBytes(path, bytes));
  const size_t written = std::fwrite(bytes.data(), 1, bytes.size(), stdout);
  if (written != bytes.size() || std::fflush(stdout) != 0) {
    return absl::InvalidArgumentError(
        absl::StrCat("stdout: wrote ", written, " of ", bytes.size(), " bytes: ",
                     std::strerror(errno)));
  }
  return absl::OkStatus();
}

}  // namespace membrane::client
