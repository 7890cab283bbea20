#include "core/io/ply_vertex_rows.h"

#include <bit>
#include <cstring>

namespace membrane {

std::optional<size_t> FixedRowBytes(const PlyElement& element) {
  size_t row_bytes = 0;
  for (const PlyProperty& property : element.properties) {
    if (property.list_count_type) return std::nullopt;
    row_bytes += ScalarSize(property.type);
  }
  return row_bytes;
}

PlyVertexRows VertexRowLayout(const PlyElement& element, size_t x, size_t y, size_t z,
                              ByteOrder order) {
  PlyVertexRows layout;
  layout.order = order;
  const size_t axes[3] = {x, y, z};
  size_t offset = 0;
  for (size_t p = 0; p < element.properties.size(); ++p) {
    for (int axis = 0; axis < 3; ++axis) {
      if (axes[axis] != p) continue;
      layout.offsets[axis] = offset;
      layout.types[axis] = element.properties[p].type;
    }
    offset += ScalarSize(element.properties[p].type);
  }
  layout.row_bytes = offset;
  return layout;
}

void DecodeVertexRows(const char* rows, uint64_t count, const PlyVertexRows& layout,
                      CoordinateShift& shift, Point3f* out) {
  const size_t row_bytes = layout.row_bytes;
  const size_t* offsets = layout.offsets;
  const bool float32_positions = layout.types[0] == ScalarType::kFloat32 &&
                                 layout.types[1] == ScalarType::kFloat32 &&
                                 layout.types[2] == ScalarType::kFloat32;
  const bool native_floats =
      float32_positions &&
      (layout.order == ByteOrder::kLittleEndian) == (std::endian::native == std::endian::little);
  if (native_floats) {
    // The common scan layout: copy the floats as they are, no per-value conversion.
    for (uint64_t r = 0; r < count; ++r) {
      const char* row = rows + r * row_bytes;
      Point3f& p = out[r];
      std::memcpy(&p[0], row + offsets[0], sizeof(float));
      std::memcpy(&p[1], row + offsets[1], sizeof(float));
      std::memcpy(&p[2], row + offsets[2], sizeof(float));
    }
    return;
  }
  for (uint64_t r = 0; r < count; ++r) {
    const char* row = rows + r * row_bytes;
    const double x = DecodeScalar(row + offsets[0], layout.types[0], layout.order);
    const double y = DecodeScalar(row + offsets[1], layout.types[1], layout.order);
    const double z = DecodeScalar(row + offsets[2], layout.types[2], layout.order);
    out[r] = shift.NarrowStored(x, y, z, float32_positions);
  }
}

}  // namespace membrane
