#include "core/pipeline/draco_mesh_sink.h"

#include <utility>

#include "absl/status/statusor.h"
#include "core/io/draco_codec.h"

namespace membrane {

absl::Status DracoMeshSink::Write(const TriangleMesh& mesh, const PositionGrid& grid) {
  absl::StatusOr<DracoEncoding> encoded =
      EncodeDracoMesh(mesh, DracoOptionsOnGrid(grid, compression_level_));
  if (!encoded.ok()) return encoded.status();
  bytes_ = std::move(encoded->bytes);
  return absl::OkStatus();
}

}  // namespace membrane
