// A run from memory to memory: the cloud the caller holds in, the mesh kept for it out. For
// tests and tools that build their cloud or study the mesh themselves.
#ifndef MEMBRANE_CORE_PIPELINE_IN_MEMORY_ENDS_H_
#define MEMBRANE_CORE_PIPELINE_IN_MEMORY_ENDS_H_

#include <optional>
#include <utility>

#include "core/pipeline/cloud_source.h"
#include "core/pipeline/mesh_sink.h"

namespace membrane {

// Hands `cloud` over to the run that reads it. A second Read is FailedPrecondition: the cloud
// has been given away.
class InMemoryCloudSource : public CloudSource {
 public:
  explicit InMemoryCloudSource(PointCloud cloud) : cloud_(std::move(cloud)) {}
  absl::StatusOr<PointCloud> Read(const CancelToken& cancel, ProgressRange progress) override;

 private:
  std::optional<PointCloud> cloud_;
};

// Keeps a copy of the mesh written last and its grid.
class InMemoryMeshSink : public MeshSink {
 public:
  absl::Status Write(const TriangleMesh& mesh, const PositionGrid& grid) override;

  // The last mesh written (empty before any) and the grid its positions lie on.
  const TriangleMesh& mesh() const { return mesh_; }
  const PositionGrid& grid() const { return grid_; }
  // How many times Write was called: 2 when the run fell back to float32.
  int writes() const { return writes_; }

 private:
  TriangleMesh mesh_;
  PositionGrid grid_;
  int writes_ = 0;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_IN_MEMORY_ENDS_H_
