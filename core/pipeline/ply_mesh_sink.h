// A mesh encoded as a binary PLY file in memory: membraned's result for clients that ask for
// PLY (Parameters.mesh_format), which need no Draco decoder to read it.
#ifndef MEMBRANE_CORE_PIPELINE_PLY_MESH_SINK_H_
#define MEMBRANE_CORE_PIPELINE_PLY_MESH_SINK_H_

#include <string>
#include <utility>

#include "core/pipeline/mesh_sink.h"

namespace membrane {

class PlyMeshSink : public MeshSink {
 public:
  // EncodePlyMesh of `mesh`: float32 positions (double positions plus the origin when the
  // mesh has one), whatever `grid` (lossless runs pass float32's). Never fails.
  absl::Status Write(const TriangleMesh& mesh, const PositionGrid& grid) override;

  // The encoding written last (empty before any), moved out.
  std::string TakeBytes() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_PLY_MESH_SINK_H_
