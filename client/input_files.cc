#include "client/input_files.h"

#include "absl/strings/str_cat.h"
#include "client/format_flags.h"
#include "client/std_streams.h"
#include "core/io/decode_subprocess.h"
#include "core/io/file_format.h"
#include "core/io/mesh_io.h"
#include "core/io/point_cloud_io.h"

namespace membrane::client {
namespace {

// The decoder's address space: 1 GiB holds the executable, its libraries and any real cloud
// of a few million points; the rest grows with the file (a lossless cloud decodes to about as
// many bytes as it has).
constexpr int64_t kDecoderBaseBytes = int64_t{1} << 30;
constexpr int64_t kDecoderBytesPerFileByte = 32;
constexpr double kDecoderSeconds = 30;

// The limits of a child decoding `bytes`, named `path` in its messages.
DecodeLimits DecoderLimits(const std::string& bytes, const std::string& path) {
  DecodeLimits limits;
  limits.helper = {"/proc/self/exe", kDecodeHelperFlag};
  limits.timeout_seconds = kDecoderSeconds;
  limits.memory_bytes =
      kDecoderBaseBytes + kDecoderBytesPerFileByte * static_cast<int64_t>(bytes.size());
  limits.max_points = INT64_MAX;
  limits.subject = path;
  return limits;
}

}  // namespace

absl::StatusOr<PointCloud> ReadInputCloud(const std::string& path, absl::string_view format_flag,
                                          const CancelToken& cancel) {
  // A file's name is checked before it is read: a wrong extension fails at once.
  if (!IsStdStream(path)) {
    if (absl::Status s = InputFormat(path, format_flag, FileUse::kReadPointCloud).status();
        !s.ok()) {
      return s;
    }
  }
  absl::StatusOr<std::string> bytes = ReadInputBytes(path);
  if (!bytes.ok()) return bytes.status();
  absl::StatusOr<FileFormat> format =
      InputFormat(path, format_flag, FileUse::kReadPointCloud, *bytes);
  if (!format.ok()) return format.status();
  return ParseInputCloud(*bytes, *format, InputName(path), cancel);
}

absl::StatusOr<PointCloud> ParseInputCloud(const std::string& bytes, FileFormat format,
                                           const std::string& path, const CancelToken& cancel) {
  if (format != FileFormat::kDrc || bytes.empty()) {
    return ReadPointCloudFromBuffer(bytes, format, path);
  }
  DecodeLimits limits = DecoderLimits(bytes, path);
  limits.accept_mesh = true;  // as ReadPointCloud: a mesh's vertices
  absl::StatusOr<PointCloud> cloud = DecodeInSubprocess(bytes, limits, cancel);
  // No child (no /proc, out of processes): the checks in front of Draco still stand.
  if (cloud.status().code() == absl::StatusCode::kInternal) {
    return ReadPointCloudFromBuffer(bytes, format, path);
  }
  return cloud;
}

absl::StatusOr<TriangleMesh> ReadInputMesh(const std::string& path, absl::string_view format_flag,
                                           const CancelToken& cancel) {
  if (!IsStdStream(path)) {
    if (absl::Status s = InputFormat(path, format_flag, FileUse::kReadMesh).status(); !s.ok()) {
      return s;
    }
  }
  absl::StatusOr<std::string> bytes = ReadInputBytes(path);
  if (!bytes.ok()) return bytes.status();
  absl::StatusOr<FileFormat> format = InputFormat(path, format_flag, FileUse::kReadMesh, *bytes);
  if (!format.ok()) return format.status();
  return ParseInputMesh(*bytes, *format, InputName(path), cancel);
}

std::string InputName(const std::string& path) { return IsStdStream(path) ? "stdin" : path; }

absl::StatusOr<TriangleMesh> ParseInputMesh(const std::string& bytes, FileFormat format,
                                            const std::string& path, const CancelToken& cancel) {
  if (format != FileFormat::kDrc || bytes.empty()) return ReadMeshFromBuffer(bytes, format, path);
  absl::StatusOr<TriangleMesh> mesh =
      DecodeMeshInSubprocess(bytes, DecoderLimits(bytes, path), cancel);
  if (mesh.status().code() == absl::StatusCode::kInternal) {
    return ReadMeshFromBuffer(bytes, format, path);
  }
  return mesh;
}

}  // namespace membrane::client
