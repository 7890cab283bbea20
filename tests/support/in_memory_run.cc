#include "tests/support/in_memory_run.h"

#include "core/pipeline/in_memory_ends.h"
#include "core/pipeline/reconstruction_pipeline.h"

namespace membrane::testing {

absl::StatusOr<ReconstructionReport> ReconstructInMemory(const PointCloud& cloud,
                                                         const ReconstructionOptions& options) {
  InMemoryCloudSource source(cloud);
  NoResourceLimit gate;
  InMemoryMeshSink sink;
  NullReconstructionObserver observer;
  return RunReconstruction(options, {source, gate, sink, observer}, ErrorContext{},
                           CancelToken::Never());
}

}  // namespace membrane::testing
