#include "client/mesh_file_sink.h"

#include "absl/strings/str_cat.h"
#include "client/cloud_origin.h"
#include "client/output_files.h"
#include "client/std_streams.h"
#include "core/io/draco_codec.h"
#include "core/io/mesh_io.h"

namespace membrane::client {

absl::Status MeshFileSink::CheckOrigin(const Origin3d& origin) {
  return CheckOutputKeepsOrigin(origin, format_, OutputName(path_));
}

absl::Status MeshFileSink::Write(const TriangleMesh& mesh, const PositionGrid& grid) {
  const DracoOptions draco = DracoOptionsOnGrid(grid, compression_level_);
  if (!IsStdStream(path_)) return WriteOutputMesh(mesh, path_, format_, draco);
  absl::StatusOr<std::string> bytes = WriteMeshToBuffer(mesh, format_, draco);
  if (!bytes.ok()) {
    return absl::Status(bytes.status().code(),
                        absl::StrCat(OutputName(path_), ": ", bytes.status().message()));
  }
  kept_ = *std::move(bytes);
  return absl::OkStatus();
}

absl::Status MeshFileSink::Flush() {
  if (kept_.empty()) return absl::OkStatus();
  absl::Status written = WriteOutputBytes(path_, kept_);
  kept_.clear();
  return written;
}

}  // namespace membrane::client
