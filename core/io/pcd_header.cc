#include "core/io/pcd_header.h"

#include <optional>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "core/io/ascii_scan.h"
#include "core/io/parse_error.h"

namespace membrane {
namespace {

// The values of a header line after its keyword.
std::vector<absl::string_view> Values(TokenScanner& tokens) {
  std::vector<absl::string_view> values;
  absl::string_view token;
  while (tokens.Next(&token)) values.push_back(token);
  return values;
}

bool ValidTypeAndSize(char type, size_t size) {
  if (type == 'F') return size == 4 || size == 8;
  if (type == 'I' || type == 'U') return size == 1 || size == 2 || size == 4 || size == 8;
  return false;
}

}  // namespace

absl::StatusOr<PcdHeader> ParsePcdHeader(absl::string_view data, absl::string_view source) {
  PcdHeader header;
  std::vector<absl::string_view> names, sizes, types, counts;
  std::optional<uint64_t> points, width, height;
  bool have_data = false;
  LineScanner lines(data);
  absl::string_view line;
  while (lines.Next(&line)) {
    const auto error = [&](absl::string_view what) {
      return LineError(source, lines.line_number(), lines.line_offset(), what);
    };
    TokenScanner tokens(line);
    absl::string_view keyword;
    if (!tokens.Next(&keyword) || keyword[0] == '#') continue;
    const std::string key = absl::AsciiStrToUpper(keyword);
    std::vector<absl::string_view> values = Values(tokens);
    const auto single_count = [&](std::optional<uint64_t>* out) -> absl::Status {
      if (values.size() != 1 || !(*out = ParseUint64(values[0]))) {
        return error(absl::StrCat(key, " needs one non-negative integer"));
      }
      return absl::OkStatus();
    };
    absl::Status status;
    if (key == "VERSION" || key == "VIEWPOINT") {
      continue;
    } else if (key == "FIELDS" || key == "COLUMNS") {
      names = std::move(values);
    } else if (key == "SIZE") {
      sizes = std::move(values);
    } else if (key == "TYPE") {
      types = std::move(values);
    } else if (key == "COUNT") {
      counts = std::move(values);
    } else if (key == "WIDTH") {
      status = single_count(&width);
    } else if (key == "HEIGHT") {
      status = single_count(&height);
    } else if (key == "POINTS") {
      status = single_count(&points);
    } else if (key == "DATA") {
      const std::string encoding = values.size() == 1 ? absl::AsciiStrToLower(values[0]) : "";
      if (encoding == "ascii") {
        header.encoding = PcdEncoding::kAscii;
      } else if (encoding == "binary") {
        header.encoding = PcdEncoding::kBinary;
      } else if (encoding == "binary_compressed") {
        header.encoding = PcdEncoding::kBinaryCompressed;
      } else {
        return error("DATA must be ascii, binary or binary_compressed");
      }
      header.body_offset = lines.end_offset();
      have_data = true;
      break;
    } else {
      return error(absl::StrCat("unknown header keyword '", keyword.substr(0, 32), "'"));
    }
    if (!status.ok()) return status;
  }
  const auto header_error = [&](absl::string_view what) {
    return ParseError(source, lines.line_offset(), what);
  };
  if (!have_data) return ParseError(source, data.size(), "the file ends before DATA");
  if (names.empty()) return header_error("the header has no FIELDS");
  if (sizes.size() != names.size() || types.size() != names.size() ||
      (!counts.empty() && counts.size() != names.size())) {
    return header_error(absl::StrCat("FIELDS has ", names.size(), " entries but SIZE has ",
                                     sizes.size(), ", TYPE ", types.size(), " and COUNT ",
                                     counts.size()));
  }
  for (size_t i = 0; i < names.size(); ++i) {
    PcdField field;
    field.name = std::string(names[i]);
    const std::optional<uint64_t> size = ParseUint64(sizes[i]);
    field.type = types[i].size() == 1 ? absl::ascii_toupper(types[i][0]) : '?';
    if (!size || !ValidTypeAndSize(field.type, *size)) {
      return header_error(absl::StrCat("field '", field.name, "' has TYPE ", types[i].substr(0, 8),
                                       " and SIZE ", sizes[i].substr(0, 8),
                                       "; expected I or U of 1, 2, 4, 8 bytes or F of 4, 8"));
    }
    field.size = *size;
    if (!counts.empty()) {
      const std::optional<uint64_t> count = ParseUint64(counts[i]);
      // More values per point than bytes in the file is a lie whatever the encoding, and
      // bounding it keeps the row size arithmetic far from overflow.
      if (!count || *count == 0 || *count > data.size()) {
        return header_error(absl::StrCat("field '", field.name, "' has impossible COUNT ",
                                         counts[i].substr(0, 24)));
      }
      field.count = *count;
    }
    header.fields.push_back(std::move(field));
  }
  if (width && height) {
    const uint64_t w = *width, h = *height;
    if (h != 0 && w > UINT64_MAX / h) return header_error("WIDTH x HEIGHT overflows");
    if (points && *points != w * h) {
      return header_error(
          absl::StrCat("POINTS ", *points, " disagrees with WIDTH x HEIGHT = ", w * h));
    }
    if (!points) points = w * h;
  }
  if (!points) return header_error("the header has neither POINTS nor WIDTH and HEIGHT");
  header.points = *points;
  return header;
}

}  // namespace membrane
