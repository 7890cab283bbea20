// The rows of a binary PLY element whose properties are all scalars: every row has the same
// size, so a block of vertices decodes without a bounds check per value. Shared by the reader
// of a PLY held in memory (ply_body.h) and the one that streams a file (ply_stream.h).
#ifndef MEMBRANE_CORE_IO_PLY_VERTEX_ROWS_H_
#define MEMBRANE_CORE_IO_PLY_VERTEX_ROWS_H_

#include <cstddef>
#include <cstdint>
#include <optional>

#include "core/geometry/point_cloud.h"
#include "core/io/binary_scalar.h"
#include "core/io/coordinate_shift.h"
#include "core/io/ply_header.h"

namespace membrane {

// Bytes per row of `element`; nullopt when it has a list property (rows of varying size).
std::optional<size_t> FixedRowBytes(const PlyElement& element);

// Where x, y and z lie in a fixed-size row, and how they are stored.
struct PlyVertexRows {
  size_t row_bytes = 0;
  size_t offsets[3] = {0, 0, 0};
  ScalarType types[3] = {ScalarType::kFloat32, ScalarType::kFloat32, ScalarType::kFloat32};
  ByteOrder order = ByteOrder::kLittleEndian;
};

// The layout of `element`'s rows (it must have no list property) with x, y and z at the
// property indices `x`, `y` and `z`, stored in `order`.
PlyVertexRows VertexRowLayout(const PlyElement& element, size_t x, size_t y, size_t z,
                              ByteOrder order);

// Decodes the `count` rows at `rows` (count * layout.row_bytes readable bytes) into
// out[0 .. count): float32 positions as they are (copied when stored in this machine's byte
// order), anything else moved by `shift` (CoordinateShift::NarrowStored). Decoding a block in
// pieces, with the same `shift`, gives the same points as at once.
void DecodeVertexRows(const char* rows, uint64_t count, const PlyVertexRows& layout,
                      CoordinateShift& shift, Point3f* out);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_PLY_VERTEX_ROWS_H_
