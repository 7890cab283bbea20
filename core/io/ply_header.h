// The header of a PLY file: encoding, elements and their properties, and where the body starts.
#ifndef MEMBRANE_CORE_IO_PLY_HEADER_H_
#define MEMBRANE_CORE_IO_PLY_HEADER_H_

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/io/binary_scalar.h"

namespace membrane {

enum class PlyEncoding { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct PlyProperty {
  std::string name;
  // The value type; for a list, the type of its items.
  ScalarType type = ScalarType::kFloat32;
  // Set only for "property list <count type> <item type> <name>".
  std::optional<ScalarType> list_count_type;
};

struct PlyElement {
  std::string name;
  // As declared; nothing has checked it against the body yet.
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::kAscii;
  std::vector<PlyElement> elements;
  // Offset of the first body byte, just past the "end_header" line.
  size_t body_offset = 0;
};

// Parses the header at the start of `data`. InvalidArgument naming `source` and the line when
// the magic "ply" line, the format line or "end_header" is missing, or a line is malformed
// (unknown keyword or type, a property before any element, a float list count type).
absl::StatusOr<PlyHeader> ParsePlyHeader(absl::string_view data, absl::string_view source);

// The index in `element.properties` of the property called `name`, or nullopt.
std::optional<size_t> FindPlyProperty(const PlyElement& element, absl::string_view name);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_PLY_HEADER_H_
