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
#include "core/io/pcd_compressed.h"
#include "core/io/pcd_header.h"

namespace membrane {
namespace {

// Where one of x, y, z sits in a point: its byte offset in a binary row, its value index in
// an ascii line, the bytes of the fields before it in a binary_compressed row (which leaves
// out the padding fields "_"), and its type.
struct AxisSlot {
  size_t byte_offset = 0;
  uint64_t value_index = 0;
  size_t packed_offset = 0;
  ScalarType type = ScalarType::kFloat32;
};

struct PointLayout {
  std::array<AxisSlot, 3> axes;
  size_t row_bytes = 0;         // bytes per point in binary
  size_t packed_row_bytes = 0;  // bytes per point in binary_compressed
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
      layout.axes[axis] = {layout.row_bytes, layout.values_per_row, layout.packed_row_bytes,
                           field.size == 8 ? ScalarType::kFloat64 : ScalarType::kFloat32};
    }
    // Cannot overflow: ParsePcdHeader bounds each count by the file size.
    layout.row_bytes += field.size * field.count;
    // PCL leaves the padding fields out when it compresses.
    if (field.name != "_") layout.packed_row_bytes += field.size * field.count;
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

// The cloud of `points` points whose axis `axis` (0-2) of point i is stored at
// value_at(i, axis), little endian, of the layout's type.
template <typename ValueAt>
PointCloud DecodePoints(uint64_t points, const PointLayout& layout, const ValueAt& value_at) {
  PointCloud cloud;
  CoordinateShift shift;
  bool float32_positions = true;  // CoordinateShift::NarrowStored
  for (const AxisSlot& slot : layout.axes) float32_positions &= slot.type == ScalarType::kFloat32;
  cloud.points.resize(points);
  for (uint64_t i = 0; i < points; ++i) {
    double point[3];
    for (int axis = 0; axis < 3; ++axis) {
      // PCL writes binary data in host order, which is little endian on every platform PCL
      // is used on.
      point[axis] = DecodeScalar(value_at(i, axis), layout.axes[axis].type,
                                 ByteOrder::kLittleEndian);
    }
    cloud.points[i] = shift.NarrowStored(point[0], point[1], point[2], float32_positions);
  }
  cloud.origin = shift.origin();
  return cloud;
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
  const char* rows = data.data() + start;
  return DecodePoints(header.points, layout, [&](uint64_t i, int axis) {
    return rows + i * layout.row_bytes + layout.axes[axis].byte_offset;
  });
}

// binary_compressed: the same values, each field's column for all points after the last.
absl::StatusOr<PointCloud> ReadBinaryCompressed(absl::string_view data, const PcdHeader& header,
                                                const PointLayout& layout,
                                                absl::string_view source) {
  absl::StatusOr<std::string> body = DecompressPcdBody(data, header.body_offset, header.points,
                                                       layout.packed_row_bytes, source);
  if (!body.ok()) return body.status();
  // DecompressPcdBody checked points x packed_row_bytes against the 32-bit size.
  return DecodePoints(header.points, layout, [&](uint64_t i, int axis) {
    const AxisSlot& slot = layout.axes[axis];
    return body->data() + slot.packed_offset * header.points + i * ScalarSize(slot.type);
  });
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
  absl::StatusOr<PointLayout> layout = LayoutOf(*header, source);
  if (!layout.ok()) return layout.status();
  switch (header->encoding) {
    case PcdEncoding::kBinary: return ReadBinary(data, *header, *layout, source);
    case PcdEncoding::kBinaryCompressed:
      return ReadBinaryCompressed(data, *header, *layout, source);
    case PcdEncoding::kAscii: break;
  }
  return ReadAscii(data, *header, *layout, source);
}

}  // namespace membrane
