// A reconstruction of a cloud held in memory, for the pipeline's tests: RunReconstruction with
// the in-memory source and sink, no resource limit and no observer.
#ifndef MEMBRANE_TESTS_SUPPORT_IN_MEMORY_RUN_H_
#define MEMBRANE_TESTS_SUPPORT_IN_MEMORY_RUN_H_

#include "absl/status/statusor.h"
#include "core/geometry/point_cloud.h"
#include "core/pipeline/reconstruction_options.h"
#include "core/pipeline/reconstruction_report.h"

namespace membrane::testing {

// RunReconstruction(options) of `cloud` (InMemoryCloudSource, NoResourceLimit, InMemoryMeshSink,
// NullReconstructionObserver, an empty ErrorContext, never cancelled): its report or error.
absl::StatusOr<ReconstructionReport> ReconstructInMemory(const PointCloud& cloud,
                                                         const ReconstructionOptions& options);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SUPPORT_IN_MEMORY_RUN_H_
