// Writing the meshes and clouds the commands produce, to a file or to standard output ("-"),
// in a format given rather than read off the name (--output-format, OutputFormat).
#ifndef MEMBRANE_CLIENT_OUTPUT_FILES_H_
#define MEMBRANE_CLIENT_OUTPUT_FILES_H_

#include <string>

#include "absl/status/status.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"
#include "core/io/draco_codec.h"
#include "core/io/file_format.h"

namespace membrane::client {

// The name of output `path` in messages: "stdout" for "-", else the path.
std::string OutputName(const std::string& path);

// `mesh` encoded as `format` (WriteMeshToBuffer with `draco`) into `path` (WriteOutputBytes:
// a file, or standard output for "-"). InvalidArgument "NAME: ..." (OutputName) for what the
// encoder refuses and for a write that fails; Internal when the Draco encoder fails.
absl::Status WriteOutputMesh(const TriangleMesh& mesh, const std::string& path,
                             FileFormat format, const DracoOptions& draco = {});

// The same for a point cloud (WritePointCloudToBuffer).
absl::Status WriteOutputCloud(const PointCloud& cloud, const std::string& path,
                              FileFormat format, const DracoOptions& draco = {});

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_OUTPUT_FILES_H_
