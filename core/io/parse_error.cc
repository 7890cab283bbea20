#include "core/io/parse_error.h"

#include "absl/strings/str_cat.h"

namespace membrane {

absl::Status ParseError(absl::string_view source, size_t offset, absl::string_view what) {
  return absl::InvalidArgumentError(absl::StrCat(source, ": at byte ", offset, ": ", what));
}

absl::Status LineError(absl::string_view source, size_t line, size_t offset,
                       absl::string_view what) {
  return absl::InvalidArgumentError(
      absl::StrCat(source, ": line ", line, " (byte ", offset, "): ", what));
}

absl::Status PrefixStatus(absl::string_view prefix, const absl::Status& status) {
  if (status.ok()) return status;
  return absl::Status(status.code(), absl::StrCat(prefix, ": ", status.message()));
}

}  // namespace membrane
