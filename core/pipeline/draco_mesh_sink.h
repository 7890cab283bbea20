// A mesh encoded with Draco into memory, its positions stored exactly on the grid they were
// built on: membraned's result, the benchmark's .drc file.
#ifndef MEMBRANE_CORE_PIPELINE_DRACO_MESH_SINK_H_
#define MEMBRANE_CORE_PIPELINE_DRACO_MESH_SINK_H_

#include <string>

#include "core/pipeline/mesh_sink.h"

namespace membrane {

class DracoMeshSink : public MeshSink {
 public:
  // `compression_level`: Draco's, 0..10 (DracoOptions).
  explicit DracoMeshSink(int compression_level) : compression_level_(compression_level) {}

  // EncodeDracoMesh on DracoOptionsOnGrid(grid, compression_level); its errors as they are
  // (InvalidArgument for an invalid level or mesh, Internal when Draco fails).
  absl::Status Write(const TriangleMesh& mesh, const PositionGrid& grid) override;

  // The encoding written last (empty before any), moved out.
  std::string TakeBytes() { return std::move(bytes_); }

 private:
  int compression_level_;
  std::string bytes_;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_DRACO_MESH_SINK_H_
