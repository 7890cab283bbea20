#include "core/io/ply_header.h"

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/io/ascii_scan.h"
#include "core/io/parse_error.h"

namespace membrane {
namespace {

std::optional<PlyEncoding> EncodingFromName(absl::string_view name) {
  if (name == "ascii") return PlyEncoding::kAscii;
  if (name == "binary_little_endian") return PlyEncoding::kBinaryLittleEndian;
  if (name == "binary_big_endian") return PlyEncoding::kBinaryBigEndian;
  return std::nullopt;
}

}  // namespace

absl::StatusOr<PlyHeader> ParsePlyHeader(absl::string_view data, absl::string_view source) {
  LineScanner lines(data);
  absl::string_view line;
  if (!lines.Next(&line) || line != "ply") {
    return ParseError(source, 0, "not a PLY file: it does not start with a \"ply\" line");
  }
  PlyHeader header;
  bool have_format = false;
  while (lines.Next(&line)) {
    const auto error = [&](absl::string_view what) {
      return LineError(source, lines.line_number(), lines.line_offset(), what);
    };
    TokenScanner tokens(line);
    absl::string_view keyword;
    if (!tokens.Next(&keyword) || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      if (!have_format) return error("the header has no \"format\" line");
      header.body_offset = lines.end_offset();
      return header;
    }
    if (keyword == "format") {
      absl::string_view name, version;
      if (!tokens.Next(&name) || !tokens.Next(&version)) {
        return error("expected \"format <encoding> <version>\"");
      }
      std::optional<PlyEncoding> encoding = EncodingFromName(name);
      if (!encoding) {
        return error(absl::StrCat("unknown encoding '", name,
                                  "' (expected ascii, binary_little_endian or binary_big_endian)"));
      }
      header.encoding = *encoding;
      have_format = true;
      continue;
    }
    if (keyword == "element") {
      absl::string_view name, count_token;
      if (!tokens.Next(&name) || !tokens.Next(&count_token)) {
        return error("expected \"element <name> <count>\"");
      }
      std::optional<uint64_t> count = ParseUint64(count_token);
      if (!count) return error(absl::StrCat("element count '", count_token, "' is not a count"));
      header.elements.push_back(PlyElement{std::string(name), *count, {}});
      continue;
    }
    if (keyword == "property") {
      if (header.elements.empty()) return error("a property comes before any element");
      PlyProperty property;
      absl::string_view type_name;
      if (!tokens.Next(&type_name)) return error("expected \"property <type> <name>\"");
      if (type_name == "list") {
        absl::string_view count_name;
        if (!tokens.Next(&count_name) || !tokens.Next(&type_name)) {
          return error("expected \"property list <count type> <item type> <name>\"");
        }
        std::optional<ScalarType> count_type = ScalarTypeFromPlyName(count_name);
        if (!count_type || IsFloatingPoint(*count_type)) {
          return error(absl::StrCat("list count type '", count_name, "' is not an integer type"));
        }
        property.list_count_type = count_type;
      }
      std::optional<ScalarType> type = ScalarTypeFromPlyName(type_name);
      if (!type) return error(absl::StrCat("unknown property type '", type_name, "'"));
      property.type = *type;
      absl::string_view name;
      if (!tokens.Next(&name)) return error("the property has no name");
      property.name = std::string(name);
      header.elements.back().properties.push_back(std::move(property));
      continue;
    }
    return error(absl::StrCat("unknown header keyword '", keyword, "'"));
  }
  return ParseError(source, data.size(), "the file ends before \"end_header\"");
}

std::optional<size_t> FindPlyProperty(const PlyElement& element, absl::string_view name) {
  for (size_t i = 0; i < element.properties.size(); ++i) {
    if (element.properties[i].name == name) return i;
  }
  return std::nullopt;
}

}  // namespace membrane
