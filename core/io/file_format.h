// File formats the io library reads and writes, chosen by file-name extension.
#ifndef MEMBRANE_CORE_IO_FILE_FORMAT_H_
#define MEMBRANE_CORE_IO_FILE_FORMAT_H_

#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"

namespace membrane {

enum class FileFormat {
  kPly,  // .ply: ascii, binary_little_endian or binary_big_endian
  kObj,  // .obj: Wavefront, "v" and "f" lines
  kXyz,  // .xyz, .txt, .pts: one "x y z ..." point per line
  kPcd,  // .pcd: Point Cloud Library, ascii or binary DATA
  kStl,  // .stl: binary (ascii is read too)
  kDrc,  // .drc: Draco-compressed point cloud or mesh
  kOff,  // .off: Object File Format (read only), "OFF" header, vertex and face lines
};

// What a caller wants to do with a file; each use supports its own set of formats.
enum class FileUse { kReadPointCloud, kWritePointCloud, kReadMesh, kWriteMesh };

// The formats supported for `use`.
absl::Span<const FileFormat> SupportedFormats(FileUse use);

// The extensions of `format`, lower case with the dot, e.g. ".xyz, .txt, .pts".
std::string FormatExtensions(FileFormat format);

// A short name for messages, e.g. "PLY".
absl::string_view FormatName(FileFormat format);

// The format of `path` from its extension, compared case-insensitively. InvalidArgument,
// naming the path and listing the extensions supported for `use`, when the extension is
// missing or not supported for `use`.
absl::StatusOr<FileFormat> FormatFromPath(absl::string_view path, FileUse use);

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_FILE_FORMAT_H_
