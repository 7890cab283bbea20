#include "core/pipeline/in_memory_ends.h"

#include <utility>

#include "absl/status/status.h"

namespace membrane {

absl::StatusOr<PointCloud> InMemoryCloudSource::Read(const CancelToken& /*cancel*/,
                                                     ProgressRange /*progress*/) {
  if (!cloud_.has_value()) {
    return absl::FailedPreconditionError("the cloud in memory was read already");
  }
  PointCloud cloud = *std::move(cloud_);
  cloud_.reset();
  return cloud;
}

absl::Status InMemoryMeshSink::Write(const TriangleMesh& mesh, const PositionGrid& grid) {
  mesh_ = mesh;
  grid_ = grid;
  ++writes_;
  return absl::OkStatus();
}

}  // namespace membrane
