#include "client/flag_checks.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <system_error>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "client/std_streams.h"

namespace membrane::client {
namespace {

absl::Status OutOfRange(absl::string_view flag, absl::string_view value, absl::string_view lo,
                        absl::string_view hi, absl::string_view note) {
  std::string message = absl::StrCat(flag, " ", value, " is out of range [", lo, ", ", hi, "]");
  if (!note.empty()) absl::StrAppend(&message, " (", note, ")");
  return absl::InvalidArgumentError(message);
}

}  // namespace

absl::Status CheckIntRange(absl::string_view flag, int64_t value, int64_t lo, int64_t hi,
                           absl::string_view note) {
  if (value >= lo && value <= hi) return absl::OkStatus();
  return OutOfRange(flag, absl::StrCat(value), absl::StrCat(lo), absl::StrCat(hi), note);
}

absl::Status CheckRealRange(absl::string_view flag, double value, double lo, double hi,
                            absl::string_view note) {
  // Written so that NaN fails: every comparison with NaN is false.
  if (std::isfinite(value) && value >= lo && value <= hi) return absl::OkStatus();
  return OutOfRange(flag, absl::StrFormat("%g", value), absl::StrFormat("%g", lo),
                    absl::StrFormat("%g", hi), note);
}

absl::Status CheckOutputPath(absl::string_view flag, const std::string& path) {
  if (IsStdStream(path)) return absl::OkStatus();
  std::error_code error;  // a path we cannot even stat counts as missing
  if (std::filesystem::is_directory(path, error)) {
    return absl::InvalidArgumentError(
        absl::StrCat(flag, ": cannot write '", path, "': it is a directory"));
  }
  std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (parent.empty()) parent = ".";
  if (!std::filesystem::is_directory(parent, error)) {
    return absl::InvalidArgumentError(absl::StrCat(flag, ": cannot write '", path,
                                                   "': directory '", parent.string(),
                                                   "' does not exist"));
  }
  // An existing file must itself be writable; a new one needs a writable directory.
  const bool exists = std::filesystem::exists(path, error);
  if (access(exists ? path.c_str() : parent.c_str(), W_OK) != 0) {
    return absl::InvalidArgumentError(
        absl::StrCat(flag, ": cannot write '", path, "': ",
                     exists ? "the file is not writable"
                            : absl::StrCat("directory '", parent.string(), "' is not writable")));
  }
  return absl::OkStatus();
}

}  // namespace membrane::client
