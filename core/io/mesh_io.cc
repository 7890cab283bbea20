#include "core/io/mesh_io.h"

#include "absl/strings/str_cat.h"
#include "core/io/coordinate_shift.h"
#include "core/io/file_bytes.h"
#include "core/io/geometry_checks.h"
#include "core/io/obj_reader.h"
#include "core/io/obj_writer.h"
#include "core/io/off_reader.h"
#include "core/io/parse_error.h"
#include "core/io/ply_reader.h"
#include "core/io/ply_writer.h"
#include "core/io/stl_reader.h"
#include "core/io/stl_writer.h"

namespace membrane {
namespace {

absl::StatusOr<TriangleMesh> Parse(absl::string_view data, FileFormat format,
                                   absl::string_view source) {
  switch (format) {
    case FileFormat::kPly: return ReadPlyMesh(data, source);
    case FileFormat::kObj: return ReadObjMesh(data, source);
    case FileFormat::kStl: return ReadStlMesh(data, source);
    case FileFormat::kOff: return ReadOffMesh(data, source);
    case FileFormat::kDrc: {
      absl::StatusOr<TriangleMesh> mesh = DecodeDracoMesh(data);
      if (!mesh.ok()) return PrefixStatus(source, mesh.status());
      return mesh;
    }
    case FileFormat::kXyz:
    case FileFormat::kPcd: break;
  }
  return absl::InvalidArgumentError(
      absl::StrCat(source, ": meshes cannot be read from ", FormatName(format), " files"));
}

}  // namespace

absl::StatusOr<TriangleMesh> ReadMesh(const std::string& path) {
  absl::StatusOr<FileFormat> format = FormatFromPath(path, FileUse::kReadMesh);
  if (!format.ok()) return format.status();
  absl::StatusOr<std::string> bytes = ReadFileBytes(path);
  if (!bytes.ok()) return bytes.status();
  return ReadMeshFromBuffer(*bytes, *format, path);
}

absl::StatusOr<TriangleMesh> ReadMeshFromBuffer(absl::string_view data, FileFormat format,
                                                absl::string_view source) {
  if (data.empty()) return absl::InvalidArgumentError(absl::StrCat(source, ": the file is empty"));
  absl::StatusOr<TriangleMesh> mesh = Parse(data, format, source);
  if (!mesh.ok()) return mesh.status();
  absl::Status status = CheckFinitePoints(mesh->vertices, source, /*is_mesh=*/true);
  if (status.ok()) status = CheckFaceIndices(*mesh, source);
  if (!status.ok()) return status;
  return mesh;
}

absl::StatusOr<std::string> WriteMeshToBuffer(const TriangleMesh& mesh, FileFormat format,
                                              const DracoOptions& draco) {
  constexpr absl::string_view kWhat = "cannot write the mesh";
  absl::Status status = CheckFinitePoints(mesh.vertices, kWhat, /*is_mesh=*/true);
  if (status.ok()) status = CheckFaceIndices(mesh, kWhat);
  if (status.ok()) status = CheckOriginFitsFormat(mesh.origin, format, FileUse::kWriteMesh);
  if (!status.ok()) return status;
  switch (format) {
    case FileFormat::kPly: return EncodePlyMesh(mesh);
    case FileFormat::kObj: return EncodeObjMesh(mesh);
    case FileFormat::kStl: return EncodeStlMesh(mesh);
    case FileFormat::kDrc: {
      absl::StatusOr<DracoEncoding> encoded = EncodeDracoMesh(mesh, draco);
      if (!encoded.ok()) return encoded.status();
      return std::move(encoded->bytes);
    }
    case FileFormat::kXyz:
    case FileFormat::kPcd:
    case FileFormat::kOff: break;
  }
  return absl::InvalidArgumentError(
      absl::StrCat("meshes cannot be written as ", FormatName(format)));
}

absl::Status WriteMesh(const TriangleMesh& mesh, const std::string& path,
                       const DracoOptions& draco) {
  absl::StatusOr<FileFormat> format = FormatFromPath(path, FileUse::kWriteMesh);
  if (!format.ok()) return format.status();
  absl::StatusOr<std::string> bytes = WriteMeshToBuffer(mesh, *format, draco);
  if (!bytes.ok()) return PrefixStatus(path, bytes.status());
  return WriteFileBytes(path, *bytes);
}

}  // namespace membrane
