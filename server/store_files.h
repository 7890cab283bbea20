// The file operations DiskJobStore needs, behind an interface: the store's code is the same on
// a real directory and in tests that make the disk fail (read-only, full) without mounting one.
#ifndef MEMBRANE_SERVER_STORE_FILES_H_
#define MEMBRANE_SERVER_STORE_FILES_H_

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"

namespace membrane::server {

class StoreFiles {
 public:
  virtual ~StoreFiles() = default;

  // Creates the directory `dir` (mode 0700) unless it exists. Unavailable naming it otherwise.
  virtual absl::Status MakeDirectory(const std::string& dir) = 0;

  // The names of the entries of `dir` ("." and ".." left out). Unavailable naming it when it
  // cannot be listed.
  virtual absl::StatusOr<std::vector<std::string>> List(const std::string& dir) = 0;

  // The bytes of the regular file `path`. FailedPrecondition when it is not one (a symbolic
  // link is not followed, a FIFO not opened for long: either could lead out of the store or
  // block); OutOfRange, before anything is read, when it holds more than `max_bytes`;
  // NotFound when it does not exist; Unavailable with errno's text when it cannot be read.
  virtual absl::StatusOr<std::string> Read(const std::string& path, int64_t max_bytes) = 0;

  // Replaces `path` (in `dir`) with the concatenation of `pieces` so that a crash leaves the
  // old file or the new one, never a mix, and the new one survives a crash once this returns
  // OK: a temporary file `path`.tmp, fsync, rename over `path`, fsync of `dir`. Unavailable
  // naming the file and errno's text (read-only file system, no space left, ...) otherwise;
  // the temporary file is then removed and `path` is as it was.
  virtual absl::Status Write(const std::string& dir, const std::string& path,
                             absl::Span<const absl::string_view> pieces) = 0;

  // Removes `path`; a missing file is no error. Unavailable naming it otherwise.
  virtual absl::Status Remove(const std::string& path) = 0;
};

// StoreFiles on this machine's file system (POSIX calls).
std::unique_ptr<StoreFiles> PosixStoreFiles();

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_STORE_FILES_H_
