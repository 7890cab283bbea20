#include "core/io/point_cloud_io.h"

#include <optional>
#include <utility>

#include "absl/strings/str_cat.h"
#include "core/io/coordinate_shift.h"
#include "core/io/file_bytes.h"
#include "core/io/geometry_checks.h"
#include "core/io/obj_reader.h"
#include "core/io/obj_writer.h"
#include "core/io/off_reader.h"
#include "core/io/parse_error.h"
#include "core/io/pcd_reader.h"
#include "core/io/ply_reader.h"
#include "core/io/ply_stream.h"
#include "core/io/ply_writer.h"
#include "core/io/xyz_reader.h"
#include "core/io/xyz_writer.h"

namespace membrane {
namespace {

absl::StatusOr<PointCloud> Parse(absl::string_view data, FileFormat format,
                                 absl::string_view source) {
  switch (format) {
    case FileFormat::kPly: return ReadPlyPointCloud(data, source);
    case FileFormat::kObj: return ReadObjPointCloud(data, source);
    case FileFormat::kXyz: return ReadXyzPointCloud(data, source);
    case FileFormat::kPcd: return ReadPcdPointCloud(data, source);
    case FileFormat::kDrc: {
      absl::StatusOr<DecodedDracoCloud> decoded = DecodeDracoPointCloud(data);
      if (!decoded.ok()) return PrefixStatus(source, decoded.status());
      return std::move(decoded->cloud);
    }
    case FileFormat::kOff: return ReadOffPointCloud(data, source);
    case FileFormat::kStl: break;
  }
  return absl::InvalidArgumentError(
      absl::StrCat(source, ": point clouds cannot be read from ", FormatName(format), " files"));
}

// `cloud` with its points that are not finite refused or dropped as `invalid` says.
absl::StatusOr<PointCloud> CheckedPoints(PointCloud cloud, absl::string_view source,
                                         InvalidPoints invalid, size_t* dropped) {
  if (dropped != nullptr) *dropped = 0;
  if (invalid == InvalidPoints::kDrop) {
    const size_t count = DropNonFinitePoints(&cloud.points);
    if (dropped != nullptr) *dropped = count;
    return cloud;
  }
  absl::Status finite = CheckFinitePoints(cloud.points, source);
  if (!finite.ok()) return finite;
  return cloud;
}

}  // namespace

absl::StatusOr<PointCloud> ReadPointCloud(const std::string& path, InvalidPoints invalid,
                                          size_t* dropped) {
  absl::StatusOr<FileFormat> format = FormatFromPath(path, FileUse::kReadPointCloud);
  if (!format.ok()) return format.status();
  return ReadPointCloudFile(path, *format, path, invalid, dropped);
}

absl::StatusOr<PointCloud> ReadPointCloudFile(const std::string& path, FileFormat format,
                                              absl::string_view source, InvalidPoints invalid,
                                              size_t* dropped) {
  if (format == FileFormat::kPly) {
    if (std::optional<PointCloud> streamed = StreamPlyPointCloud(path)) {
      return CheckedPoints(*std::move(streamed), source, invalid, dropped);
    }
  }
  absl::StatusOr<std::string> bytes = ReadFileBytes(path);
  if (!bytes.ok()) return bytes.status();
  return ReadPointCloudFromBuffer(*bytes, format, source, invalid, dropped);
}

absl::StatusOr<PointCloud> ReadPointCloudFromBuffer(absl::string_view data, FileFormat format,
                                                    absl::string_view source,
                                                    InvalidPoints invalid, size_t* dropped) {
  if (dropped != nullptr) *dropped = 0;
  if (data.empty()) return absl::InvalidArgumentError(absl::StrCat(source, ": the file is empty"));
  absl::StatusOr<PointCloud> cloud = Parse(data, format, source);
  if (!cloud.ok()) return cloud.status();
  return CheckedPoints(*std::move(cloud), source, invalid, dropped);
}

absl::StatusOr<std::string> WritePointCloudToBuffer(const PointCloud& cloud, FileFormat format,
                                                    const DracoOptions& draco) {
  absl::Status status = CheckFinitePoints(cloud.points, "cannot write the point cloud");
  if (status.ok()) status = CheckOriginFitsFormat(cloud.origin, format, FileUse::kWritePointCloud);
  if (!status.ok()) return status;
  switch (format) {
    case FileFormat::kPly: return EncodePlyPointCloud(cloud);
    case FileFormat::kXyz: return EncodeXyzPointCloud(cloud);
    case FileFormat::kObj: return EncodeObjPointCloud(cloud);
    case FileFormat::kDrc: {
      absl::StatusOr<DracoEncoding> encoded = EncodeDracoPointCloud(cloud, draco);
      if (!encoded.ok()) return encoded.status();
      return std::move(encoded->bytes);
    }
    case FileFormat::kPcd:
    case FileFormat::kStl:
    case FileFormat::kOff: break;
  }
  return absl::InvalidArgumentError(
      absl::StrCat("point clouds cannot be written as ", FormatName(format)));
}

absl::Status WritePointCloud(const PointCloud& cloud, const std::string& path,
                             const DracoOptions& draco) {
  absl::StatusOr<FileFormat> format = FormatFromPath(path, FileUse::kWritePointCloud);
  if (!format.ok()) return format.status();
  absl::StatusOr<std::string> bytes = WritePointCloudToBuffer(cloud, *format, draco);
  if (!bytes.ok()) return PrefixStatus(path, bytes.status());
  return WriteFileBytes(path, *bytes);
}

}  // namespace membrane
