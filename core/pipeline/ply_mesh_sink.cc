#include "core/pipeline/ply_mesh_sink.h"

#include "core/io/ply_writer.h"

namespace membrane {

absl::Status PlyMeshSink::Write(const TriangleMesh& mesh, const PositionGrid& /*grid*/) {
  bytes_ = EncodePlyMesh(mesh);
  return absl::OkStatus();
}

}  // namespace membrane
