#include "client/output_files.h"

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "client/std_streams.h"
#include "core/io/mesh_io.h"
#include "core/io/point_cloud_io.h"

namespace membrane::client {
namespace {

absl::Status WriteEncoded(const absl::StatusOr<std::string>& bytes, const std::string& path) {
  if (!bytes.ok()) {
    return absl::Status(bytes.status().code(),
                        absl::StrCat(OutputName(path), ": ", bytes.status().message()));
  }
  return WriteOutputBytes(path, *bytes);
}

}  // namespace

std::string OutputName(const std::string& path) { return IsStdStream(path) ? "stdout" : path; }

absl::Status WriteOutputMesh(const TriangleMesh& mesh, const std::string& path,
                             FileFormat format, const DracoOptions& draco) {
  return WriteEncoded(WriteMeshToBuffer(mesh, format, draco), path);
}

absl::Status WriteOutputCloud(const PointCloud& cloud, const std::string& path,
                              FileFormat format, const DracoOptions& draco) {
  return WriteEncoded(WritePointCloudToBuffer(cloud, format, draco), path);
}

}  // namespace membrane::client
