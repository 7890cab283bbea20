#include "core/io/ply_stream.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <system_error>
#include <memory>
#include <vector>

#include "core/io/coordinate_shift.h"
#include "core/io/ply_header.h"
#include "core/io/ply_vertex_rows.h"

namespace membrane {
namespace {

// Enough for any header a scanner writes (a few hundred bytes to a few KB of comments).
constexpr size_t kHeaderBytes = size_t{64} << 10;

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

// Reads exactly `bytes` bytes into `buffer`; false on a short read or an error.
bool ReadExactly(std::FILE* file, char* buffer, size_t bytes) {
  return std::fread(buffer, 1, bytes, file) == bytes;
}

}  // namespace

std::optional<PointCloud> StreamPlyPointCloud(const std::string& path) {
  // Opening a FIFO would block until a writer comes: only regular files.
  std::error_code ec;
  if (std::filesystem::status(path, ec).type() != std::filesystem::file_type::regular || ec) {
    return std::nullopt;
  }
  FilePtr file(std::fopen(path.c_str(), "rb"));
  if (file == nullptr) return std::nullopt;
  if (std::fseek(file.get(), 0, SEEK_END) != 0) return std::nullopt;
  const long size_value = std::ftell(file.get());
  if (size_value <= 0) return std::nullopt;
  const auto file_size = static_cast<uint64_t>(size_value);
  std::rewind(file.get());

  std::string head(static_cast<size_t>(std::min<uint64_t>(file_size, kHeaderBytes)), '\0');
  if (!ReadExactly(file.get(), head.data(), head.size())) return std::nullopt;
  absl::StatusOr<PlyHeader> header = ParsePlyHeader(head, path);
  if (!header.ok() || header->encoding == PlyEncoding::kAscii) return std::nullopt;
  const ByteOrder order = header->encoding == PlyEncoding::kBinaryLittleEndian
                              ? ByteOrder::kLittleEndian
                              : ByteOrder::kBigEndian;

  // Every element's rows must have a fixed size, and the file must hold them all: then the
  // whole-file reader would find nothing wrong either.
  uint64_t body_bytes = 0;
  uint64_t vertex_start = 0;  // from the body's start
  const PlyElement* vertex = nullptr;
  for (const PlyElement& element : header->elements) {
    const std::optional<size_t> row_bytes = FixedRowBytes(element);
    if (!row_bytes) return std::nullopt;
    if (*row_bytes > 0 && element.count > (UINT64_MAX - body_bytes) / *row_bytes) {
      return std::nullopt;
    }
    if (element.name == "vertex" && vertex == nullptr) {
      vertex = &element;
      vertex_start = body_bytes;
    }
    body_bytes += element.count * *row_bytes;
  }
  if (vertex == nullptr || header->body_offset > file_size ||
      body_bytes > file_size - header->body_offset) {
    return std::nullopt;
  }
  size_t axes[3];
  const char* names[3] = {"x", "y", "z"};
  for (int axis = 0; axis < 3; ++axis) {
    const std::optional<size_t> index = FindPlyProperty(*vertex, names[axis]);
    if (!index) return std::nullopt;
    axes[axis] = *index;
  }
  const PlyVertexRows layout = VertexRowLayout(*vertex, axes[0], axes[1], axes[2], order);

  PointCloud cloud;
  if (vertex->count == 0 || layout.row_bytes == 0) return std::nullopt;
  if (std::fseek(file.get(), static_cast<long>(header->body_offset + vertex_start), SEEK_SET) !=
      0) {
    return std::nullopt;
  }
  cloud.points.resize(vertex->count);
  const uint64_t rows_per_chunk =
      std::max<uint64_t>(1, kPlyStreamChunkBytes / layout.row_bytes);
  std::vector<char> buffer(rows_per_chunk * layout.row_bytes);
  CoordinateShift shift;
  for (uint64_t done = 0; done < vertex->count;) {
    const uint64_t rows = std::min(rows_per_chunk, vertex->count - done);
    if (!ReadExactly(file.get(), buffer.data(), rows * layout.row_bytes)) return std::nullopt;
    DecodeVertexRows(buffer.data(), rows, layout, shift, cloud.points.data() + done);
    done += rows;
  }
  cloud.origin = shift.origin();
  return cloud;
}

}  // namespace membrane
