#include "client/mesh_file_sink.h"

#include "client/cloud_origin.h"
#include "client/io_errors.h"
#include "core/io/draco_codec.h"
#include "core/io/mesh_io.h"

namespace membrane::client {

absl::Status MeshFileSink::CheckOrigin(const Origin3d& origin) {
  return CheckOutputKeepsOrigin(origin, path_);
}

absl::Status MeshFileSink::Write(const TriangleMesh& mesh, const PositionGrid& grid) {
  return FileErrorAsInvalidInput(
      WriteMesh(mesh, path_, DracoOptionsOnGrid(grid, compression_level_)));
}

}  // namespace membrane::client
