#include "core/io/pcd_reader.h"

#include <array>
#include <cstdint>

#include "absl/status/status.h"
#include "absl/strings/ascii.h"
#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"
#include "core/io/ascii_scan.h"
#include "core/io/binary_scalar.h"
#include "core/io/coordinate_shift.h"
#include "core/io/parse_error.h"
#include "core/io/pcd_header.h"

namespace membrane {
namespace {

// Where one of x, y, z sits in a point: its byte offset in a binary row, its value index in
// an ascii line, and its type.
struct AxisSlot {
  size_t byte_offset = 0;
  uint64_t value_index = 0;
  ScalarType type = ScalarType::kFloat32;
};

struct PointLayout {
  std::array<AxisSlot, 3> axes;
  size_t row_bytes = 0;         // bytes per point in binary
  uint64_t values_per_row = 0;  // values per point in ascii
};

absl::StatusOr<PointLayout> LayoutOf(const PcdHeader& header, absl::string_view source) {
  PointLayout layout;
  std::array<bool, 3> found = {false, false, false};
  static constexpr absl::string_view kAxisNames[3] = {"x", "y", "z"};
  for (const PcdField& field : header.fields) {
    for (int axis = 0; axis < 3; ++axis) {
      if (field.name != kAxisNames[axis] || found[axis]) continue;
      if (field.type != 'F' || field.count != 1) {
        return absl::InvalidArgumentError(absl::StrCat(
            source, ": PCD field '", field.name, "' must be TYPE F with SIZE 4 or 8 and COUNT 1"));
      }
      found[axis] = true;
      layout.axes[axis] = {layout.row_bytes, layout.values_per_row,
                           field.size == 8 ? ScalarType::kFloat64 : ScalarType::kFloat32};
    }
    // Cannot overflow: ParsePcdHeader bounds each count by the file size.
    layout.row_bytes += field.size * field.count;
    layout.values_per_row += field.count;
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (!found[axis]) {
      return absl::InvalidArgumentError(
          absl::StrCat(source, ": the PCD file has no field '", kAxisNames[axis], "'"));
    }
  }
  return layout;
}

absl::StatusOr<PointCloud> ReadBinary(absl::string_view data, const PcdHeader& header,
                                      const PointLayout& layout, absl::string_view source) {
  const size_t start = header.body_offset;
  const size_t remaining = data.size() - start;
  if (header.points > remaining / layout.row_bytes) {
    const uint64_t whole = remaining / layout.row_bytes;
    return ParseError(source, start + whole * layout.row_bytes,
                      absl::StrCat("the data ends inside point ", whole, " of ", header.points,
                                   " (", layout.row_bytes, " bytes each from byte ", start,
                                   "; only ", remaining, " bytes remain)"));
  }
  PointCloud cloud;
  CoordinateShift shift;
  bool float32_positions = true;  // CoordinateShift::NarrowStored
  for (const AxisSlot& slot : layout.axes) float32_positions &= slot.type == ScalarType::kFloat32;
  cloud.points.resize(header.points);
  const char* rows = data.data() + start;
  for (uint64_t i = 0; i < header.points; ++i) {
    const char* row = rows + i * layout.row_bytes;
    double point[3];
    for (int axis = 0; axis < 3; ++axis) {
      const AxisSlot& slot = layout.axes[axis];
      // PCL writes binary data in host order, which is little endian on every platform PCL
      // is used on.
      point[axis] = DecodeScalar(row + slot.byte_offset, slot.type, ByteOrder::kLittleEndian);
    }
    cloud.points[i] = shift.NarrowStored(point[0], point[1], point[2], float32_positions);
  }
  cloud.origin = shift.origin();
  return cloud;
}

absl::StatusOr<PointCloud> ReadAscii(absl::string_view data, const PcdHeader& header,
                                     const PointLayout& layout, absl::string_view source) {
  const size_t remaining = data.size() - header.body_offset;
  // Each value takes a character and a separator: check before reserving.
  if (layout.values_per_row > (remaining + 1) / 2 ||
      header.points > (remaining + 1) / (2 * layout.values_per_row)) {
    return ParseError(
        source, header.body_offset,
        absl::StrCat("POINTS declares ", header.points, " points of ", layout.values_per_row,
                     " values, but only ", remaining, " bytes follow the header"));
  }
  PointCloud cloud;
  CoordinateShift shift;
  cloud.points.reserve(header.points);
  LineScanner lines(data.substr(header.body_offset), header.body_offset);
  absl::string_view line;
  while (lines.Next(&line)) {
    if (absl::StripAsciiWhitespace(line).empty()) continue;
    const auto error = [&](size_t offset, absl::string_view what) {
      return LineError(source, lines.line_number(), offset,
                       absl::StrCat(what, " (in the data section)"));
    };
    if (cloud.points.size() == header.points) {
      return error(lines.line_offset(),
                   absl::StrCat("more point lines than POINTS ", header.points));
    }
    TokenScanner tokens(line, lines.line_offset());
    double point[3] = {0, 0, 0};
    uint64_t index = 0;
    absl::string_view token;
    while (tokens.Next(&token)) {
      for (int axis = 0; axis < 3; ++axis) {
        if (layout.axes[axis].value_index != index) continue;
        const std::optional<double> value = ParseDouble(token);
        if (!value) {
          return error(
              tokens.token_offset(),
              absl::StrCat("'", absl::CHexEscape(token.substr(0, 32)), "' is not a number"));
        }
        point[axis] = *value;
      }
      ++index;
    }
    if (index != layout.values_per_row) {
      return error(lines.line_offset(),
                   absl::StrCat("expected ", layout.values_per_row, " values, found ", index));
    }
    cloud.points.push_back(shift.Narrow(point[0], point[1], point[2]));
  }
  cloud.origin = shift.origin();
  if (cloud.points.size() != header.points) {
    return ParseError(source, data.size(),
                      absl::StrCat("the data ends after ", cloud.points.size(), " of ",
                                   header.points, " points"));
  }
  return cloud;
}

}  // namespace

absl::StatusOr<PointCloud> ReadPcdPointCloud(absl::string_view data, absl::string_view source) {
  absl::StatusOr<PcdHeader> header = ParsePcdHeader(data, source);
  if (!header.ok()) return header.status();
  if (header->encoding == PcdEncoding::kBinaryCompressed) {
    return absl::UnimplementedError(
        absl::StrCat(source,
                     ": PCD DATA binary_compressed is not supported; save it as binary or ascii "
                     "(e.g. with pcl_convert_pcd_ascii_binary)"));
  }
  absl::StatusOr<PointLayout> layout = LayoutOf(*header, source);
  if (!layout.ok()) return layout.status();
  if (header->encoding == PcdEncoding::kBinary) return ReadBinary(data, *header, *layout, source);
  return ReadAscii(data, *header, *layout, source);
}

}  // namespace membrane
