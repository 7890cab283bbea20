#include "client/format_flags.h"

#include <vector>

#include "absl/algorithm/container.h"
#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "client/std_streams.h"

namespace membrane::client {
namespace {

// Bytes looked at to tell a format: enough for any header line we match.
constexpr size_t kSniffBytes = 4096;

// True when `line` is `word` or starts with `word` and a blank.
bool StartsWithWord(absl::string_view line, absl::string_view word) {
  if (!absl::StartsWith(line, word)) return false;
  return line.size() == word.size() || absl::ascii_isspace(line[word.size()]);
}

}  // namespace

absl::StatusOr<FileFormat> ParseFormatName(absl::string_view flag, absl::string_view name,
                                           FileUse use) {
  // Parsed as the extension it names, so that the flag takes what file names take.
  absl::StatusOr<FileFormat> format =
      name.empty() || absl::StrContains(name, '.') || absl::StrContains(name, '/')
          ? absl::InvalidArgumentError("")
          : FormatFromPath(absl::StrCat("x.", name), use);
  if (format.ok()) return format;
  std::vector<std::string> names;
  for (FileFormat f : SupportedFormats(use)) {
    for (absl::string_view extension : absl::StrSplit(FormatExtensions(f), ", ")) {
      names.emplace_back(absl::StripPrefix(extension, "."));
    }
  }
  return absl::InvalidArgumentError(absl::StrCat(flag, " '", name, "' is not one of: ",
                                                 absl::StrJoin(names, ", ")));
}

std::optional<FileFormat> SniffFormat(absl::string_view bytes) {
  bytes = bytes.substr(0, kSniffBytes);
  if (absl::StartsWith(bytes, "DRACO")) return FileFormat::kDrc;
  bool first = true;
  for (absl::string_view line : absl::StrSplit(bytes, absl::ByAnyChar("\r\n"))) {
    line = absl::StripLeadingAsciiWhitespace(line);
    if (first) {
      if (StartsWithWord(line, "ply")) return FileFormat::kPly;
      for (absl::string_view off : {"OFF", "COFF", "NOFF", "CNOFF"}) {
        if (StartsWithWord(line, off)) return FileFormat::kOff;
      }
      first = false;
    }
    if (absl::StartsWith(line, "# .PCD") || StartsWithWord(line, "VERSION")) {
      return FileFormat::kPcd;
    }
    if (line.empty() || line[0] == '#') continue;
    for (absl::string_view obj : {"v", "o", "g", "mtllib"}) {
      if (StartsWithWord(line, obj)) return FileFormat::kObj;
    }
    const char c = line[0];
    if (absl::ascii_isdigit(c) || c == '-' || c == '+' || c == '.') return FileFormat::kXyz;
    return std::nullopt;
  }
  return std::nullopt;
}

absl::StatusOr<FileFormat> InputFormat(const std::string& path, absl::string_view format_flag,
                                       FileUse use, absl::string_view bytes) {
  if (!format_flag.empty()) return ParseFormatName("--input-format", format_flag, use);
  if (!IsStdStream(path)) return FormatFromPath(path, use);
  const std::optional<FileFormat> sniffed = SniffFormat(bytes);
  if (sniffed && absl::c_linear_search(SupportedFormats(use), *sniffed)) return *sniffed;
  return absl::InvalidArgumentError(absl::StrCat(
      "stdin: its first bytes are not those of a format membrane reads here",
      sniffed ? absl::StrCat(" (they look like ", FormatName(*sniffed), ")") : "",
      "; name its format with --input-format"));
}

absl::StatusOr<FileFormat> OutputFormat(const std::string& path, absl::string_view format_flag,
                                        FileUse use) {
  if (!format_flag.empty()) return ParseFormatName("--output-format", format_flag, use);
  if (IsStdStream(path)) return FileFormat::kPly;
  return FormatFromPath(path, use);
}

}  // namespace membrane::client
