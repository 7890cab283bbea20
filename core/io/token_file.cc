#include "core/io/token_file.h"

#include "absl/strings/string_view.h"

#include "absl/status/status.h"
#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "core/io/file_bytes.h"

namespace membrane {

absl::StatusOr<std::string> ReadTokenFile(const std::string& path) {
  absl::StatusOr<std::string> bytes = ReadFileBytes(path);
  if (!bytes.ok()) return absl::InvalidArgumentError(bytes.status().message());
  const absl::string_view first_line = absl::string_view(*bytes).substr(0, bytes->find('\n'));
  std::string token(absl::StripAsciiWhitespace(first_line));
  if (token.empty()) return absl::InvalidArgumentError(absl::StrCat(path, " holds no token"));
  for (const char ch : token) {
    if (ch < 0x21 || ch > 0x7e) {
      return absl::InvalidArgumentError(
          absl::StrCat("the token in ", path, " holds a space or a non-printable character"));
    }
  }
  return token;
}

}  // namespace membrane
