#include "client/input_files.h"

#include <utility>

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
// Its time grows with the file too: the 6.9 MB .drc of a 10M-point cloud's mesh (15.3M faces)
// decodes in about 3 CPU s, and took over 30 s of wall on a machine shared five ways. A hostile
// file of a few bytes still gets only the base.
constexpr double kDecoderSeconds = 30;
constexpr double kDecoderSecondsPerMiB = 10;

}  // namespace

DecodeLimits DecoderLimits(const std::string& bytes, const std::string& path) {
  DecodeLimits limits;
  limits.helper = {"/proc/self/exe", kDecodeHelperFlag};
  limits.timeout_seconds =
      kDecoderSeconds + kDecoderSecondsPerMiB * static_cast<double>(bytes.size()) / (1 << 20);
  limits.memory_bytes =
      kDecoderBaseBytes + kDecoderBytesPerFileByte * static_cast<int64_t>(bytes.size());
  limits.max_points = INT64_MAX;
  limits.subject = path;
  return limits;
}

namespace {

// A cloud read with its points that are not finite dropped (`count` of them), refused
// instead when `invalid` says so, naming the flag that drops them.
absl::StatusOr<PointCloud> WithInvalidPoints(absl::StatusOr<PointCloud> cloud, size_t count,
                                             const std::string& path, InvalidPoints invalid,
                                             size_t* dropped) {
  if (!cloud.ok()) return cloud;
  if (count > 0 && invalid == InvalidPoints::kRefuse) return InvalidPointsError(path, count);
  if (dropped != nullptr) *dropped = count;
  return cloud;
}

// ReadPointCloudFromBuffer, with the refusal of points that are not finite naming the flag
// that drops them.
absl::StatusOr<PointCloud> ReadCloudBuffer(const std::string& bytes, FileFormat format,
                                           const std::string& path, InvalidPoints invalid,
                                           size_t* dropped) {
  size_t count = 0;
  absl::StatusOr<PointCloud> cloud =
      ReadPointCloudFromBuffer(bytes, format, path, InvalidPoints::kDrop, &count);
  return WithInvalidPoints(std::move(cloud), count, path, invalid, dropped);
}

}  // namespace

absl::Status InvalidPointsError(absl::string_view name, size_t count) {
  return absl::InvalidArgumentError(
      absl::StrCat(name, ": ", count, count == 1 ? " point has" : " points have",
                   " NaN or infinite coordinates (how organized scans mark pixels without a "
                   "return); --drop-invalid leaves them out"));
}

std::string DroppedPointsNote(size_t count) {
  return absl::StrCat(count, count == 1 ? " point" : " points",
                      " with NaN or infinite coordinates left out by --drop-invalid");
}

absl::StatusOr<PointCloud> ReadInputCloud(const std::string& path, absl::string_view format_flag,
                                          const CancelToken& cancel, InvalidPoints invalid,
                                          size_t* dropped, ProgressRange progress) {
  // A file's name is checked before it is read: a wrong extension fails at once.
  if (!IsStdStream(path)) {
    absl::StatusOr<FileFormat> format = InputFormat(path, format_flag, FileUse::kReadPointCloud);
    if (!format.ok()) return format.status();
    // Draco goes to a decoder process as bytes; the rest is read here, a binary PLY in pieces
    // (ReadPointCloudFile), so that a large scan's file and its points are not both held.
    if (*format != FileFormat::kDrc) {
      if (dropped != nullptr) *dropped = 0;
      size_t count = 0;
      absl::StatusOr<PointCloud> cloud =
          ReadPointCloudFile(path, *format, InputName(path), InvalidPoints::kDrop, &count);
      return WithInvalidPoints(std::move(cloud), count, InputName(path), invalid, dropped);
    }
  }
  absl::StatusOr<std::string> bytes = ReadInputBytes(path);
  if (!bytes.ok()) return bytes.status();
  absl::StatusOr<FileFormat> format =
      InputFormat(path, format_flag, FileUse::kReadPointCloud, *bytes);
  if (!format.ok()) return format.status();
  return ParseInputCloud(*bytes, *format, InputName(path), cancel, invalid, dropped, progress);
}

absl::StatusOr<PointCloud> ParseInputCloud(const std::string& bytes, FileFormat format,
                                           const std::string& path, const CancelToken& cancel,
                                           InvalidPoints invalid, size_t* dropped,
                                           ProgressRange progress) {
  if (dropped != nullptr) *dropped = 0;
  if (format != FileFormat::kDrc || bytes.empty()) {
    return ReadCloudBuffer(bytes, format, path, invalid, dropped);
  }
  DecodeLimits limits = DecoderLimits(bytes, path);
  limits.accept_mesh = true;  // as ReadPointCloud: a mesh's vertices
  absl::StatusOr<PointCloud> cloud = DecodeInSubprocess(bytes, limits, cancel, progress);
  // No child (no /proc, out of processes): the checks in front of Draco still stand.
  if (cloud.status().code() == absl::StatusCode::kInternal) {
    return ReadCloudBuffer(bytes, format, path, invalid, dropped);
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
