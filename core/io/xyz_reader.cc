#include "core/io/xyz_reader.h"

#include <cstdint>
#include <optional>

#include "absl/strings/ascii.h"
#include "absl/strings/escaping.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "core/io/ascii_scan.h"
#include "core/io/coordinate_shift.h"
#include "core/io/parse_error.h"

namespace membrane {
namespace {

constexpr absl::string_view kSeparators = ",;";

bool IsComment(absl::string_view line) {
  return absl::StartsWith(line, "#") || absl::StartsWith(line, "//");
}

// The count of a ".pts" count line: a line holding exactly one unsigned integer.
std::optional<uint64_t> CountLine(absl::string_view line) {
  TokenScanner tokens(line, 0, kSeparators);
  absl::string_view first, second;
  if (!tokens.Next(&first) || tokens.Next(&second)) return std::nullopt;
  return ParseUint64(first);
}

}  // namespace

absl::StatusOr<PointCloud> ReadXyzPointCloud(absl::string_view data, absl::string_view source) {
  PointCloud cloud;
  CoordinateShift shift;
  std::optional<uint64_t> declared_count;
  bool first_data_line = true;
  LineScanner lines(data);
  absl::string_view line;
  while (lines.Next(&line)) {
    const absl::string_view content = absl::StripLeadingAsciiWhitespace(line);
    if (content.empty() || IsComment(content)) continue;
    if (first_data_line) {
      first_data_line = false;
      declared_count = CountLine(content);
      if (declared_count) continue;
    }
    TokenScanner tokens(line, lines.line_offset(), kSeparators);
    double point[3];
    for (double& coordinate : point) {
      absl::string_view token;
      if (!tokens.Next(&token)) {
        return LineError(source, lines.line_number(), tokens.token_offset(),
                         "a point line needs three coordinates");
      }
      const std::optional<double> value = ParseDouble(token);
      if (!value) {
        return LineError(
            source, lines.line_number(), tokens.token_offset(),
            absl::StrCat("'", absl::CHexEscape(token.substr(0, 32)), "' is not a number"));
      }
      coordinate = *value;
    }
    cloud.points.push_back(shift.Narrow(point[0], point[1], point[2]));
  }
  cloud.origin = shift.origin();
  if (declared_count && *declared_count != cloud.points.size()) {
    return ParseError(source, data.size(),
                      absl::StrCat("the data ends after ", cloud.points.size(),
                                   " points but the count line declares ", *declared_count));
  }
  return cloud;
}

}  // namespace membrane
