#include "core/io/file_bytes.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "absl/strings/str_cat.h"

namespace membrane {
namespace {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

absl::Status ErrnoError(absl::string_view action, const std::string& path, int error) {
  return absl::InternalError(
      absl::StrCat("cannot ", action, " '", path, "': ", std::strerror(error)));
}

}  // namespace

absl::StatusOr<std::string> ReadFileBytes(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found) {
    return absl::NotFoundError(absl::StrCat("no such file: '", path, "'"));
  }
  if (ec) {
    return absl::InternalError(absl::StrCat("cannot stat '", path, "': ", ec.message()));
  }
  if (status.type() != std::filesystem::file_type::regular) {
    return absl::InvalidArgumentError(absl::StrCat("'", path, "' is not a regular file"));
  }
  FilePtr file(std::fopen(path.c_str(), "rb"));
  if (file == nullptr) return ErrnoError("open", path, errno);
  // The size is taken from the open file, not the earlier stat, so a file replaced in
  // between is still read consistently; a file that grows meanwhile is read up to this size.
  if (std::fseek(file.get(), 0, SEEK_END) != 0) return ErrnoError("seek in", path, errno);
  const long size = std::ftell(file.get());
  if (size < 0) return ErrnoError("size", path, errno);
  std::rewind(file.get());
  std::string bytes(static_cast<size_t>(size), '\0');
  const size_t read = std::fread(bytes.data(), 1, bytes.size(), file.get());
  if (read != bytes.size()) {
    if (std::ferror(file.get())) return ErrnoError("read", path, errno);
    bytes.resize(read);  // Shrunk while reading: parse what is there.
  }
  return bytes;
}

absl::Status WriteFileBytes(const std::string& path, absl::string_view bytes) {
  FilePtr file(std::fopen(path.c_str(), "wb"));
  if (file == nullptr) return ErrnoError("create", path, errno);
  if (std::fwrite(bytes.data(), 1, bytes.size(), file.get()) != bytes.size()) {
    return ErrnoError("write", path, errno);
  }
  // fclose flushes; a full disk often surfaces only here.
  if (std::fclose(file.release()) != 0) return ErrnoError("write", path, errno);
  return absl::OkStatus();
}

}  // namespace membrane
